//! The Continental ARS408 radar driver (`Ars408Driver`) fed a bus's frames:
//! RadarState, cluster and object lists decoded through the built-in DBC.

use crate::can_device::{record, run as run_driver};
use shroud_drivers::ars408::{Ars408Config, Ars408Driver, RadarOutput};
use shroud_drivers::can_device::CanDeviceDriver;
use shroud_drivers::dbc::builtin;

pub fn run(data: &[u8]) {
    run_driver(driver, data);
}

fn driver(choice: u8) -> Box<dyn CanDeviceDriver> {
    let output = match choice % 2 {
        0 => Ars408Config::default().output,
        _ => RadarOutput::Objects,
    };
    let config = Ars408Config {
        output,
        ..Ars408Config::default()
    };
    let database = builtin("ars408").expect("the built-in ARS408 database");
    Box::new(Ars408Driver::new(config, database).expect("a valid radar configuration"))
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![
        record("ars408", driver, 0, 0.3),
        record("ars408", driver, 1, 0.3),
    ]
}
