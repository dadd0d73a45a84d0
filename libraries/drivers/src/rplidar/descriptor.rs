//! The response descriptor that precedes every answer:
//! `A5 5A`, a `u32 LE` whose bits 0..29 are the answer length and bits 30..31
//! the send mode, then the answer type byte (`sl_lidar_ans_header_t` in
//! `sl_lidar_protocol.h`; protocol PDF §"Response packets' format").

use super::protocol::{ANSWER_SYNC, DESCRIPTOR_LEN};

/// How the device sends the answer that follows a descriptor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SendMode {
    /// One answer of `len` bytes.
    Single,
    /// Answers of `len` bytes, one after another, until the next command
    /// (scans).
    Multiple,
}

/// A parsed response descriptor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Descriptor {
    /// Bytes in one answer (30 bits).
    pub len: u32,
    pub mode: SendMode,
    /// The answer type (`protocol::answer`).
    pub answer_type: u8,
}

/// Why seven bytes are not a descriptor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum DescriptorError {
    #[error("descriptor does not start with A5 5A")]
    BadSync,
    /// Send modes 2 and 3 are not defined by the protocol.
    #[error("undefined send mode {0}")]
    BadMode(u8),
}

impl Descriptor {
    /// Parses the seven bytes of a descriptor.
    pub fn parse(bytes: &[u8; DESCRIPTOR_LEN]) -> Result<Self, DescriptorError> {
        let [s1, s2, l0, l1, l2, l3, answer_type] = *bytes;
        if [s1, s2] != ANSWER_SYNC {
            return Err(DescriptorError::BadSync);
        }
        let word = u32::from_le_bytes([l0, l1, l2, l3]);
        let mode = match (word >> 30) as u8 {
            0 => SendMode::Single,
            1 => SendMode::Multiple,
            other => return Err(DescriptorError::BadMode(other)),
        };
        Ok(Self {
            len: word & 0x3FFF_FFFF,
            mode,
            answer_type,
        })
    }
}
