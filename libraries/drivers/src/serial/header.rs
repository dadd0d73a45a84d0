//! The 24-byte frame header of the serial range-sensor protocol (see
//! `docs/sensor-protocols.md`, section 1): layout, point encodings, writing and validation.

use super::crc16::crc16;
use crate::IngestError;

/// The two bytes every frame starts with.
pub const SYNC: [u8; 2] = [0xA5, 0x5A];
/// The protocol version this build writes and reads.
pub const VERSION: u8 = 1;
/// Header bytes, including the header CRC-16.
pub const HEADER_LEN: usize = 24;
/// Trailer bytes: the CRC-32 of header and payload.
pub const TRAILER_LEN: usize = 4;
/// Most points one frame may carry.
pub const MAX_FRAME_POINTS: usize = 1024;

const FLAG_ENCODING: u8 = 0b0000_0011;
const FLAG_INTENSITY: u8 = 0b0000_0100;

/// How a frame stores its coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PointEncoding {
    /// x, y, z as little-endian f32 metres (12 bytes a point).
    #[default]
    F32Metres,
    /// x, y, z as little-endian i32 millimetres (12 bytes a point, ±2147 km).
    I32Millimetres,
    /// x, y, z as little-endian i16 millimetres (6 bytes a point, ±32.767 m).
    I16Millimetres,
}

impl PointEncoding {
    /// The two flag bits of this encoding.
    pub fn bits(self) -> u8 {
        match self {
            Self::F32Metres => 0,
            Self::I32Millimetres => 1,
            Self::I16Millimetres => 2,
        }
    }

    pub fn from_bits(bits: u8) -> Option<Self> {
        match bits {
            0 => Some(Self::F32Metres),
            1 => Some(Self::I32Millimetres),
            2 => Some(Self::I16Millimetres),
            _ => None,
        }
    }

    /// Bytes of one point's coordinates.
    pub fn point_bytes(self) -> usize {
        match self {
            Self::F32Metres | Self::I32Millimetres => 12,
            Self::I16Millimetres => 6,
        }
    }
}

/// A decoded, validated frame header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameHeader {
    pub encoding: PointEncoding,
    /// Whether each point also carries a u16 intensity.
    pub intensity: bool,
    pub sequence: u32,
    pub stamp_ns: u64,
    /// This frame's position in its scan, from 0.
    pub frame_index: u16,
    /// Frames in the scan (at least 1).
    pub frame_count: u16,
    /// Points in this frame (at most [`MAX_FRAME_POINTS`]).
    pub points: u16,
}

impl FrameHeader {
    /// Payload bytes: the points, then their intensities.
    pub fn payload_len(&self) -> usize {
        let per_point = self.encoding.point_bytes() + if self.intensity { 2 } else { 0 };
        usize::from(self.points) * per_point
    }

    /// Whole frame bytes: header, payload and CRC-32.
    pub fn frame_len(&self) -> usize {
        HEADER_LEN + self.payload_len() + TRAILER_LEN
    }

    /// Appends the 24 header bytes, header CRC included.
    pub fn write(&self, out: &mut Vec<u8>) {
        let start = out.len();
        let flags = self.encoding.bits() | if self.intensity { FLAG_INTENSITY } else { 0 };
        out.extend_from_slice(&SYNC);
        out.push(VERSION);
        out.push(flags);
        out.extend_from_slice(&self.sequence.to_le_bytes());
        out.extend_from_slice(&self.stamp_ns.to_le_bytes());
        out.extend_from_slice(&self.frame_index.to_le_bytes());
        out.extend_from_slice(&self.frame_count.to_le_bytes());
        out.extend_from_slice(&self.points.to_le_bytes());
        let crc = crc16(&out[start..]);
        out.extend_from_slice(&crc.to_le_bytes());
    }

    /// Validates and decodes the first [`HEADER_LEN`] bytes of `bytes`, which must
    /// start with [`SYNC`]. Checks, in order: header CRC, version, flags, frame
    /// index/count, point count.
    pub fn parse(bytes: &[u8]) -> Result<Self, IngestError> {
        let Some(h) = bytes.get(..HEADER_LEN) else {
            return Err(IngestError::Truncated {
                got: bytes.len(),
                expected: HEADER_LEN,
            });
        };
        debug_assert_eq!(h[..2], SYNC);
        let found = u16::from_le_bytes([h[22], h[23]]);
        let computed = crc16(&h[..22]);
        if found != computed {
            return Err(IngestError::BadHeaderCrc { found, computed });
        }
        if h[2] != VERSION {
            return Err(IngestError::Version {
                found: h[2],
                expected: VERSION,
            });
        }
        let flags = h[3];
        let encoding = PointEncoding::from_bits(flags & FLAG_ENCODING);
        let Some(encoding) = encoding.filter(|_| flags & !(FLAG_ENCODING | FLAG_INTENSITY) == 0)
        else {
            return Err(IngestError::Malformed {
                what: "serial frame header",
                reason: format!("unknown flags {flags:#04x}"),
            });
        };
        let u16_at = |i: usize| u16::from_le_bytes([h[i], h[i + 1]]);
        let header = Self {
            encoding,
            intensity: flags & FLAG_INTENSITY != 0,
            sequence: u32::from_le_bytes([h[4], h[5], h[6], h[7]]),
            stamp_ns: u64::from_le_bytes(h[8..16].try_into().expect("8 bytes")),
            frame_index: u16_at(16),
            frame_count: u16_at(18),
            points: u16_at(20),
        };
        if header.frame_index >= header.frame_count {
            return Err(IngestError::Malformed {
                what: "serial frame header",
                reason: format!(
                    "frame index {} not below frame count {}",
                    header.frame_index, header.frame_count
                ),
            });
        }
        if usize::from(header.points) > MAX_FRAME_POINTS {
            return Err(IngestError::Oversize {
                what: "points in a frame",
                found: header.points.into(),
                limit: MAX_FRAME_POINTS,
            });
        }
        Ok(header)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header() -> FrameHeader {
        FrameHeader {
            encoding: PointEncoding::I16Millimetres,
            intensity: true,
            sequence: 0xDEAD_BEEF,
            stamp_ns: 1_700_000_000_123_456_789,
            frame_index: 2,
            frame_count: 3,
            points: 10,
        }
    }

    #[test]
    fn writes_the_documented_layout_and_reads_it_back() {
        let mut bytes = Vec::new();
        header().write(&mut bytes);
        assert_eq!(bytes.len(), HEADER_LEN);
        assert_eq!(&bytes[..4], &[0xA5, 0x5A, 1, 0b110]);
        assert_eq!(&bytes[4..8], &0xDEAD_BEEFu32.to_le_bytes());
        assert_eq!(&bytes[20..22], &10u16.to_le_bytes());
        assert_eq!(FrameHeader::parse(&bytes), Ok(header()));
        assert_eq!(header().payload_len(), 10 * 8);
        assert_eq!(header().frame_len(), 24 + 80 + 4);
    }

    #[test]
    fn every_header_fault_is_named() {
        let write = |h: FrameHeader| {
            let mut b = Vec::new();
            h.write(&mut b);
            b
        };
        let mut bytes = write(header());
        bytes[9] ^= 1;
        assert!(matches!(
            FrameHeader::parse(&bytes),
            Err(IngestError::BadHeaderCrc { .. })
        ));
        let refresh = |b: &mut Vec<u8>| {
            let crc = crc16(&b[..22]);
            b[22..24].copy_from_slice(&crc.to_le_bytes());
        };
        let mut bytes = write(header());
        bytes[2] = 9;
        refresh(&mut bytes);
        assert!(matches!(
            FrameHeader::parse(&bytes),
            Err(IngestError::Version { found: 9, .. })
        ));
        for flags in [0b11, 0b1000_0000] {
            let mut bytes = write(header());
            bytes[3] = flags;
            refresh(&mut bytes);
            assert!(matches!(
                FrameHeader::parse(&bytes),
                Err(IngestError::Malformed { .. })
            ));
        }
        let bad_index = FrameHeader {
            frame_index: 3,
            ..header()
        };
        assert!(matches!(
            FrameHeader::parse(&write(bad_index)),
            Err(IngestError::Malformed { .. })
        ));
        let huge = FrameHeader {
            points: 1025,
            ..header()
        };
        assert!(matches!(
            FrameHeader::parse(&write(huge)),
            Err(IngestError::Oversize { found: 1025, .. })
        ));
        assert!(matches!(
            FrameHeader::parse(&write(header())[..10]),
            Err(IngestError::Truncated { .. })
        ));
    }
}
