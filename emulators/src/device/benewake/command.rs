//! The Benewake command set: frames `5A len id payload sum` (len counts
//! every byte, sum = low byte of the sum of all bytes before it), their
//! IDs, and replies in the same format (TFmini Plus manual §7.3, TFmini-S
//! A01 manual Table 12, TF-Luna A05 manual Appendix II).

use super::frame::sum8;
use super::rejects::{RejectCounts, RejectKind};

/// First byte of every command and reply.
pub(crate) const HEAD: u8 = 0x5A;
/// Shortest frame: head, len, id, sum.
const MIN_LEN: usize = 4;
/// Longest frame this emulator accepts (the documented ones stop at 9).
const MAX_LEN: usize = 32;

/// Command IDs.
pub(crate) mod id {
    pub const VERSION: u8 = 0x01;
    pub const SOFT_RESET: u8 = 0x02;
    pub const FRAME_RATE: u8 = 0x03;
    pub const TRIGGER: u8 = 0x04;
    pub const OUTPUT_FORMAT: u8 = 0x05;
    pub const BAUD_RATE: u8 = 0x06;
    pub const OUTPUT_ENABLE: u8 = 0x07;
    /// TF-Luna ID_CHECKSUM: 0 = ignore command sums, 1 = check them.
    pub const CHECKSUM_ENABLE: u8 = 0x08;
    pub const FACTORY_RESET: u8 = 0x10;
    pub const SAVE: u8 = 0x11;
}

/// A framed command, its sum checked (or not, when the model ignores sums).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct RawCommand {
    pub id: u8,
    /// At most `MAX_LEN - 4` bytes.
    pub payload: Vec<u8>,
}

/// A command the emulator understands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Command {
    Version,
    SoftReset,
    FrameRate(u16),
    Trigger,
    OutputFormat(u8),
    BaudRate(u32),
    OutputEnable(u8),
    ChecksumEnable(u8),
    FactoryReset,
    Save,
}

impl Command {
    /// The command `raw` names, or `None` for an unknown ID or a payload of
    /// the wrong length.
    pub(crate) fn parse(raw: &RawCommand) -> Option<Command> {
        let p = raw.payload.as_slice();
        match (raw.id, p) {
            (id::VERSION, []) => Some(Command::Version),
            (id::SOFT_RESET, []) => Some(Command::SoftReset),
            (id::FRAME_RATE, [lo, hi]) => Some(Command::FrameRate(u16::from_le_bytes([*lo, *hi]))),
            // TF-Luna documents its trigger as `5A 04 04 00`; others `5A 04 04 62`.
            (id::TRIGGER, []) => Some(Command::Trigger),
            (id::OUTPUT_FORMAT, [format]) => Some(Command::OutputFormat(*format)),
            (id::BAUD_RATE, [b0, b1, b2, b3]) => {
                Some(Command::BaudRate(u32::from_le_bytes([*b0, *b1, *b2, *b3])))
            }
            (id::OUTPUT_ENABLE, [flag]) => Some(Command::OutputEnable(*flag)),
            (id::CHECKSUM_ENABLE, [flag]) => Some(Command::ChecksumEnable(*flag)),
            (id::FACTORY_RESET, []) => Some(Command::FactoryReset),
            (id::SAVE, []) => Some(Command::Save),
            _ => None,
        }
    }
}

/// A reply frame: `5A len id payload sum`.
pub(crate) fn reply(id: u8, payload: &[u8]) -> Vec<u8> {
    let len = u8::try_from(payload.len() + MIN_LEN).unwrap_or(u8::MAX);
    let mut bytes = vec![HEAD, len, id];
    bytes.extend_from_slice(payload);
    bytes.push(sum8(&bytes));
    bytes
}

/// Cuts the host's bytes into command frames.
#[derive(Debug, Clone, Default)]
pub(crate) struct CommandParser {
    /// The frame so far; never longer than `MAX_LEN`.
    buf: Vec<u8>,
}

impl CommandParser {
    /// Forgets a partial frame.
    pub(crate) fn reset(&mut self) {
        self.buf.clear();
    }

    /// Feeds one byte; returns a command when it completes a frame whose sum
    /// matches (or whatever its sum when `check_sums` is false).
    pub(crate) fn push(
        &mut self,
        byte: u8,
        check_sums: bool,
        rejects: &mut RejectCounts,
    ) -> Option<RawCommand> {
        match self.buf.len() {
            0 if byte != HEAD => {
                rejects.count(RejectKind::StrayByte);
                return None;
            }
            1 if !(MIN_LEN..=MAX_LEN).contains(&usize::from(byte)) => {
                rejects.count(RejectKind::BadLength);
                self.buf.clear();
                return None;
            }
            _ => self.buf.push(byte),
        }
        let len = usize::from(*self.buf.get(1)?);
        if self.buf.len() < len {
            return None;
        }
        let frame = std::mem::take(&mut self.buf);
        let (body, sum) = frame.split_at(len - 1);
        if check_sums && sum.first() != Some(&sum8(body)) {
            rejects.count(RejectKind::BadChecksum);
            return None;
        }
        Some(RawCommand {
            id: *body.get(2)?,
            payload: body.get(3..).unwrap_or_default().to_vec(),
        })
    }
}
