//! Every emulated model by name, and the options they share, so that a CLI
//! can make any of them.

use super::benewake::{BenewakeEmulator, BenewakeModel, BenewakeOptions};
use super::emulator::{Faults, SerialDeviceEmulator};
use super::hokuyo::{HokuyoEmulator, HokuyoModel, HokuyoOptions, Link};
use super::rplidar::{RplidarEmulator, RplidarModel, RplidarOptions};
use shroud_sim::world::RaySource;

/// The models [`emulator`] makes.
pub const MODELS: [&str; 9] = [
    "urg-04lx",
    "utm-30lx",
    "rplidar-a1",
    "rplidar-a2",
    "tfmini",
    "tfmini-s",
    "tfmini-plus",
    "tf-luna",
    "tf02-pro",
];

/// Options every emulated model takes (each uses what applies to it).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EmulatorOptions {
    pub faults: Faults,
    /// Seed of the device's range noise and dropouts.
    pub seed: u64,
    /// Hokuyo: an RS-232 link whose UART starts at this rate (None: USB).
    pub rs232_baud: Option<u32>,
    /// Hokuyo: answer in SCIP 1.1 until switched to 2.0.
    pub starts_in_scip1: bool,
    /// Hokuyo: the millisecond clock at power-up.
    pub clock_start_ms: u32,
    /// Hokuyo: enter the abnormal state after this many scans.
    pub abnormal_after_scans: Option<u64>,
}

/// A fresh (just powered up) emulator of `model` measuring `rays`.
pub fn emulator(
    model: &str,
    rays: Box<dyn RaySource>,
    options: &EmulatorOptions,
) -> Result<Box<dyn SerialDeviceEmulator>, String> {
    if let Some(hokuyo) = HokuyoModel::from_name(model) {
        let options = HokuyoOptions {
            faults: options.faults,
            link: match options.rs232_baud {
                Some(baud) => Link::Rs232 { baud },
                None => Link::Usb,
            },
            starts_in_scip1: options.starts_in_scip1,
            clock_start_ms: options.clock_start_ms,
            abnormal_after_scans: options.abnormal_after_scans,
            seed: options.seed,
            dropout_probability: 0.002,
            ..HokuyoOptions::default()
        };
        return Ok(Box::new(HokuyoEmulator::new(hokuyo, rays, options)));
    }
    if let Some(rplidar) = RplidarModel::from_name(model) {
        let options = RplidarOptions {
            faults: options.faults,
            seed: options.seed,
            ..RplidarOptions::default()
        };
        return Ok(Box::new(RplidarEmulator::new(rplidar, rays, options)));
    }
    if let Some(benewake) = BenewakeModel::from_name(model) {
        let options = BenewakeOptions {
            faults: options.faults,
            seed: options.seed,
            ..BenewakeOptions::default()
        };
        return Ok(Box::new(BenewakeEmulator::new(benewake, rays, options)));
    }
    Err(format!(
        "unknown device model {model:?} (one of {})",
        MODELS.join(", ")
    ))
}
