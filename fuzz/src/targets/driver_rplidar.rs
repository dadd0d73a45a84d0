//! The RPLIDAR driver (`RplidarDriver`) fed a device's bytes: descriptors,
//! single answers and standard, express and dense scan streams.

use crate::serial_device::{record, run as run_driver};
use shroud_drivers::device::DeviceDriver;
use shroud_drivers::rplidar::{RplidarConfig, RplidarDriver, ScanMode};

pub fn run(data: &[u8]) {
    run_driver(driver, data);
}

fn driver(choice: u8) -> Box<dyn DeviceDriver> {
    let scan_mode = match choice % 2 {
        0 => RplidarConfig::default().scan_mode,
        _ => ScanMode::Express,
    };
    Box::new(RplidarDriver::new(RplidarConfig {
        scan_mode,
        ..RplidarConfig::default()
    }))
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![
        record("rplidar-a2", driver, 0, 1.5),
        record("rplidar-a1", driver, 1, 1.5),
    ]
}
