//! The web dashboard's wire protocol (`docs/dashboard-protocol.md`) as
//! pure code: the binary frame layout (a JSON header and little-endian arrays
//! a browser views without copying), the frames built from decoded messages,
//! and the commands a browser sends back. The node only moves these bytes.

mod command;
mod error;
mod frame;
mod views;

pub use command::{BrowserCommand, MAX_COMMAND_BYTES};
pub use error::DashboardError;
pub use frame::{ArrayData, DecodedArray, DecodedFrame, Frame};
pub use views::{
    arm_frame, blend_result_frame, cloud_frame, error_frame, hello_frame, nodes_frame,
    smooth_frame, surrogate_frame, verdict_frame, BlendPalette, CloudFrameInput, DashboardCounts,
    Hello, TopicRate,
};

/// The protocol version in `hello` (version 2 added the verdict frame's
/// `speed_scale`, `limiting_link` and `protective_distance`).
pub const PROTOCOL_VERSION: u32 = 2;
