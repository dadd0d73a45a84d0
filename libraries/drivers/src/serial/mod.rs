//! The serial range-sensor protocol (`docs/sensor-protocols.md` §1): framed binary scans with
//! a sync word, a CRC-16 guarded header and a CRC-32 trailer; an encoder and a
//! streaming, resynchronising decoder.

mod assembler;
mod crc16;
mod decoder;
mod encoder;
mod header;
mod payload;
#[cfg(test)]
mod tests;

pub use crc16::crc16;
pub use decoder::{DecoderConfig, SerialScanDecoder};
pub use encoder::SerialEncoder;
pub use header::{
    FrameHeader, PointEncoding, HEADER_LEN, MAX_FRAME_POINTS, SYNC, TRAILER_LEN, VERSION,
};

/// The frame trailer: CRC-32 (IEEE) of header and payload.
fn crc32_trailer(bytes: &[u8]) -> u32 {
    crc32fast::hash(bytes)
}
