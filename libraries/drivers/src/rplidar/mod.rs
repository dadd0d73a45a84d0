//! Slamtec RPLIDAR (A1/A2/A3, and S/C series on their standard, express and
//! dense scans) over its UART protocol, as a sans-I/O [`DeviceDriver`].
//!
//! Sources: Slamtec's "RPLIDAR Interface Protocol and Application Notes" and
//! the SDK `Slamtec/rplidar_sdk` @99478e5f (`sl_lidar_cmd.h`,
//! `sl_lidar_protocol.h`, `sl_lidarprotocol_codec.cpp`,
//! `handler_normalnode.cpp`, `handler_capsules.cpp`, `sl_lidar_driver.cpp`),
//! as summarised in the research notes §1.2. Each file cites what it uses.
//!
//! - framing: [`request`], [`descriptor`], [`reader`];
//! - answers: [`replies`], [`conf`];
//! - scans: [`node`] (0x81), [`capsule`] with [`express`] (0x82) and
//!   [`dense`] (0x85), [`stream`], [`timing`], [`angle`], [`revolution`];
//! - the driver: [`config`], [`plan`], [`motor`], [`probe`], [`driver`].
//!
//! Scans: one [`RangeScan`](crate::device::RangeScan) per
//! revolution, rays in measurement order, angles in REP-103 (the device's
//! clockwise headings negated, see [`angle`]), ranges in metres (`NaN` where
//! the device reported distance 0), intensity = quality (standard scans
//! only), stamps back-dated from the arrival of the bytes by the SDK's
//! timing model ([`timing`]).
//!
//! Not covered: HQ nodes (0x83), ultra capsules (0x84: the A series' Boost,
//! Sensitivity and Stability modes; `Auto` then picks the device's listed
//! Express mode) and ultra-dense capsules (0x86); baud-rate negotiation;
//! TCP/UDP models; the `DESIRED_ROT_FREQ` query (fixed PWM 660 / 600 rpm).
//! Standard nodes have no checksum: a corrupted byte0 can move a revolution
//! boundary undetectably (revolutions then merge or split, without holes).
//!
//! Errors counted (`DeviceStats::errors`): `resync`, `bad_checksum`,
//! `capsule_gap`, `incomplete_scan`, `oversize_scan`, `stray_bytes`,
//! `bad_descriptor`, `unexpected_response`, `bad_reply`, `timeout`,
//! `stream_timeout`, `health_warning`, `health_error`,
//! `unsupported_scan_mode`, `too_many_scan_modes`. Expected events
//! (`DeviceStats::notes`): `partial_revolution` (the first turn after a start
//! is discarded), `optional_timeout` (a query the model does not answer).
//!
//! [`DeviceDriver`]: crate::device::DeviceDriver

use crate::device;

pub mod angle;
pub mod capsule;
pub mod conf;
pub mod config;
pub mod dense;
pub mod descriptor;
pub mod driver;
pub mod express;
pub mod motor;
pub mod node;
pub mod plan;
pub mod probe;
pub mod protocol;
pub mod reader;
pub mod replies;
pub mod request;
pub mod revolution;
mod sample;
pub mod stream;
pub mod timing;

#[cfg(test)]
mod tests;

pub use config::{MotorControl, RplidarConfig, ScanMode};
pub use driver::RplidarDriver;
