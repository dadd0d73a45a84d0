//! The Benewake CAN rangefinder driver (`BenewakeCanDriver`) fed a bus's
//! frames, for each CAN model.

use crate::can_device::{record, run as run_driver};
use shroud_drivers::assembly::MountPose;
use shroud_drivers::benewake_can::{
    BenewakeCanConfig, BenewakeCanDriver, BenewakeCanModel, RangefinderConfig,
};
use shroud_drivers::can_device::CanDeviceDriver;

/// The CAN models: the emulator's name, shroud's name.
const MODELS: [(&str, &str); 4] = [
    ("tf03-can", "tf03"),
    ("tfmini-i-can", "tfmini-i"),
    ("tf02-i-can", "tf02-i"),
    ("tf02-can", "tf02"),
];

pub fn run(data: &[u8]) {
    run_driver(driver, data);
}

fn driver(choice: u8) -> Box<dyn CanDeviceDriver> {
    let (_, name) = MODELS[usize::from(choice) % MODELS.len()];
    let model = BenewakeCanModel::from_name(name).expect("a CAN model");
    let sensor = RangefinderConfig::new("front", model, MountPose::default());
    let config = BenewakeCanConfig::new(vec![sensor]);
    Box::new(BenewakeCanDriver::new(config).expect("a valid rangefinder configuration"))
}

pub fn seeds() -> Vec<Vec<u8>> {
    (0..MODELS.len() as u8)
        .map(|i| record(MODELS[usize::from(i)].0, driver, i, 0.2))
        .collect()
}
