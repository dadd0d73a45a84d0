//! Command frames the host sends: `5A len id payload sum`, where `len` counts
//! every byte of the frame and `sum` is the low byte of the sum of all bytes
//! before it (TFmini Plus manual §7.3, TFmini-S manual Table 12). The TF-Luna
//! ignores the sum unless checksum checking (id 0x08) is on; the driver sends
//! correct sums to every model anyway.

use super::checksum::sum8;
use super::config::DistanceUnit;

/// First byte of every command frame and of every reply.
pub const COMMAND_HEADER: u8 = 0x5A;
/// Header, length, id and checksum: the bytes of a frame around its payload.
pub const FRAME_OVERHEAD: usize = 4;
/// The longest payload the driver sends or accepts. The longest documented
/// one is 4 bytes (baud); TF-Luna's "ID-0" output (12 bytes in all, Appendix
/// I) still fits, so it is recognised as a frame and not taken for garbage.
pub const MAX_PAYLOAD_LEN: usize = 12;
/// The longest command frame or reply: [`MAX_PAYLOAD_LEN`] + 4.
pub const MAX_COMMAND_FRAME_LEN: usize = MAX_PAYLOAD_LEN + FRAME_OVERHEAD;

/// Command identifiers (byte 2), TFmini-S manual Table 12 / TF03 manual §4.3.
pub mod id {
    /// Read the firmware version; the reply carries three version bytes.
    pub const VERSION: u8 = 0x01;
    /// Soft reset; the reply carries a status byte.
    pub const SOFT_RESET: u8 = 0x02;
    /// Frame rate, u16 LE Hz; 0 = trigger mode. Echoed.
    pub const FRAME_RATE: u8 = 0x03;
    /// Trigger one reading (trigger mode); answered by a data frame.
    pub const TRIGGER: u8 = 0x04;
    /// Output format (`01` 9-byte cm, `06` 9-byte mm). Echoed.
    pub const OUTPUT_FORMAT: u8 = 0x05;
    /// UART baud rate, u32 LE. Echoed.
    pub const BAUD: u8 = 0x06;
    /// Output enable (`01`) / disable (`00`). Echoed.
    pub const OUTPUT_ENABLE: u8 = 0x07;
    /// Restore factory settings; the reply carries a status byte.
    pub const FACTORY_RESET: u8 = 0x10;
    /// Save settings to flash; the reply carries a status byte.
    pub const SAVE: u8 = 0x11;
}

/// A command the driver can send.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Command {
    /// `5A 04 01 5F`.
    Version,
    /// `5A 04 02 60`.
    SoftReset,
    /// `5A 06 03 LL HH SU`; 0 Hz = trigger mode.
    FrameRate(u16),
    /// `5A 04 04 62`.
    Trigger,
    /// `5A 05 05 01 65` (cm) / `5A 05 05 06 6A` (mm).
    OutputFormat(DistanceUnit),
    /// `5A 08 06 B0 B1 B2 B3 SU`, the rate u32 LE.
    Baud(u32),
    /// `5A 05 07 01 67` (enable) / `5A 05 07 00 66` (disable).
    OutputEnable(bool),
    /// `5A 04 10 6E`.
    FactoryReset,
    /// `5A 04 11 6F`.
    Save,
}

impl Command {
    /// The command's identifier byte.
    pub fn id(self) -> u8 {
        match self {
            Self::Version => id::VERSION,
            Self::SoftReset => id::SOFT_RESET,
            Self::FrameRate(_) => id::FRAME_RATE,
            Self::Trigger => id::TRIGGER,
            Self::OutputFormat(_) => id::OUTPUT_FORMAT,
            Self::Baud(_) => id::BAUD,
            Self::OutputEnable(_) => id::OUTPUT_ENABLE,
            Self::FactoryReset => id::FACTORY_RESET,
            Self::Save => id::SAVE,
        }
    }

    /// The payload bytes, little-endian where multi-byte (manual §7.2).
    pub fn payload(self) -> Vec<u8> {
        match self {
            Self::FrameRate(hz) => hz.to_le_bytes().to_vec(),
            Self::OutputFormat(unit) => vec![unit.format_code()],
            Self::Baud(rate) => rate.to_le_bytes().to_vec(),
            Self::OutputEnable(on) => vec![u8::from(on)],
            Self::Version | Self::SoftReset | Self::Trigger | Self::FactoryReset | Self::Save => {
                Vec::new()
            }
        }
    }

    /// The complete frame to write.
    pub fn encode(self) -> Vec<u8> {
        encode_frame(self.id(), &self.payload())
    }
}

/// `5A len id payload sum` for any id and payload (also how a device forms
/// its replies). A payload longer than [`MAX_PAYLOAD_LEN`] is cut to that
/// length, so the frame stays within what [`super::CommandFrame::parse`]
/// accepts.
pub fn encode_frame(id: u8, payload: &[u8]) -> Vec<u8> {
    let payload = payload.get(..MAX_PAYLOAD_LEN).unwrap_or(payload);
    let mut bytes = Vec::with_capacity(payload.len() + FRAME_OVERHEAD);
    // At most MAX_PAYLOAD_LEN + 4 = 16: fits the length byte.
    let len = (payload.len() + FRAME_OVERHEAD) as u8;
    bytes.extend_from_slice(&[COMMAND_HEADER, len, id]);
    bytes.extend_from_slice(payload);
    bytes.push(sum8(&bytes));
    bytes
}
