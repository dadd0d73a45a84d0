//! Which range sensor `shroud node serial` reads and how: the device kind,
//! the port's rate, and each kind's own settings, turned into the `shroud-drivers`
//! driver configurations.

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use shroud_drivers::benewake::{BenewakeConfig, BenewakeDriver, BenewakeModel, DistanceUnit};
use shroud_drivers::device::DeviceDriver;
use shroud_drivers::rplidar::{MotorControl, RplidarConfig, RplidarDriver, ScanMode};
use shroud_drivers::scip::{Link, ScanCommand, ScipConfig, ScipDriver};
use std::time::Duration;

/// The protocol the device on the port speaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DeviceKind {
    /// shroud's own framed protocol (docs/sensor-protocols.md §1): 3D scans.
    Shroud,
    /// A Hokuyo SCIP 2.0 lidar (URG-04LX, UTM-30LX, ...).
    Hokuyo,
    /// A Slamtec RPLIDAR (A1, A2, A3, S, C series).
    Rplidar,
    /// A Benewake UART rangefinder (TFmini, TFmini-S, TFmini Plus, TF-Luna, TF02-Pro).
    Tfmini,
}

fn parse_benewake_model(text: &str) -> Result<BenewakeModel, String> {
    BenewakeModel::from_name(text).ok_or_else(|| {
        let names: Vec<&str> = BenewakeModel::ALL.iter().map(|m| m.name()).collect();
        format!(
            "unknown Benewake model {text:?} (one of {})",
            names.join(", ")
        )
    })
}

/// The RPLIDAR scan mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RplidarScan {
    /// The device's typical mode when decoded, else its express mode.
    Auto,
    /// 5-byte nodes (all models).
    Standard,
    /// Legacy express capsules.
    Express,
    /// Dense capsules.
    Dense,
}

/// How the RPLIDAR's motor is driven: `auto`, `dtr`, `pwm:DUTY` or `rpm:SPEED`.
fn parse_motor(text: &str) -> Result<MotorControl, String> {
    let number = |v: &str| v.parse::<u16>().map_err(|e| format!("motor {text:?}: {e}"));
    match text.split_once(':') {
        None if text == "auto" => Ok(MotorControl::Auto),
        None if text == "dtr" => Ok(MotorControl::Dtr),
        Some(("pwm", v)) => match number(v)? {
            d @ 1..=1023 => Ok(MotorControl::Pwm(d)),
            _ => Err("pwm:DUTY needs a duty in 1..=1023".into()),
        },
        Some(("rpm", v)) => match number(v)? {
            0 => Err("rpm:SPEED needs a positive speed".into()),
            r => Ok(MotorControl::Rpm(r)),
        },
        _ => Err(format!(
            "motor {text:?}: expected auto, dtr, pwm:DUTY or rpm:SPEED"
        )),
    }
}

/// The SCIP measurement command.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ScipScan {
    /// Streamed 3-character ranges.
    Md,
    /// Streamed 2-character ranges (at most 4.095 m).
    Ms,
    /// Streamed ranges with intensity (UTM-30LX and later; falls back to md).
    Me,
    /// Polled single scans.
    Gd,
    /// Streamed multi-echo ranges: every echo of a step is its own ray (NE
    /// with --intensity).
    Nd,
    /// Polled multi-echo single scans (HE with --intensity).
    Hd,
}

#[derive(Debug, Clone, Args)]
pub struct DeviceArgs {
    /// The device's protocol.
    #[arg(long, value_enum, default_value_t = DeviceKind::Shroud)]
    pub device: DeviceKind,
    /// The port's baud rate (default: shroud 921600; hokuyo 115200, ignored
    /// over USB; with --rs232, probed first).
    #[arg(long)]
    pub baud: Option<u32>,
    /// Hokuyo on RS-232: probe 19200, 38400 and 115200 for the sensor.
    #[arg(long)]
    pub rs232: bool,
    /// Hokuyo on RS-232: switch the sensor to this rate after connecting (SS).
    #[arg(long)]
    pub target_baud: Option<u32>,
    /// Hokuyo: the measurement command.
    #[arg(long, value_enum, default_value_t = ScipScan::Md)]
    pub scip_scan: ScipScan,
    /// Hokuyo: ask for intensity (md becomes me, gd ge, nd ne, hd he).
    #[arg(long)]
    pub intensity: bool,
    /// Hokuyo: adjacent steps merged into one ray (the nearest of them), 1..=99.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=99))]
    pub cluster: u8,
    /// Hokuyo: scans skipped between scans sent, 0..=9.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u8).range(0..=9))]
    pub skip: u8,
    /// Hokuyo: first and last step measured (default: the sensor's AMIN..AMAX).
    #[arg(long)]
    pub start_step: Option<u16>,
    #[arg(long)]
    pub end_step: Option<u16>,
    /// RPLIDAR: the scan mode.
    #[arg(long, value_enum, default_value_t = RplidarScan::Auto)]
    pub scan_mode: RplidarScan,
    /// RPLIDAR: motor control, auto, dtr (A1), pwm:DUTY (A2 accessory board)
    /// or rpm:SPEED (S and C series).
    #[arg(long, default_value = "auto", value_parser = parse_motor)]
    pub motor: MotorControl,
    /// Benewake: the model (its invalid-reading rules and range).
    #[arg(long, default_value = "tfmini-plus", value_parser = parse_benewake_model)]
    pub model: BenewakeModel,
    /// Benewake: set the output rate in Hz (0: trigger mode, the node asks
    /// for each reading); default: the device's own setting.
    #[arg(long)]
    pub frame_rate: Option<u16>,
    /// Benewake: millimetre output (TFmini-S and TFmini Plus; others stay in cm).
    #[arg(long)]
    pub millimetres: bool,
    /// Benewake: save the settings in the device (survives power cycles).
    #[arg(long)]
    pub save: bool,
    /// Benewake: the longest (seconds) a reading may wait where this host
    /// cannot see it, between its measurement and its bytes being readable
    /// (device processing, a USB adapter's buffering; an FTDI adapter holds
    /// bytes up to 16 ms by default). The frames carry no device time, so
    /// each reading is dated by the reads around it; this widens every
    /// reading's time bound. Default 0.005.
    #[arg(long)]
    pub link_latency: Option<f64>,
}

impl DeviceArgs {
    /// The port's opening rate.
    pub fn port_baud(&self) -> u32 {
        let default = match self.device {
            DeviceKind::Shroud => 921_600,
            DeviceKind::Hokuyo if self.rs232 => 19_200,
            DeviceKind::Hokuyo | DeviceKind::Rplidar | DeviceKind::Tfmini => 115_200,
        };
        self.baud.unwrap_or(default)
    }

    /// How long the port's reads block: a Benewake's frames carry no time,
    /// so they are dated by the reads around them, and frequent reads keep
    /// that interval short (1 ms: about a thousand cheap reads a second);
    /// the other devices send their own time.
    pub fn port_read_timeout(&self) -> Duration {
        match self.device {
            DeviceKind::Tfmini => Duration::from_millis(1),
            DeviceKind::Shroud | DeviceKind::Hokuyo | DeviceKind::Rplidar => {
                Duration::from_millis(20)
            }
        }
    }

    /// Options given that the chosen device does not read: a named error.
    fn check_applicable(&self) -> Result<()> {
        let hokuyo_only = [
            ("--rs232", self.rs232),
            ("--target-baud", self.target_baud.is_some()),
            ("--scip-scan", self.scip_scan != ScipScan::Md),
            ("--intensity", self.intensity),
            ("--cluster", self.cluster != 1),
            ("--skip", self.skip != 0),
            ("--start-step", self.start_step.is_some()),
            ("--end-step", self.end_step.is_some()),
        ];
        for (flag, given) in hokuyo_only {
            if given && self.device != DeviceKind::Hokuyo {
                bail!("{flag} applies to --device hokuyo only");
            }
        }
        let rplidar_only = [
            ("--scan-mode", self.scan_mode != RplidarScan::Auto),
            ("--motor", self.motor != MotorControl::Auto),
        ];
        for (flag, given) in rplidar_only {
            if given && self.device != DeviceKind::Rplidar {
                bail!("{flag} applies to --device rplidar only");
            }
        }
        let tfmini_only = [
            ("--model", self.model != BenewakeModel::TfminiPlus),
            ("--frame-rate", self.frame_rate.is_some()),
            ("--millimetres", self.millimetres),
            ("--save", self.save),
            ("--link-latency", self.link_latency.is_some()),
        ];
        for (flag, given) in tfmini_only {
            if given && self.device != DeviceKind::Tfmini {
                bail!("{flag} applies to --device tfmini only");
            }
        }
        if self.target_baud.is_some() && !self.rs232 {
            bail!("--target-baud needs --rs232 (over USB the rate does not matter)");
        }
        if self.scip_scan == ScipScan::Ms && self.intensity {
            bail!("--scip-scan ms has no intensity (use me, ne or he)");
        }
        if let (Some(start), Some(end)) = (self.start_step, self.end_step) {
            if start > end {
                bail!("--start-step {start} is after --end-step {end}");
            }
        }
        if let Some(latency) = self.link_latency {
            // NaN is in no range, so it is refused too.
            if !(0.0..=10.0).contains(&latency) {
                bail!("--link-latency must be between 0 and 10 seconds, not {latency}");
            }
        }
        let commanded = self.frame_rate.is_some() || self.millimetres || self.save;
        if self.device == DeviceKind::Tfmini && self.model == BenewakeModel::Tfmini && commanded {
            bail!("the original TFmini takes no commands: --frame-rate, --millimetres and --save do not apply");
        }
        Ok(())
    }

    /// The driver of a real device, or `None` for shroud's own protocol
    /// (read by the protocol reader).
    pub fn driver(&self) -> Result<Option<Box<dyn DeviceDriver>>> {
        self.check_applicable()?;
        Ok(match self.device {
            DeviceKind::Shroud => None,
            DeviceKind::Hokuyo => Some(Box::new(ScipDriver::new(self.scip_config()))),
            DeviceKind::Rplidar => Some(Box::new(RplidarDriver::new(RplidarConfig {
                baud: self.port_baud(),
                scan_mode: match self.scan_mode {
                    RplidarScan::Auto => ScanMode::Auto,
                    RplidarScan::Standard => ScanMode::Standard,
                    RplidarScan::Express => ScanMode::Express,
                    RplidarScan::Dense => ScanMode::Dense,
                },
                motor: self.motor,
                ..RplidarConfig::default()
            }))),
            DeviceKind::Tfmini => Some(Box::new(BenewakeDriver::new(BenewakeConfig {
                model: self.model,
                baud: self.port_baud(),
                frame_rate: self.frame_rate,
                unit: if self.millimetres {
                    DistanceUnit::Millimetre
                } else {
                    DistanceUnit::Centimetre
                },
                save: self.save,
                link_latency: self
                    .link_latency
                    .map(Duration::from_secs_f64)
                    .unwrap_or(BenewakeConfig::default().link_latency),
                ..BenewakeConfig::default()
            }))),
        })
    }

    fn scip_config(&self) -> ScipConfig {
        let link = if self.rs232 {
            let mut bauds = Link::DEFAULT_BAUDS.to_vec();
            if let Some(first) = self.baud {
                bauds.retain(|b| *b != first);
                bauds.insert(0, first);
            }
            Link::Rs232 { bauds }
        } else {
            Link::Usb
        };
        ScipConfig {
            link,
            target_baud: self.target_baud,
            scan: match self.scip_scan {
                ScipScan::Md => ScanCommand::Md,
                ScipScan::Ms => ScanCommand::Ms,
                ScipScan::Me => ScanCommand::Me,
                ScipScan::Gd => ScanCommand::Gd,
                ScipScan::Nd => ScanCommand::Nd,
                ScipScan::Hd => ScanCommand::Hd,
            },
            start_step: self.start_step,
            end_step: self.end_step,
            cluster: self.cluster,
            interval: self.skip,
            intensity: self.intensity || self.scip_scan == ScipScan::Me,
            ..ScipConfig::default()
        }
    }
}
