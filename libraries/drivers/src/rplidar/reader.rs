//! Cuts the bytes a device sends outside a scan stream into answers: it hunts
//! for a response descriptor, then collects a single answer's payload, or
//! reports the start of a multiple-answer stream (a scan) for the driver to
//! hand the rest of the bytes to a scan decoder.
//!
//! Mirrors the states of `RPLidarProtocolCodec::onDecodeData`
//! (`sdk/src/sl_lidarprotocol_codec.cpp`), with a bound on the answer size.

use super::descriptor::{Descriptor, DescriptorError, SendMode};
use super::protocol::{ANSWER_SYNC, DESCRIPTOR_LEN};

/// The longest single answer accepted, in bytes. The longest the driver asks
/// for is `GET_INFO` (20 bytes) and `GET_LIDAR_CONF` mode names (the SDK's
/// buffer for one is 64 bytes, `LidarScanMode::scan_mode`).
pub const MAX_REPLY_LEN: usize = 256;

/// What the reader found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReaderEvent {
    /// A complete single answer.
    Reply { answer_type: u8, payload: Vec<u8> },
    /// A descriptor announcing a stream of answers; the bytes after it are
    /// the stream's.
    Stream(Descriptor),
    /// Seven bytes after `A5 5A` that are not a usable descriptor.
    Rejected(RejectReason),
}

/// Why a descriptor was not usable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum RejectReason {
    #[error(transparent)]
    Descriptor(#[from] DescriptorError),
    #[error("single answer of {0} bytes is longer than {MAX_REPLY_LEN}")]
    TooLong(u32),
}

/// The result of one [`ResponseReader::feed`].
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Fed {
    /// Bytes of the input used; the rest is for the caller to feed again (or
    /// to hand to a scan decoder after [`ReaderEvent::Stream`]).
    pub consumed: usize,
    /// Bytes that belonged to no descriptor or answer.
    pub stray: u64,
    pub event: Option<ReaderEvent>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    Sync1,
    Sync2,
    Header,
    Payload,
}

/// A streaming reader of descriptors and single answers; bounded memory.
#[derive(Debug, Clone)]
pub struct ResponseReader {
    stage: Stage,
    header: [u8; DESCRIPTOR_LEN],
    header_len: usize,
    answer_type: u8,
    expected: usize,
    payload: Vec<u8>,
}

impl Default for ResponseReader {
    fn default() -> Self {
        Self {
            stage: Stage::Sync1,
            header: [0; DESCRIPTOR_LEN],
            header_len: 0,
            answer_type: 0,
            expected: 0,
            payload: Vec::new(),
        }
    }
}

impl ResponseReader {
    /// Forgets any partial descriptor or answer.
    pub fn reset(&mut self) {
        *self = Self::default();
    }

    /// Reads `bytes` up to and including the first event.
    pub fn feed(&mut self, bytes: &[u8]) -> Fed {
        let mut fed = Fed::default();
        for &byte in bytes {
            fed.consumed += 1;
            fed.event = self.push(byte, &mut fed.stray);
            if fed.event.is_some() {
                break;
            }
        }
        fed
    }

    fn push(&mut self, byte: u8, stray: &mut u64) -> Option<ReaderEvent> {
        match self.stage {
            Stage::Sync1 => {
                if byte == ANSWER_SYNC[0] {
                    self.stage = Stage::Sync2;
                } else {
                    *stray += 1;
                }
                None
            }
            Stage::Sync2 => {
                if byte == ANSWER_SYNC[1] {
                    self.header[..2].copy_from_slice(&ANSWER_SYNC);
                    self.header_len = 2;
                    self.stage = Stage::Header;
                } else if byte == ANSWER_SYNC[0] {
                    // The earlier A5 was stray; this one may open a descriptor.
                    *stray += 1;
                } else {
                    *stray += 2;
                    self.stage = Stage::Sync1;
                }
                None
            }
            Stage::Header => self.push_header(byte),
            Stage::Payload => self.push_payload(byte),
        }
    }

    fn push_header(&mut self, byte: u8) -> Option<ReaderEvent> {
        if let Some(slot) = self.header.get_mut(self.header_len) {
            *slot = byte;
            self.header_len += 1;
        }
        if self.header_len < DESCRIPTOR_LEN {
            return None;
        }
        self.stage = Stage::Sync1;
        let descriptor = match Descriptor::parse(&self.header) {
            Ok(d) => d,
            Err(e) => return Some(ReaderEvent::Rejected(e.into())),
        };
        match descriptor.mode {
            SendMode::Multiple => Some(ReaderEvent::Stream(descriptor)),
            SendMode::Single => self.begin_payload(descriptor),
        }
    }

    fn begin_payload(&mut self, descriptor: Descriptor) -> Option<ReaderEvent> {
        let len = descriptor.len as usize;
        if len > MAX_REPLY_LEN {
            return Some(ReaderEvent::Rejected(RejectReason::TooLong(descriptor.len)));
        }
        self.answer_type = descriptor.answer_type;
        if len == 0 {
            return Some(self.take_reply());
        }
        self.expected = len;
        self.payload = Vec::with_capacity(len);
        self.stage = Stage::Payload;
        None
    }

    fn push_payload(&mut self, byte: u8) -> Option<ReaderEvent> {
        self.payload.push(byte);
        if self.payload.len() < self.expected {
            return None;
        }
        self.stage = Stage::Sync1;
        Some(self.take_reply())
    }

    fn take_reply(&mut self) -> ReaderEvent {
        ReaderEvent::Reply {
            answer_type: self.answer_type,
            payload: std::mem::take(&mut self.payload),
        }
    }
}
