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
mod error;
mod field_of_view;
mod fit_stats;
mod joints;
mod message;
mod no_return;
mod skew;
mod smooth;
mod status;
mod surface;
mod surrogate;
mod topic;

pub use blend_command::{BlendCommand, BlendCommandMessage, LocalAdjust};
pub use blend_request::{BlendRequest, MAX_REQUEST_BYTES};
pub use blob::{
    bytes_to_f32s, bytes_to_f64s, encode_into, encoded_len, f32s_to_bytes, f64s_to_bytes,
};
pub use channels::{
    blobs_to_channels, channels_to_blobs, check_channels, check_point_channels, ChannelBlobs,
    PointChannel, MAX_CHANNELS, MAX_CHANNEL_NAME,
};
pub use cloud::{CloudMessage, SensorPose};
pub use cloud_view::CloudView;
pub use collision::sample_collision;
pub use collision::{CollisionMessage, GuardVerdict, LinkClearance};
pub use error::MessageError;
pub use field_of_view::sample_field_of_view;
pub use field_of_view::{Aperture, FieldOfView};
pub use fit_stats::{FitStats, Histogram};
pub use joints::JointStateMessage;
pub use message::{Message, WireOf};
pub use no_return::sample_no_return;
pub use no_return::{DarkCone, NoReturn, MAX_DARK_CONES};
pub use skew::{
    check_stamp_skew, counted_transit, max_skew_ns_from_secs, ClockAhead, StampSkew,
    DEFAULT_MAX_CLOCK_OFFSET_NS, DEFAULT_MAX_SKEW_NS,
};
pub use smooth::{SmoothPatchesMessage, COEFFICIENTS_PER_PATCH};
pub use status::NodeStatusMessage;
pub use surface::{Certificate, Domain, Side, DOMAIN_SLACK};
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
