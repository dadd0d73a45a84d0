//! Which real device is on a CAN bus and how it is set up: the options of
//! `shroud node can` and of the emulators that must agree with it
//! (`shroud sensor-sim --device ars408 ...`).

use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use shroud_drivers::ars408::{Ars408Config, Ars408Driver, RadarOutput, RadarSettings};
use shroud_drivers::assembly::MountPose;
use shroud_drivers::benewake_can::{
    BenewakeCanConfig, BenewakeCanDriver, BenewakeCanModel, RangefinderConfig,
};
use shroud_drivers::can_device::CanDeviceDriver;
use shroud_drivers::dbc::{builtin, CanDatabase, MAX_DBC_BYTES};
use std::path::PathBuf;

/// The device on the bus.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum CanDeviceKind {
    /// shroud's own CAN scan protocol (`docs/sensor-protocols.md` §2).
    #[default]
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

/// `--device` and the settings of the real CAN devices. A setting given for
/// a device it does not apply to is a named error, never ignored.
#[derive(Debug, Clone, Default, Args)]
pub struct CanDeviceArgs {
    /// The device on the bus.
    #[arg(long, value_enum, default_value_t = CanDeviceKind::Shroud)]
    pub device: CanDeviceKind,
    /// ARS408: read the radar's signals from this DBC file instead of the one
    /// shroud ships (a firmware variant); it must name the same messages and
    /// signals.
    #[arg(long)]
    pub dbc: Option<PathBuf>,
    /// ARS408: the radar's sensor ID (0..=7, default 0); its CAN ids are
    /// moved by 0x10 per unit.
    #[arg(long)]
    pub sensor_id: Option<u8>,
    /// ARS408: the list to read (default clusters).
    #[arg(long, value_enum)]
    pub radar_output: Option<RadarOutputArg>,
    /// ARS408: the maximum distance to configure, metres (196..=1200 in 2 m
    /// steps; default: the radar's own).
    #[arg(long)]
    pub radar_max_distance: Option<u32>,
    /// ARS408: configure the quality messages (0x702 / 0x60C) on or off
    /// (default true).
    #[arg(long, action = clap::ArgAction::Set)]
    pub radar_quality: Option<bool>,
    /// ARS408: configure the objects' extended messages (0x60D) on or off
    /// (default false).
    #[arg(long, action = clap::ArgAction::Set)]
    pub radar_ext_info: Option<bool>,
    /// ARS408: do not configure the radar on start (read what it sends).
    #[arg(long)]
    pub no_configure: bool,
    /// ARS408: the radar's pose in the robot's frame: x,y,z (m),
    /// roll,pitch,yaw (degrees); default the origin.
    #[arg(long, allow_hyphen_values = true)]
    pub mount: Option<String>,
    /// Benewake: one rangefinder on the bus, `NAME@ID:x,y,z,roll,pitch,yaw`
    /// (its CAN id as the device sends it, hex with 0x or decimal; its pose in
    /// the robot's frame, m and degrees). Repeat for several; without any,
    /// one at the model's default id at the origin.
    #[arg(long = "rangefinder", allow_hyphen_values = true)]
    pub rangefinders: Vec<String>,
    /// A device silent for this long (seconds, default 1) is reported as
    /// recovering.
    #[arg(long)]
    pub silence_timeout: Option<f64>,
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

    /// The settings given, by flag, for refusing those a device does not read.
    fn given(&self) -> [(&'static str, bool); 10] {
        [
            ("--dbc", self.dbc.is_some()),
            ("--sensor-id", self.sensor_id.is_some()),
            ("--radar-output", self.radar_output.is_some()),
            ("--radar-max-distance", self.radar_max_distance.is_some()),
            ("--radar-quality", self.radar_quality.is_some()),
            ("--radar-ext-info", self.radar_ext_info.is_some()),
            ("--no-configure", self.no_configure),
            ("--mount", self.mount.is_some()),
            ("--rangefinder", !self.rangefinders.is_empty()),
            ("--silence-timeout", self.silence_timeout.is_some()),
        ]
    }

    /// Refuses every given setting that `device` does not read.
    fn refuse_all_but(&self, device: &str, read: &[&str]) -> Result<()> {
        for (flag, given) in self.given() {
            if given && !read.contains(&flag) {
                bail!("{flag} does not apply to --device {device}");
            }
        }
        Ok(())
    }

    /// For `--device shroud`: none of the device settings apply.
    pub fn check_protocol_only(&self) -> Result<()> {
        self.refuse_all_but("shroud (shroud's own protocol)", &[])
    }

    /// The driver these options describe (never for `--device shroud`).
    pub fn driver(&self) -> Result<Box<dyn CanDeviceDriver>> {
        let silence = self.silence_timeout.unwrap_or(1.0);
        if !(silence.is_finite() && silence > 0.0) {
            bail!("--silence-timeout must be a positive number of seconds");
        }
        let silence_timeout_ns = (silence * 1e9) as u64;
        if let Some(model) = self.device.benewake_model() {
            self.refuse_all_but(model.name(), &["--rangefinder", "--silence-timeout"])?;
            return self.benewake(model, silence_timeout_ns);
        }
        if self.device != CanDeviceKind::Ars408 {
            bail!("--device shroud has no device driver");
        }
        let mut read = vec![
            "--dbc",
            "--sensor-id",
            "--radar-output",
            "--mount",
            "--silence-timeout",
            "--no-configure",
        ];
        let device = if self.no_configure {
            "ars408 with --no-configure"
        } else {
            read.extend([
                "--radar-max-distance",
                "--radar-quality",
                "--radar-ext-info",
            ]);
            "ars408"
        };
        self.refuse_all_but(device, &read)?;
        let settings = (!self.no_configure).then_some(RadarSettings {
            max_distance_m: self.radar_max_distance,
            send_quality: Some(self.radar_quality.unwrap_or(true)),
            send_ext_info: Some(self.radar_ext_info.unwrap_or(false)),
            ..RadarSettings::default()
        });
        let config = Ars408Config {
            sensor_id: self.sensor_id.unwrap_or(0),
            output: match self.radar_output.unwrap_or(RadarOutputArg::Clusters) {
                RadarOutputArg::Clusters => RadarOutput::Clusters,
                RadarOutputArg::Objects => RadarOutput::Objects,
            },
            settings,
            mount: match &self.mount {
                Some(pose) => pose.parse().context("--mount")?,
                None => MountPose::default(),
            },
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
        let parsed: Vec<RangefinderArg> = self
            .rangefinders
            .iter()
            .map(|r| r.parse())
            .collect::<Result<_>>()?;
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
