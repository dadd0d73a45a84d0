//! The CAN range-sensor protocol (`docs/sensor-protocols.md` §2): four message ids from a
//! base id, their 8-byte layouts, and the encoder (scan -> frames).

use super::frame::CanFrame;
use crate::{IngestError, Scan};

/// Protocol version carried in the START frame.
pub const CAN_VERSION: u8 = 1;
/// Most points one CAN scan can carry (point indices are u16).
pub const MAX_CAN_POINTS: usize = u16::MAX as usize;

/// The four message types, at `base_id + offset`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CanMessage {
    /// seq u16, point count u16, version u8, flags u8 (0), reserved u16 (0).
    Start = 0,
    /// stamp_ns u64.
    Stamp = 1,
    /// x, y, z as i16 millimetres, point index u16.
    Point = 2,
    /// seq u16, point count u16, CRC-32 of START, STAMP and POINT data in order.
    End = 3,
}

/// Where a sensor sits on the bus.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CanSensorConfig {
    /// Id of the START message; STAMP, POINT and END follow it.
    pub base_id: u32,
    /// Whether the sensor uses 29-bit identifiers.
    pub extended: bool,
}

impl Default for CanSensorConfig {
    fn default() -> Self {
        Self {
            base_id: 0x300,
            extended: false,
        }
    }
}

impl CanSensorConfig {
    pub fn id(&self, message: CanMessage) -> u32 {
        self.base_id + message as u32
    }

    /// Which protocol message `frame` is, if it is one of this sensor's.
    pub fn classify(&self, frame: &CanFrame) -> Option<CanMessage> {
        if frame.extended != self.extended || frame.remote {
            return None;
        }
        match frame.id.checked_sub(self.base_id)? {
            0 => Some(CanMessage::Start),
            1 => Some(CanMessage::Stamp),
            2 => Some(CanMessage::Point),
            3 => Some(CanMessage::End),
            _ => None,
        }
    }

    /// The frames of `scan`: START, STAMP, one POINT per point, END. The
    /// sequence is sent modulo 2^16; intensity is not carried.
    pub fn encode(&self, scan: &Scan) -> Result<Vec<CanFrame>, IngestError> {
        let count = scan.points.len();
        if count > MAX_CAN_POINTS {
            return Err(IngestError::Oversize {
                what: "points in a CAN scan",
                found: count,
                limit: MAX_CAN_POINTS,
            });
        }
        let seq = (scan.sequence as u16).to_le_bytes();
        let n = (count as u16).to_le_bytes();
        let frame = |message, data: [u8; 8]| CanFrame::new(self.id(message), self.extended, &data);
        let mut frames = Vec::with_capacity(count + 3);
        frames.push(frame(
            CanMessage::Start,
            [seq[0], seq[1], n[0], n[1], CAN_VERSION, 0, 0, 0],
        )?);
        frames.push(frame(CanMessage::Stamp, scan.stamp_ns.to_le_bytes())?);
        for (index, point) in scan.points.iter().enumerate() {
            let mut data = [0u8; 8];
            for (axis, &value) in point.iter().enumerate() {
                let field = ["x", "y", "z"][axis];
                if !value.is_finite() {
                    return Err(IngestError::NonFinite { field, index });
                }
                let mm = (f64::from(value) * 1000.0).round();
                if !(f64::from(i16::MIN)..=f64::from(i16::MAX)).contains(&mm) {
                    return Err(IngestError::OutOfRange {
                        field,
                        index,
                        value,
                    });
                }
                data[axis * 2..axis * 2 + 2].copy_from_slice(&(mm as i16).to_le_bytes());
            }
            data[6..].copy_from_slice(&(index as u16).to_le_bytes());
            frames.push(frame(CanMessage::Point, data)?);
        }
        let crc = scan_checksum(&frames);
        let c = crc.to_le_bytes();
        frames.push(frame(
            CanMessage::End,
            [seq[0], seq[1], n[0], n[1], c[0], c[1], c[2], c[3]],
        )?);
        Ok(frames)
    }
}

/// The END checksum: CRC-32 (IEEE) over the 8 data bytes of START, STAMP and
/// every POINT frame, in order.
pub fn scan_checksum(frames: &[CanFrame]) -> u32 {
    let mut hasher = crc32fast::Hasher::new();
    for f in frames {
        hasher.update(&f.data);
    }
    hasher.finalize()
}

/// Decodes a POINT frame's data: metres and index.
pub fn point_of(data: &[u8; 8]) -> ([f32; 3], u16) {
    let mm = |i: usize| f32::from(i16::from_le_bytes([data[i], data[i + 1]])) / 1000.0;
    (
        [mm(0), mm(2), mm(4)],
        u16::from_le_bytes([data[6], data[7]]),
    )
}
