//! The Continental ARS408-21 radar on CAN (sensors.md §2.2), as a sans-I/O
//! [`CanDeviceDriver`](crate::can_device::CanDeviceDriver) (kind
//! `ars408`): the radar's frames are read through its DBC
//! ([`dbc::builtin("ars408")`](crate::dbc::builtin) or a user's
//! variant), a measurement cycle (cluster list or object list) becomes one
//! cloud in the robot's frame, RadarState becomes health and identity, and an
//! optional configuration is sent on connect and confirmed. A complete cycle
//! is published when the next status frame shows no status was lost in
//! between (its MeasCounter follows): one cycle of latency, counted in the
//! cloud's age.
//!
//! Counters the driver keeps in its
//! [`DeviceStats`](crate::device::DeviceStats):
//! - errors: `incomplete_cycle` (a cycle dropped whole, counted once), with
//!   its cause `lost_frame` (an id gap or repeat, too few frames when the next
//!   status arrives, a frame of the cycle's kind with no open cycle),
//!   `lost_status` (the next status's MeasCounter skips: a status was lost,
//!   and the complete-looking cycle before it may hold another cycle's
//!   frames) or `bad_frame` (a frame that does not decode: short, a count
//!   over the limit; also remote or extended frames on the radar's ids);
//!   `config_not_confirmed`, `config_lost`, `silent`, `sensor_id_mismatch`;
//! - notes: `config_confirmed`, `config_not_sent`, `other_output`,
//!   `other_id`, `partial_first_cycle`, `dropped_cycle_frame`, `cycle_cut`.

mod cloud;
mod config;
mod configure;
mod cycle;
mod driver;
mod error;
mod layout;
mod radar_state;

#[cfg(test)]
mod tests;

pub use cloud::{CLUSTER_CHANNELS, OBJECT_CHANNELS};
pub use config::{
    Ars408Config, RadarOutput, RadarSettings, DEFAULT_SILENCE_TIMEOUT_NS, MAX_SENSOR_ID,
};
pub use configure::{CONFIG_RESENDS, CONFIG_RETRY_NS};
pub use cycle::{MAX_CLUSTERS, MAX_OBJECTS};
pub use driver::Ars408Driver;
pub use error::Ars408Error;
pub use radar_state::ERROR_NAMES;
