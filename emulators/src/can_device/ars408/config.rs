//! The radar's configuration, as 0x200 RadarConfiguration sets it and 0x201
//! RadarState reports it (sensors.md §2.2; Continental's ARS408 DBC).

use shroud_drivers::dbc::DecodedMessage;

/// What the radar sends each cycle (0x201 OutputTypeCfg / 0x200 OutputType).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputType {
    /// 0: no measurement cycles.
    None,
    /// 1: tracked objects (0x60A..0x60D).
    Objects,
    /// 2: raw clusters (0x600, 0x701, 0x702).
    Clusters,
}

impl OutputType {
    pub(crate) fn code(self) -> f64 {
        match self {
            Self::None => 0.0,
            Self::Objects => 1.0,
            Self::Clusters => 2.0,
        }
    }

    fn from_code(code: u64) -> Option<Self> {
        match code {
            0 => Some(Self::None),
            1 => Some(Self::Objects),
            2 => Some(Self::Clusters),
            _ => None,
        }
    }
}

/// The radar's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadarConfig {
    /// Far end of the measurement range, metres (MaxDistanceCfg, 2 m steps).
    pub max_distance_m: f64,
    /// 0..=7: the radar adds 0x10 · sensor_id to every CAN id.
    pub sensor_id: u8,
    pub output: OutputType,
    /// Transmit power: 0 standard, 1 −3 dB, 2 −6 dB, 3 −9 dB.
    pub radar_power: u8,
    /// Send 0x702 / 0x60C quality frames.
    pub send_quality: bool,
    /// Send 0x60D extended object frames.
    pub send_ext_info: bool,
    /// Object order: 0 none, 1 by range, 2 by RCS.
    pub sort_index: u8,
    /// 0 standard, 1 high sensitivity.
    pub rcs_threshold: u8,
    /// The last 0x200 asked to store the configuration (NVMwriteStatus).
    pub stored: bool,
}

impl Default for RadarConfig {
    /// Clusters with quality and extended information, 196 m (the standard
    /// range's maximum distance), sensor 0, full power, sorted by range. The
    /// factory default output of a real unit is objects; the emulator starts
    /// in clusters, the mode shroud's driver reads.
    fn default() -> Self {
        Self {
            max_distance_m: 196.0,
            sensor_id: 0,
            output: OutputType::Clusters,
            radar_power: 0,
            send_quality: true,
            send_ext_info: true,
            sort_index: 1,
            rcs_threshold: 0,
            stored: false,
        }
    }
}

/// The far range's lower limit of a standard-range unit (sensors.md §2.2;
/// a smaller request is raised to it).
const MIN_MAX_DISTANCE_M: f64 = 196.0;
/// The far range's upper limit of a standard-range unit.
const MAX_MAX_DISTANCE_M: f64 = 260.0;

impl RadarConfig {
    /// Applies a decoded 0x200: each field whose `*_valid` bit is set, when its
    /// value is one the radar knows; the rest stay.
    pub(crate) fn apply(&mut self, message: &DecodedMessage<'_>) {
        let valid = |name: &str| message.get(name).is_some_and(|v| v >= 0.5);
        let code = |name: &str| message.get(name).map(|v| v.round().max(0.0) as u64);
        if valid("MaxDistance_valid") {
            if let Some(m) = message.get("MaxDistance") {
                // A standard-range unit clamps the far range to its limits
                // (196..260 m); it reports the clamped value in 0x201.
                if m.is_finite() {
                    self.max_distance_m = m.clamp(MIN_MAX_DISTANCE_M, MAX_MAX_DISTANCE_M);
                }
            }
        }
        if valid("SensorID_valid") {
            if let Some(id) = code("SensorID").filter(|&id| id <= 7) {
                self.sensor_id = id as u8;
            }
        }
        if valid("OutputType_valid") {
            if let Some(output) = code("OutputType").and_then(OutputType::from_code) {
                self.output = output;
            }
        }
        if valid("RadarPower_valid") {
            if let Some(power) = code("RadarPower").filter(|&p| p <= 3) {
                self.radar_power = power as u8;
            }
        }
        if valid("SendQuality_valid") {
            if let Some(flag) = code("SendQuality") {
                self.send_quality = flag == 1;
            }
        }
        if valid("SendExtInfo_valid") {
            if let Some(flag) = code("SendExtInfo") {
                self.send_ext_info = flag == 1;
            }
        }
        if valid("SortIndex_valid") {
            if let Some(sort) = code("SortIndex").filter(|&s| s <= 2) {
                self.sort_index = sort as u8;
            }
        }
        if valid("RCS_Threshold_valid") {
            if let Some(threshold) = code("RCS_Threshold").filter(|&t| t <= 1) {
                self.rcs_threshold = threshold as u8;
            }
        }
        if valid("StoreInNVM_valid") && code("StoreInNVM") == Some(1) {
            self.stored = true;
        }
    }
}
