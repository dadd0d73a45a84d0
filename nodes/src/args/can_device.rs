//! Which real device is on a CAN bus and how it is set up: the options of
//! `shroud node can` and of the emulators that must agree with it
//! (`shroud sensor-sim --device ars408 ...`).

use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use shroud_core::ingest::ars408::{Ars408Config, Ars408Driver, RadarOutput, RadarSettings};
use shroud_core::ingest::assembly::MountPose;
use shroud_core::ingest::benewake_can::{
    BenewakeCanConfig, BenewakeCanDriver, BenewakeCanModel, RangefinderConfig,
};
use shroud_core::ingest::can_device::CanDeviceDriver;
use shroud_core::ingest::dbc::{builtin, CanDatabase, MAX_DBC_BYTES};
use std::path::PathBuf;

/// The device on the bus.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CanDeviceKind {
    /// shroud's own CAN scan protocol (`PROTOCOLS.md` §2).
    Shroud,
    /// Continental ARS408-21 radar.
    Ars408,
    /// Benewake TF03-CAN rangefinders.
    Tf03,
    /// Benewake TFmini-i-CAN rangefinders.
    TfminiI,
    /// Benewake TF02-i-CAN rangefinders.
    Tf02I,
    /// Benewake TF02 (legacy CAN, extended id) rangefinders.
    Tf02,
}

impl CanDeviceKind {
    fn benewake_model(self) -> Option<BenewakeCanModel> {
        Some(match self {
            Self::Tf03 => BenewakeCanModel::Tf03,
            Self::TfminiI => BenewakeCanModel::TfminiI,
            Self::Tf02I => BenewakeCanModel::Tf02I,
            Self::Tf02 => BenewakeCanModel::Tf02,
            Self::Shroud | Self::Ars408 => return None,
        })
    }
}

/// What the radar outputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RadarOutputArg {
    /// The cluster list (0x600, 0x701, 0x702): raw detections.
    Clusters,
    /// The object list (0x60A to 0x60D): tracked objects.
    Objects,
}

/// `--device` and the settings of the real CAN devices.
#[derive(Debug, Clone, Args)]
pub struct CanDeviceArgs {
    /// The device on the bus.
    #[arg(long, value_enum, default_value_t = CanDeviceKind::Shroud)]
    pub device: CanDeviceKind,
    /// Read the device's signals from this DBC file instead of the one shroud
    /// ships (a firmware variant); it must name the same messages and signals.
    #[arg(long)]
    pub dbc: Option<PathBuf>,
    /// ARS408: the radar's sensor ID (0..=7); its CAN ids are moved by 0x10 per unit.
    #[arg(long, default_value_t = 0)]
    pub sensor_id: u8,
    /// ARS408: the list to read.
    #[arg(long, value_enum, default_value_t = RadarOutputArg::Clusters)]
    pub radar_output: RadarOutputArg,
    /// ARS408: the maximum distance to configure, metres (196..=1200 in 2 m steps).
    #[arg(long)]
    pub radar_max_distance: Option<u32>,
    /// ARS408: send the quality messages (0x702 / 0x60C) too.
    #[arg(long, default_value_t = true, action = clap::ArgAction::Set)]
    pub radar_quality: bool,
    /// ARS408: send the objects' extended messages (0x60D).
    #[arg(long, default_value_t = false, action = clap::ArgAction::Set)]
    pub radar_ext_info: bool,
    /// ARS408: do not configure the radar on start (read what it sends).
    #[arg(long)]
    pub no_configure: bool,
    /// ARS408: the radar's pose in the robot's frame: x,y,z (m),
    /// roll,pitch,yaw (degrees).
    #[arg(long, default_value = "0,0,0,0,0,0", allow_hyphen_values = true)]
    pub mount: String,
    /// Benewake: one rangefinder on the bus, `NAME@ID:x,y,z,roll,pitch,yaw`
    /// (its CAN id as the device sends it, hex with 0x or decimal; its pose in
    /// the robot's frame, m and degrees). Repeat for several; without any,
    /// one at the model's default id at the origin.
    #[arg(long = "rangefinder", allow_hyphen_values = true)]
    pub rangefinders: Vec<String>,
    /// A device silent for this long (seconds) is reported as recovering.
    #[arg(long, default_value_t = 1.0)]
    pub silence_timeout: f64,
}

impl Default for CanDeviceArgs {
    fn default() -> Self {
        Self {
            device: CanDeviceKind::Shroud,
            dbc: None,
            sensor_id: 0,
            radar_output: RadarOutputArg::Clusters,
            radar_max_distance: None,
            radar_quality: true,
            radar_ext_info: false,
            no_configure: false,
            mount: "0,0,0,0,0,0".into(),
            rangefinders: Vec::new(),
            silence_timeout: 1.0,
        }
    }
}

/// One `--rangefinder NAME@ID:POSE`.
#[derive(Debug, Clone, PartialEq)]
pub struct RangefinderArg {
    pub name: String,
    pub id: u32,
    pub mount: MountPose,
}

impl std::str::FromStr for RangefinderArg {
    type Err = anyhow::Error;

    fn from_str(text: &str) -> Result<Self> {
        let usage = || format!("--rangefinder {text:?}: expected NAME@ID:x,y,z,roll,pitch,yaw");
        let (name, rest) = text.split_once('@').with_context(usage)?;
        let (id, pose) = rest.split_once(':').with_context(usage)?;
        if name.is_empty() {
            bail!("{}: empty name", usage());
        }
        Ok(Self {
            name: name.to_owned(),
            id: parse_can_id(id).with_context(usage)?,
            mount: pose.parse().with_context(usage)?,
        })
    }
}

/// A CAN id: hex with `0x`, or decimal.
pub fn parse_can_id(text: &str) -> Result<u32> {
    let parsed = match text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        Some(hex) => u32::from_str_radix(hex, 16),
        None => text.parse(),
    };
    parsed.with_context(|| format!("bad CAN id {text:?}"))
}

impl CanDeviceArgs {
    /// Whether a real device (not shroud's protocol) is on the bus.
    pub fn is_real_device(&self) -> bool {
        self.device != CanDeviceKind::Shroud
    }

    /// The driver these options describe (never for `--device shroud`).
    pub fn driver(&self) -> Result<Box<dyn CanDeviceDriver>> {
        if !(self.silence_timeout.is_finite() && self.silence_timeout > 0.0) {
            bail!("--silence-timeout must be a positive number of seconds");
        }
        let silence_timeout_ns = (self.silence_timeout * 1e9) as u64;
        if let Some(model) = self.device.benewake_model() {
            return self.benewake(model, silence_timeout_ns);
        }
        if self.device != CanDeviceKind::Ars408 {
            bail!("--device shroud has no device driver");
        }
        if !self.rangefinders.is_empty() {
            bail!("--rangefinder applies to Benewake devices, not the ARS408");
        }
        let settings = (!self.no_configure).then_some(RadarSettings {
            max_distance_m: self.radar_max_distance,
            send_quality: Some(self.radar_quality),
            send_ext_info: Some(self.radar_ext_info),
            ..RadarSettings::default()
        });
        let config = Ars408Config {
            sensor_id: self.sensor_id,
            output: match self.radar_output {
                RadarOutputArg::Clusters => RadarOutput::Clusters,
                RadarOutputArg::Objects => RadarOutput::Objects,
            },
            settings,
            mount: self.mount.parse().context("--mount")?,
            silence_timeout_ns,
        };
        let database = self.database("ars408")?;
        Ok(Box::new(Ars408Driver::new(config, database)?))
    }

    fn benewake(
        &self,
        model: BenewakeCanModel,
        silence_timeout_ns: u64,
    ) -> Result<Box<dyn CanDeviceDriver>> {
        if self.mount != "0,0,0,0,0,0" {
            bail!("--mount is the radar's: give each rangefinder's pose in --rangefinder NAME@ID:POSE");
        }
        let parsed: Vec<RangefinderArg> = self
            .rangefinders
            .iter()
            .map(|r| r.parse())
            .collect::<Result<_>>()?;
        if self.dbc.is_some() {
            bail!("--dbc applies to the ARS408; the Benewake layouts are fixed by their manuals");
        }
        let (_, extended) = model.default_id();
        let sensors = if parsed.is_empty() {
            vec![RangefinderConfig::new(
                "rangefinder",
                model,
                MountPose::default(),
            )]
        } else {
            parsed
                .into_iter()
                .map(|r| RangefinderConfig {
                    name: r.name,
                    model,
                    id: r.id,
                    extended,
                    mount: r.mount,
                })
                .collect()
        };
        let mut config = BenewakeCanConfig::new(sensors);
        config.silence_timeout_ns = silence_timeout_ns;
        Ok(Box::new(BenewakeCanDriver::new(config)?))
    }

    /// `--dbc`, or the builtin file `name`.
    fn database(&self, name: &str) -> Result<CanDatabase> {
        match &self.dbc {
            Some(path) => read_dbc(path),
            None => builtin(name).with_context(|| format!("no builtin DBC {name:?}")),
        }
    }
}

/// Reads and parses a DBC file, naming the file in every error.
pub fn read_dbc(path: &std::path::Path) -> Result<CanDatabase> {
    let size = std::fs::metadata(path)
        .with_context(|| format!("--dbc {}", path.display()))?
        .len();
    if size > MAX_DBC_BYTES as u64 {
        bail!(
            "--dbc {}: {size} bytes, more than the {MAX_DBC_BYTES} a DBC may have",
            path.display()
        );
    }
    let text =
        std::fs::read_to_string(path).with_context(|| format!("--dbc {}", path.display()))?;
    CanDatabase::parse(&text).with_context(|| format!("--dbc {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rangefinders_parse_and_bad_ones_are_named() {
        let r: RangefinderArg = "front@0x003:0.2,0,0.3,0,0,90".parse().unwrap();
        assert_eq!(r.name, "front");
        assert_eq!(r.id, 3);
        assert!((r.mount.translation.x - 0.2).abs() < 1e-12);
        let r: RangefinderArg = "rear@17:-0.2,0,0.3,0,0,180".parse().unwrap();
        assert_eq!(r.id, 17);
        for bad in [
            "front",
            "@3:0,0,0,0,0,0",
            "a@x:0,0,0,0,0,0",
            "a@3",
            "a@3:0,0",
        ] {
            assert!(bad.parse::<RangefinderArg>().is_err(), "{bad}");
        }
    }
}
