//! Benewake TFmini-family single-beam lidars on a UART (TFmini, TFmini-S,
//! TFmini Plus, TF-Luna, TF02-Pro; sensors.md §1.3): the 9-byte data frame,
//! the `5A` command frames and their replies, the per-model invalid-reading
//! rules, and a sans-I/O [`BenewakeDriver`] implementing
//! [`DeviceDriver`](crate::device::DeviceDriver) (kind `tfmini`).
//!
//! Counters the driver keeps in its
//! [`DeviceStats`](crate::device::DeviceStats): `bad_checksum`,
//! `garbage`, `partial_frame` (decoder); `command_unanswered`,
//! `unexpected_reply`, `save_failed`, `trigger_unanswered`, `timeout`
//! (driver); as an expected event (`DeviceStats::notes`),
//! `frame_while_configuring`; and, as invalid readings
//! (delivered as `NaN` rays, not errors), `weak_return`, `saturated`,
//! `out_of_range`.

mod checksum;
mod command;
mod config;
mod decoder;
mod driver;
mod frame;
mod handshake;
mod identity;
mod model;
mod reading;
mod reply;
mod timing;
mod validity;

#[cfg(test)]
mod tests;

pub use checksum::sum8;
pub use command::{
    encode_frame, id as command_id, Command, COMMAND_HEADER, MAX_COMMAND_FRAME_LEN, MAX_PAYLOAD_LEN,
};
pub use config::{BenewakeConfig, DistanceUnit};
pub use decoder::{DecodeError, Decoded, Decoder, Packet};
pub use driver::BenewakeDriver;
pub use frame::{DataFrame, FrameError, TfminiDistanceMode, FRAME_HEADER, FRAME_LEN};
pub use handshake::{plan, Step};
pub use identity::{frame_rate_text, identity};
pub use model::BenewakeModel;
pub use reading::Reading;
pub use reply::{CommandFrame, FirmwareVersion, Reply, ReplyError};
pub use timing::{frame_transmission_ns, stream_timeout_ns};
pub use validity::Validity;
