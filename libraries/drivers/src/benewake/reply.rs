//! Frames the device sends back in the command scheme (`5A len id payload
//! sum`, the same as commands: TFmini Plus manual §7.3) and what each reply
//! says.

use std::fmt;

use super::checksum::sum8;
use super::command::{id, COMMAND_HEADER, FRAME_OVERHEAD, MAX_COMMAND_FRAME_LEN, MAX_PAYLOAD_LEN};

/// One checksum-valid `5A` frame from the device.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CommandFrame {
    id: u8,
    payload_len: u8,
    payload: [u8; MAX_PAYLOAD_LEN],
}

/// Why bytes are not a `5A` frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum ReplyError {
    #[error("command frame does not start with 5A")]
    BadHeader,
    #[error("command frame length {0} outside 4..=16")]
    BadLength(u8),
    #[error("command frame length byte says {expected} bytes, got {got}")]
    LengthMismatch { expected: u8, got: usize },
    #[error("command frame checksum {found:#04x}, expected {expected:#04x}")]
    BadChecksum { expected: u8, found: u8 },
}

impl CommandFrame {
    /// Whether `len` (byte 1) is a length this driver accepts.
    pub fn valid_length(len: u8) -> bool {
        (FRAME_OVERHEAD..=MAX_COMMAND_FRAME_LEN).contains(&usize::from(len))
    }

    /// Reads exactly one frame: header, a length byte equal to `bytes.len()`
    /// and within 4..=16, and the checksum.
    pub fn parse(bytes: &[u8]) -> Result<Self, ReplyError> {
        let (&head, rest) = bytes.split_first().ok_or(ReplyError::BadHeader)?;
        if head != COMMAND_HEADER {
            return Err(ReplyError::BadHeader);
        }
        let len = rest.first().copied().ok_or(ReplyError::BadLength(0))?;
        if !Self::valid_length(len) {
            return Err(ReplyError::BadLength(len));
        }
        if usize::from(len) != bytes.len() {
            return Err(ReplyError::LengthMismatch {
                expected: len,
                got: bytes.len(),
            });
        }
        let (&found, body) = bytes.split_last().ok_or(ReplyError::BadLength(len))?;
        let expected = sum8(body);
        if found != expected {
            return Err(ReplyError::BadChecksum { expected, found });
        }
        let id = body.get(2).copied().ok_or(ReplyError::BadLength(len))?;
        let data = body.get(3..).unwrap_or_default();
        let mut payload = [0; MAX_PAYLOAD_LEN];
        let n = data.len().min(MAX_PAYLOAD_LEN);
        payload[..n].copy_from_slice(&data[..n]);
        Ok(Self {
            id,
            payload_len: n as u8,
            payload,
        })
    }

    /// Byte 2: the command this frame answers.
    pub fn id(&self) -> u8 {
        self.id
    }

    /// The bytes between the id and the checksum.
    pub fn payload(&self) -> &[u8] {
        &self.payload[..usize::from(self.payload_len)]
    }

    /// What the frame says, by its id and payload size.
    pub fn reply(&self) -> Reply {
        Reply::from_frame(self)
    }
}

/// A firmware version from the reply to `01`: bytes `V1 V2 V3` mean version
/// V3.V2.V1 (TF03 manual §4.3.1: bytes 112, 50, 9 are version 9.50.112;
/// TFmini-S manual Table 12 "Version V3.2.1").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FirmwareVersion {
    pub major: u8,
    pub minor: u8,
    pub patch: u8,
}

impl fmt::Display for FirmwareVersion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}.{}.{}", self.major, self.minor, self.patch)
    }
}

/// A reply, interpreted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Reply {
    /// `5A 07 01 V1 V2 V3 SU`.
    Version(FirmwareVersion),
    /// `5A 05 <02|10|11> <status> SU`: soft reset, factory reset or save;
    /// status 0 is success (TF03 manual §4.3.2, TFmini-S manual Table 12).
    Status { command: u8, ok: bool },
    /// `5A 06 03 LL HH SU`: the frame rate now set, Hz.
    FrameRate(u16),
    /// `5A 05 05 <format> SU`: the output format now set.
    OutputFormat(u8),
    /// `5A 08 06 <u32 LE> SU`: the baud rate now set.
    Baud(u32),
    /// `5A 05 07 <00|01> SU`: output now enabled (true) or disabled.
    OutputEnable(bool),
    /// An id this driver does not use, or a payload of an unexpected size.
    Unrecognised { id: u8, payload_len: u8 },
}

impl Reply {
    fn from_frame(frame: &CommandFrame) -> Self {
        match (frame.id(), frame.payload()) {
            (id::VERSION, &[v1, v2, v3]) => Self::Version(FirmwareVersion {
                major: v3,
                minor: v2,
                patch: v1,
            }),
            (id::SOFT_RESET | id::FACTORY_RESET | id::SAVE, &[status]) => Self::Status {
                command: frame.id(),
                ok: status == 0,
            },
            (id::FRAME_RATE, &[lo, hi]) => Self::FrameRate(u16::from_le_bytes([lo, hi])),
            (id::OUTPUT_FORMAT, &[format]) => Self::OutputFormat(format),
            (id::BAUD, &[b0, b1, b2, b3]) => Self::Baud(u32::from_le_bytes([b0, b1, b2, b3])),
            (id::OUTPUT_ENABLE, &[state]) => Self::OutputEnable(state != 0),
            (id, payload) => Self::Unrecognised {
                id,
                payload_len: payload.len() as u8,
            },
        }
    }
}
