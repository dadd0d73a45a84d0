//! ROS 2's wire: CDR messages and rmw_zenoh's keys, liveliness tokens, QoS and attachment.
//!
//! Pure encoding and decoding (no I/O, no clocks, no zenoh), for a process
//! that speaks to ROS 2 nodes over rmw_zenoh without ROS installed:
//! - [`cdr`]: the classic CDR (XCDR1) encapsulation of ROS 2 messages;
//! - [`msgs`]: the ROS 2 Jazzy messages shroud publishes, as plain structs;
//! - [`rmw`]: rmw_zenoh's topic keys, liveliness tokens, QoS strings,
//!   sample attachment and entity gids.

pub mod cdr;
pub mod msgs;
pub mod rmw;

pub use cdr::{CdrError, CdrReader, CdrWriter};
pub use msgs::*;
pub use rmw::*;
