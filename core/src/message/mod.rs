//! The wire schema of shroud's messages (version 2): MessagePack maps with named
//! fields, bulk arrays as little-endian byte blobs, so that any language decodes a
//! message with a MessagePack library and a byte-to-array view (numpy's
//! `frombuffer`). Pure encode/decode with validation; transport lives in `nodes/`.

mod blend_command;
mod blend_request;
mod blob;
mod channels;
mod cloud;
mod cloud_view;
mod collision;
mod describe;
mod error;
mod field_of_view;
mod joints;
mod no_return;
mod skew;
mod smooth;
mod status;
mod surrogate;
mod topic;

pub use blend_command::BlendCommandMessage;
pub use blend_request::{BlendRequest, MAX_REQUEST_BYTES};
pub use blob::{encode_into, encoded_len};
pub use channels::{
    blobs_to_channels, channels_to_blobs, check_channels, check_point_channels, ChannelBlobs,
    PointChannel, MAX_CHANNELS, MAX_CHANNEL_NAME,
};
pub use cloud::{CloudMessage, SensorPose};
pub use cloud_view::CloudView;
#[cfg(test)]
pub(crate) use collision::sample_collision;
pub use collision::{CollisionMessage, GuardVerdict, LinkClearance};
pub use describe::describe;
pub use error::MessageError;
#[cfg(test)]
pub(crate) use field_of_view::sample_field_of_view;
pub use field_of_view::{Aperture, FieldOfView};
pub use joints::JointStateMessage;
#[cfg(test)]
pub(crate) use no_return::sample_no_return;
pub use no_return::{DarkCone, NoReturn, MAX_DARK_CONES};
pub use skew::{
    check_stamp_skew, counted_transit, max_skew_ns_from_secs, ClockAhead, StampSkew,
    DEFAULT_MAX_CLOCK_OFFSET_NS, DEFAULT_MAX_SKEW_NS,
};
#[cfg(test)]
pub(crate) use smooth::sample_smooth_message;
pub use smooth::{SmoothFitReport, SmoothPatchesMessage};
pub use status::NodeStatusMessage;
pub use surrogate::{SurfaceMessage, SurrogateMessage};
pub use topic::{check_name, Congestion, TopicKey, TopicKind, TopicQos, Topics, ROOT};

/// The schema version every message carries; decoders refuse other versions.
/// Version 2 added `pipeline_ns` to clouds and surrogates and the guard's
/// age, views, reason and unobserved-space fields to collision messages.
pub const SCHEMA_VERSION: u16 = 2;

/// Checks a decoded message's version.
pub(crate) fn check_version(found: u16) -> Result<(), MessageError> {
    if found == SCHEMA_VERSION {
        Ok(())
    } else {
        Err(MessageError::Version {
            found,
            expected: SCHEMA_VERSION,
        })
    }
}

/// Checks that every value of a decoded field is finite.
pub(crate) fn check_finite(field: &'static str, values: &[f64]) -> Result<(), MessageError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(MessageError::NonFinite { field, index }),
        None => Ok(()),
    }
}
