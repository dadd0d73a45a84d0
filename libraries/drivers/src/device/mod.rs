//! Drivers of real range sensors, written sans-I/O: a driver is a state machine
//! fed the bytes read from its port and the host's time, and it answers with
//! what to write, which line settings to change and what it decoded
//! ([`DriverOutput`]). The node that owns the port only carries bytes; every
//! decision (handshake, probing, recovery, when a scan is complete, what a
//! reading is worth) is made here, where it is unit-tested.
//!
//! Frames follow REP-103: x forward, y left, z up, angles counter-clockwise
//! positive about z, ranges in metres.

mod driver;
mod range_scan;
mod stats;
mod time;

pub use driver::{DeviceDriver, DeviceState, DriverOutput};
pub use range_scan::{RangeScan, Ray, StampBound};
pub use stats::DeviceStats;
pub use time::{HostTime, ReadWindow};
