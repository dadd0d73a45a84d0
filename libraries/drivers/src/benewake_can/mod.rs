//! Benewake single-beam lidars on CAN (sensors.md §2.1): TF03-CAN,
//! TFmini-i-CAN, TF02-i-CAN and the legacy TF02, several on one bus, each
//! with its id and mount, read through the model's DBC and assembled into one
//! cloud per cycle by a sans-I/O
//! [`CanDeviceDriver`](crate::can_device::CanDeviceDriver) (kind
//! `benewake_can`).
//!
//! Unlike a radar's cycle, whose frames together make one measurement (one
//! lost frame drops the cycle whole), each rangefinder's frame is a whole
//! measurement of its own: a cycle's cloud holds the readings that arrived
//! within it (every sensor once, or until a sensor reports again, or until
//! the cycle timeout), and a sensor that did not report is counted as
//! `missing_reading`, never guessed. A consumer that needs every beam reads
//! the cloud's `sensor_index` channel.
//!
//! Counters the driver keeps in its
//! [`DeviceStats`](crate::device::DeviceStats):
//! - errors: `missing_reading` (per sensor in
//!   [`BenewakeCanDriver::missing_by_sensor`]), `bad_frame` (shorter than the
//!   model's DLC, or a remote frame on a sensor's id), `silent`;
//! - invalid readings (no point): `weak_return`, `saturated`,
//!   `out_of_range`, `unreliable`;
//! - notes: `other_id`, `repeated_reading`, `cycle_cut`.

mod config;
mod cycle;
mod driver;
mod error;
mod model;
mod reading;

#[cfg(test)]
mod tests;

pub use config::{
    BenewakeCanConfig, RangefinderConfig, DEFAULT_CYCLE_TIMEOUT_NS, DEFAULT_SILENCE_TIMEOUT_NS,
    MAX_RANGEFINDERS,
};
pub use driver::BenewakeCanDriver;
pub use error::BenewakeCanError;
pub use model::{BenewakeCanModel, Validity};
pub use reading::{CanReading, DEVICE_TIME_MODULUS_MS};
