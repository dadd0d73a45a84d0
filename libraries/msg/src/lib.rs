//! The wire schema of shroud's messages (version 2; joint states and collision
//! messages version 3): MessagePack maps with named fields, bulk arrays as
//! little-endian byte blobs, so that any language decodes a message with a
//! MessagePack library and a byte-to-array view (numpy's `frombuffer`). Pure
//! encode/decode with validation; transport lives in `nodes/`.

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
pub use topic::{
    check_name, is_sector_stream, sector_stream, Congestion, TopicKey, TopicKind, TopicPriority,
    TopicQos, Topics, ROOT,
};

/// The schema version of every message except joint states and collision
/// messages, which carry their own ([`JointStateMessage::VERSION`],
/// [`CollisionMessage::VERSION`]); decoders refuse other versions, naming the
/// message. Version 2 added `pipeline_ns` to clouds and surrogates and the
/// guard's age, views, reason and unobserved-space fields to collision
/// messages.
pub const SCHEMA_VERSION: u16 = 2;

/// Checks a decoded `message`'s version against the one this build reads.
pub(crate) fn check_version(
    message: &'static str,
    found: u16,
    expected: u16,
) -> Result<(), MessageError> {
    if found == expected {
        Ok(())
    } else {
        Err(MessageError::Version {
            message,
            found,
            expected,
        })
    }
}

/// Decodes a message whose version must be `expected`, checking the version
/// before anything else: a message of another version, whose fields may
/// differ, is refused as that, by name, not as malformed.
pub(crate) fn decode_versioned<'a, T: serde::Deserialize<'a>>(
    bytes: &'a [u8],
    message: &'static str,
    expected: u16,
) -> Result<T, MessageError> {
    /// Only the version of a message (serde skips the other fields).
    #[derive(serde::Deserialize)]
    struct Versioned {
        version: u16,
    }
    let Versioned { version } = blob::decode(bytes)?;
    check_version(message, version, expected)?;
    blob::decode(bytes)
}

/// Checks that every value of a decoded field is finite.
pub(crate) fn check_finite(field: &'static str, values: &[f64]) -> Result<(), MessageError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(MessageError::NonFinite { field, index }),
        None => Ok(()),
    }
}

/// Byte mutations of valid encodings, and the check that a decoder's error
/// names what it refused, for the decoders' property tests.
#[cfg(test)]
pub(crate) mod mutation {
    use crate::MessageError;
    use proptest::prelude::*;
    use proptest::sample::Index;

    /// One edit of an encoding.
    #[derive(Debug, Clone)]
    enum Edit {
        Set(Index, u8),
        FlipBit(Index, u8),
        Insert(Index, u8),
        Remove(Index),
        Truncate(Index),
    }

    fn edit() -> impl Strategy<Value = Edit> {
        prop_oneof![
            3 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Edit::Set(i, b)),
            3 => (any::<Index>(), 0u8..8).prop_map(|(i, b)| Edit::FlipBit(i, b)),
            1 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Edit::Insert(i, b)),
            1 => any::<Index>().prop_map(Edit::Remove),
            1 => any::<Index>().prop_map(Edit::Truncate),
        ]
    }

    /// `bytes` after one to five random edits (set, flip a bit, insert,
    /// remove, truncate), mostly one: most edits break the MessagePack
    /// structure, and one edit of a value is what reaches the validation.
    pub fn mutated(bytes: Vec<u8>) -> impl Strategy<Value = Vec<u8>> {
        let edits = prop_oneof![
            3 => proptest::collection::vec(edit(), 1..2),
            1 => proptest::collection::vec(edit(), 2..6),
        ];
        edits.prop_map(move |edits| {
            let mut out = bytes.clone();
            for edit in edits {
                let len = out.len();
                match edit {
                    Edit::Insert(i, b) => out.insert(i.index(len + 1), b),
                    Edit::Truncate(i) => out.truncate(i.index(len + 1)),
                    _ if len == 0 => {}
                    Edit::Set(i, b) => out[i.index(len)] = b,
                    Edit::FlipBit(i, bit) => out[i.index(len)] ^= 1 << bit,
                    Edit::Remove(i) => {
                        out.remove(i.index(len));
                    }
                }
            }
            out
        })
    }

    /// Panics unless `error` says what it refused: a version error names
    /// `message`, a field error one of `fields`, and the text is not empty.
    pub fn assert_named(error: &MessageError, message: &str, fields: &[&str]) {
        assert!(!error.to_string().trim().is_empty(), "{error:?}");
        match error {
            MessageError::Malformed(text) => assert!(!text.trim().is_empty(), "{error:?}"),
            MessageError::Version { message: m, .. } => assert_eq!(*m, message, "{error}"),
            MessageError::BlobLength { field, .. }
            | MessageError::Count { field, .. }
            | MessageError::NonFinite { field, .. }
            | MessageError::Invalid { field, .. } => {
                assert!(
                    fields.contains(field),
                    "{error} names no field of a {message}"
                )
            }
            MessageError::PositionError { .. } => panic!("{error} from a {message}"),
        }
    }
}
