//! The attachment rmw_zenoh requires on every sample (without it the sample
//! is dropped: "Unable to obtain attachment", rmw_subscription_data.cpp@a72659a6):
//! zenoh-ext's serialization of `(i64, i64, [u8; 16])` (attachment_helpers.cpp@534747dc,
//! since Jazzy 0.2.4, rmw_zenoh #601/#605).

use super::error::RmwError;

/// The attachment's length: two i64 and the gid with its length byte.
pub const ATTACHMENT_LEN: usize = 33;
/// The byte before the gid: zenoh-ext's varint length of the 16-byte array.
pub const GID_LEN_MARKER: u8 = 0x10;

/// A sample's attachment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Attachment {
    /// Counts the publisher's samples from 1.
    pub sequence_number: i64,
    /// When the sample was published, nanoseconds since the Unix epoch.
    pub source_timestamp_ns: i64,
    /// The publisher's gid ([`super::entity_gid`] of its token).
    pub gid: [u8; 16],
}

impl Attachment {
    /// `i64 LE sequence_number | i64 LE source_timestamp_ns | 0x10 | gid`.
    pub fn encode(&self) -> [u8; ATTACHMENT_LEN] {
        let mut bytes = [0; ATTACHMENT_LEN];
        bytes[..8].copy_from_slice(&self.sequence_number.to_le_bytes());
        bytes[8..16].copy_from_slice(&self.source_timestamp_ns.to_le_bytes());
        bytes[16] = GID_LEN_MARKER;
        bytes[17..].copy_from_slice(&self.gid);
        bytes
    }

    /// Reads exactly [`ATTACHMENT_LEN`] bytes with the 0x10 marker.
    pub fn decode(bytes: &[u8]) -> Result<Self, RmwError> {
        let bytes: &[u8; ATTACHMENT_LEN] = bytes
            .try_into()
            .map_err(|_| RmwError::AttachmentLength { len: bytes.len() })?;
        if bytes[16] != GID_LEN_MARKER {
            return Err(RmwError::AttachmentGidMarker { found: bytes[16] });
        }
        let i64_at =
            |start: usize| i64::from_le_bytes(bytes[start..start + 8].try_into().expect("8 bytes"));
        Ok(Self {
            sequence_number: i64_at(0),
            source_timestamp_ns: i64_at(8),
            gid: bytes[17..].try_into().expect("16 bytes"),
        })
    }
}
