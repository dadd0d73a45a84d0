//! Drivers of real CAN sensors, written sans-I/O like the serial ones
//! ([`device`](super::device)): a driver is fed received frames, each with
//! its time, and the host's time when nothing arrives; it answers with the
//! frames to send and the clouds it assembled ([`CanDriverOutput`]). Signals
//! are read through a DBC ([`dbc`](super::dbc)), not by hand-shifted bytes.

mod driver;
mod timed_frame;

pub use driver::{CanDeviceDriver, CanDriverOutput, SensorCloud};
pub use timed_frame::{FrameClock, TimedFrame};
