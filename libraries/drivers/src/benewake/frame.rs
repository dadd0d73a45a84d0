//! The 9-byte data frame every model streams by default:
//! `59 59 DL DH SL SH TL TH CS` (sensors.md §1.3; TFmini Plus manual §6.1,
//! TF-Luna manual Appendix I "9-byte/cm").

use super::checksum::sum8;

/// Both of the first two bytes of a data frame.
pub const FRAME_HEADER: u8 = 0x59;
/// Bytes in a data frame, header and checksum included.
pub const FRAME_LEN: usize = 9;

/// One data frame, its three little-endian words as sent. What they mean
/// depends on the model and on the output unit ([`super::Reading`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct DataFrame {
    /// Bytes 2-3: the distance, in the output unit (cm by default, mm when the
    /// unit was set to mm), or the model's invalid-reading code.
    pub distance: u16,
    /// Bytes 4-5: the return strength (TF-Luna calls it `Amp`).
    pub strength: u16,
    /// Bytes 6-7: the chip temperature on every model but the original TFmini,
    /// where byte 6 is the distance mode and byte 7 is reserved.
    pub aux: u16,
}

/// Why nine bytes are not a data frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum FrameError {
    #[error("data frame does not start with 59 59")]
    BadHeader,
    #[error("data frame checksum {found:#04x}, expected {expected:#04x}")]
    BadChecksum { expected: u8, found: u8 },
}

/// The original TFmini's byte 6 (TFmini datasheet 2017, via sensors.md §1.3):
/// the distance mode it chose for this reading.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TfminiDistanceMode {
    /// 0x02.
    Short,
    /// 0x07.
    Long,
    /// Any other value (firmwares that report integration time here).
    Other(u8),
}

impl DataFrame {
    /// Reads a frame, checking the header and the checksum.
    pub fn parse(bytes: &[u8; FRAME_LEN]) -> Result<Self, FrameError> {
        let [h0, h1, dl, dh, sl, sh, tl, th, found] = *bytes;
        if h0 != FRAME_HEADER || h1 != FRAME_HEADER {
            return Err(FrameError::BadHeader);
        }
        let expected = sum8(&bytes[..FRAME_LEN - 1]);
        if found != expected {
            return Err(FrameError::BadChecksum { expected, found });
        }
        Ok(Self {
            distance: u16::from_le_bytes([dl, dh]),
            strength: u16::from_le_bytes([sl, sh]),
            aux: u16::from_le_bytes([tl, th]),
        })
    }

    /// The frame as the device sends it, checksum included.
    pub fn encode(&self) -> [u8; FRAME_LEN] {
        let [dl, dh] = self.distance.to_le_bytes();
        let [sl, sh] = self.strength.to_le_bytes();
        let [tl, th] = self.aux.to_le_bytes();
        let mut bytes = [FRAME_HEADER, FRAME_HEADER, dl, dh, sl, sh, tl, th, 0];
        bytes[FRAME_LEN - 1] = sum8(&bytes[..FRAME_LEN - 1]);
        bytes
    }

    /// Bytes 6-7 read as the chip temperature: raw / 8 - 256 °C (TFmini Plus,
    /// TFmini-S, TF02-Pro and TF-Luna A05 manuals). Meaningless on the
    /// original TFmini.
    pub fn temperature_c(&self) -> f32 {
        f32::from(self.aux) / 8.0 - 256.0
    }

    /// Byte 6 read as the original TFmini's distance mode.
    pub fn tfmini_distance_mode(&self) -> TfminiDistanceMode {
        match self.aux.to_le_bytes()[0] {
            0x02 => TfminiDistanceMode::Short,
            0x07 => TfminiDistanceMode::Long,
            other => TfminiDistanceMode::Other(other),
        }
    }
}
