//! The Benewake serial driver (`BenewakeDriver`, TFmini family) fed a
//! device's bytes: data frames and command replies.

use crate::serial_device::{record, run as run_driver};
use shroud_drivers::benewake::{BenewakeConfig, BenewakeDriver, BenewakeModel};
use shroud_drivers::device::DeviceDriver;

pub fn run(data: &[u8]) {
    run_driver(driver, data);
}

fn driver(choice: u8) -> Box<dyn DeviceDriver> {
    let (model, frame_rate) = match choice % 3 {
        0 => (BenewakeModel::TfminiPlus, Some(100)),
        1 => (BenewakeModel::TfminiPlus, None),
        _ => (BenewakeModel::Tfmini, None),
    };
    Box::new(BenewakeDriver::new(BenewakeConfig {
        model,
        frame_rate,
        ..BenewakeConfig::default()
    }))
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![
        record("tfmini-plus", driver, 0, 0.3),
        record("tfmini", driver, 2, 0.3),
    ]
}
