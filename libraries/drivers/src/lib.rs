//! Sensor ingest codecs: turning the bytes and frames of depth/range sensors into
//! [`Scan`]s, and scans back into bytes for simulators. Pure: no I/O, no threads,
//! no clocks. The wire protocols are specified in `docs/sensor-protocols.md`.
//!
//! - [`serial`]: a framed binary protocol for serial range sensors;
//! - [`can`]: a CAN range-sensor protocol over classic 8-byte frames, plus the
//!   SLCAN (Lawicel ASCII) and candump-log codecs that carry CAN frames;
//! - [`device`]: the sans-I/O contract of real sensors' drivers
//!   ([`device::DeviceDriver`]) and the range scans they deliver;
//! - [`scip`], [`rplidar`], [`benewake`]: the drivers of Hokuyo SCIP 2.0
//!   lidars, Slamtec RPLIDARs and Benewake TFmini-family rangefinders;
//! - [`assembly`]: range scans placed through a (moving) mount into 3D clouds;
//! - [`dbc`]: CAN signal databases (DBC files) and the generic signal codec;
//! - [`can_device`]: the sans-I/O contract of real CAN sensors' drivers
//!   ([`can_device::CanDeviceDriver`]); [`ars408`] and [`benewake_can`]: the
//!   drivers of the Continental ARS408-21 radar and the Benewake CAN
//!   rangefinders, which read their signals through a DBC.
//!
//! Every decoder is streaming and never panics on any input. The protocol
//! decoders return named [`IngestError`]s and count them per [`ErrorKind`] in
//! [`DecoderStats`]; the device drivers count theirs by name in
//! [`device::DeviceStats`].
// `!(x > 0.0)` deliberately rejects NaN as well, which `x <= 0.0` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod ars408;
pub mod assembly;
pub mod benewake;
pub mod benewake_can;
pub mod can;
pub mod can_device;
pub mod dbc;
pub mod device;
mod error;
pub mod rplidar;
mod scan;
pub mod scip;
pub mod serial;
mod stats;

pub use error::{ErrorKind, IngestError};
pub use scan::Scan;
pub use stats::DecoderStats;
