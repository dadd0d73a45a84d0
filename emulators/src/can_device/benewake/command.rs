//! Benewake `5A` configuration commands carried in CAN frames (sensors.md
//! §2.1): `5A <len> <id> <payload…> <sum>`, sum = low byte of the sum of all
//! earlier bytes. A command longer than 8 bytes (the TFmini-i's 14-byte CAN
//! setting) spans several frames, so the bytes of a unit's receive id are
//! read as one stream.

/// Header byte of every command.
pub(crate) const HEADER: u8 = 0x5A;
/// Shortest (header, len, id, sum) and longest command the parser takes.
const MIN_LEN: usize = 4;
const MAX_LEN: usize = 32;

/// Command ids (TF03 UART/CAN manual V1.2.2 p.14; TFmini-i manual §3.2.1).
pub(crate) mod id {
    pub const FACTORY_RESET: u8 = 0x10;
    pub const SAVE: u8 = 0x11;
    pub const TX_ID: u8 = 0x50;
    /// TF03: the receive id. TFmini-i / TF02-i: the whole CAN setting.
    pub const RX_ID_OR_CAN_SETTING: u8 = 0x51;
    pub const BITRATE: u8 = 0x52;
    pub const FRAME_TYPE: u8 = 0x5D;
}

/// Low byte of the sum of `bytes`.
pub(crate) fn checksum(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0u8, |sum, &b| sum.wrapping_add(b))
}

/// `5A 05 <id> <status> <sum>`: the TF03's reply to a setting, save or
/// factory reset (0 = success).
pub(crate) fn status_reply(command: u8, status: u8) -> Vec<u8> {
    let mut reply = vec![HEADER, 5, command, status];
    reply.push(checksum(&reply));
    reply
}

/// A complete, checksum-verified command.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Command {
    /// Every byte, header to sum.
    pub bytes: Vec<u8>,
}

impl Command {
    pub(crate) fn id(&self) -> u8 {
        self.bytes.get(2).copied().unwrap_or(0)
    }

    /// The bytes between the id and the sum.
    pub(crate) fn payload(&self) -> &[u8] {
        let end = self.bytes.len().saturating_sub(1);
        self.bytes.get(3..end).unwrap_or_default()
    }
}

/// Finds commands in a byte stream, skipping bytes that cannot start one
/// and commands whose sum is wrong.
#[derive(Debug, Default)]
pub(crate) struct CommandParser {
    buffer: Vec<u8>,
    /// Bytes skipped (no header, bad length or bad sum).
    pub(crate) skipped: u64,
}

impl CommandParser {
    /// Takes `bytes`; appends each command they complete to `out`.
    pub(crate) fn push(&mut self, bytes: &[u8], out: &mut Vec<Command>) {
        for &byte in bytes {
            self.buffer.push(byte);
            self.scan(out);
        }
    }

    fn scan(&mut self, out: &mut Vec<Command>) {
        loop {
            match self.buffer.iter().position(|&b| b == HEADER) {
                Some(0) => {}
                Some(n) => self.skip(n),
                None => {
                    let n = self.buffer.len();
                    return self.skip(n);
                }
            }
            let Some(&len) = self.buffer.get(1) else {
                return;
            };
            let len = usize::from(len);
            if !(MIN_LEN..=MAX_LEN).contains(&len) {
                self.skip(1);
                continue;
            }
            if self.buffer.len() < len {
                return;
            }
            let (Some(body), Some(&sum)) = (self.buffer.get(..len - 1), self.buffer.get(len - 1))
            else {
                return;
            };
            if checksum(body) != sum {
                self.skip(1);
                continue;
            }
            out.push(Command {
                bytes: self.buffer.drain(..len).collect(),
            });
        }
    }

    fn skip(&mut self, n: usize) {
        let n = n.min(self.buffer.len());
        self.buffer.drain(..n);
        self.skipped = self.skipped.saturating_add(n as u64);
    }
}

/// A little-endian u32 at `at` of `payload`.
pub(crate) fn u32_le(payload: &[u8], at: usize) -> Option<u32> {
    let bytes = payload.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes(bytes.try_into().ok()?))
}
