//! What the integrator chooses about one ARS408: its sensor id on the bus,
//! which list it outputs, the radar settings to send, its mount and how long
//! a silence may last.

use super::error::Ars408Error;
use crate::assembly::MountPose;

/// The largest sensor id (3 bits, RadarConfiguration `SensorID`).
pub const MAX_SENSOR_ID: u8 = 7;
/// One second without a radar frame is a silent radar (RadarState alone
/// comes every 50 ms, sensors.md §2.2).
pub const DEFAULT_SILENCE_TIMEOUT_NS: u64 = 1_000_000_000;

/// Which of its two lists the radar sends (RadarConfiguration `OutputType`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum RadarOutput {
    /// Raw detections, one cycle = `Cluster_0_Status` + generals (+ quality).
    #[default]
    Clusters,
    /// Tracked objects, one cycle = `Obj_0_Status` + generals (+ quality, +
    /// extended).
    Objects,
}

impl RadarOutput {
    /// The `OutputType` / `OutputTypeCfg` code: 1 objects, 2 clusters.
    pub fn code(self) -> u32 {
        match self {
            Self::Objects => 1,
            Self::Clusters => 2,
        }
    }

    /// `clusters` or `objects`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Clusters => "clusters",
            Self::Objects => "objects",
        }
    }
}

/// The RadarConfiguration (0x200) fields to set; `None` leaves the radar's
/// value alone (its `*_valid` bit stays 0). The output type is always set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RadarSettings {
    /// Far-scan range in metres, 2 m steps (`MaxDistance`, 10 bits x 2 m):
    /// an even number in 196..=1200, the radar's own limits (196..260 m in
    /// standard range, up to 1200 m in extended range). A radar that clamps
    /// it further does not confirm it (counted `config_not_confirmed`, its
    /// health says what it reports instead).
    pub max_distance_m: Option<u32>,
    /// Send the quality frames (0x702 / 0x60C).
    pub send_quality: Option<bool>,
    /// Send the extended object frames (0x60D).
    pub send_ext_info: Option<bool>,
    /// Transmit power code 0..=3 (0 standard, 1 -3 dB, 2 -6 dB, 3 -9 dB).
    pub radar_power: Option<u8>,
    /// Object sort order code 0..=2 (0 none, 1 by range, 2 by RCS).
    pub sort_index: Option<u8>,
    /// `RCS_Threshold`: true = high sensitivity (code 1), false = standard (0).
    pub rcs_threshold_high: Option<bool>,
}

/// How to run one ARS408.
#[derive(Debug, Clone, PartialEq)]
pub struct Ars408Config {
    /// 0..=7: every id the radar uses is its base id + 0x10 * `sensor_id`.
    pub sensor_id: u8,
    pub output: RadarOutput,
    /// Settings to send on connect (only on a writable bus); `None` reads the
    /// radar as it is.
    pub settings: Option<RadarSettings>,
    /// The radar's pose in the robot's frame (its x forward, y left).
    pub mount: MountPose,
    /// No radar frame for this long makes the driver `Recovering`.
    pub silence_timeout_ns: u64,
}

impl Default for Ars408Config {
    fn default() -> Self {
        Self {
            sensor_id: 0,
            output: RadarOutput::Clusters,
            settings: None,
            mount: MountPose::default(),
            silence_timeout_ns: DEFAULT_SILENCE_TIMEOUT_NS,
        }
    }
}

impl Ars408Config {
    /// Checks every value against what the radar accepts; the error names
    /// the setting and why.
    pub fn validate(&self) -> Result<(), Ars408Error> {
        if self.sensor_id > MAX_SENSOR_ID {
            return Err(bad(
                "sensor_id",
                format!("{} is not in 0..={MAX_SENSOR_ID}", self.sensor_id),
            ));
        }
        if self.silence_timeout_ns == 0 {
            return Err(bad("silence_timeout", "must be more than 0".into()));
        }
        let finite = self.mount.translation.is_finite() && self.mount.rotation.is_finite();
        if !finite {
            return Err(bad("mount", "has a non-finite value".into()));
        }
        let Some(settings) = &self.settings else {
            return Ok(());
        };
        if let Some(m) = settings.max_distance_m {
            if !(196..=1200).contains(&m) || m % 2 != 0 {
                return Err(bad(
                    "max_distance_m",
                    format!("{m} m is not an even number of metres in 196..=1200"),
                ));
            }
        }
        if let Some(p) = settings.radar_power {
            if p > 3 {
                return Err(bad("radar_power", format!("code {p} is not in 0..=3")));
            }
        }
        if let Some(s) = settings.sort_index {
            if s > 2 {
                return Err(bad("sort_index", format!("code {s} is not in 0..=2")));
            }
        }
        Ok(())
    }
}

fn bad(name: &'static str, reason: String) -> Ars408Error {
    Ars408Error::BadSetting { name, reason }
}
