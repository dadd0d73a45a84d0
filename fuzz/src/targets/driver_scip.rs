//! The Hokuyo SCIP 2.0 driver (`ScipDriver`) fed a device's bytes: `MD`
//! (ranges) or `ME` (ranges and intensity) streams.

use crate::serial_device::{record, run as run_driver};
use shroud_drivers::device::DeviceDriver;
use shroud_drivers::scip::{ScanCommand, ScipConfig, ScipDriver};

pub fn run(data: &[u8]) {
    run_driver(driver, data);
}

fn driver(choice: u8) -> Box<dyn DeviceDriver> {
    let config = match choice % 2 {
        0 => ScipConfig::default(),
        _ => ScipConfig {
            scan: ScanCommand::Me,
            intensity: true,
            ..ScipConfig::default()
        },
    };
    Box::new(ScipDriver::new(config))
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![
        record("urg-04lx", driver, 0, 0.35),
        record("utm-30lx", driver, 1, 0.15),
    ]
}
