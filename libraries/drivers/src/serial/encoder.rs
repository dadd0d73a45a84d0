//! Scan -> serial frames: splits a scan into frames of at most
//! `points_per_frame` points, for the sensor simulator and the tests.

use super::crc32_trailer;
use super::header::{FrameHeader, PointEncoding, MAX_FRAME_POINTS};
use super::payload::write_payload;
use crate::{IngestError, Scan};

/// How scans are written. Intensity is sent exactly when the scan has it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SerialEncoder {
    pub encoding: PointEncoding,
    /// Points a frame carries (the last frame of a scan may carry fewer), 1..=1024.
    pub points_per_frame: usize,
}

impl Default for SerialEncoder {
    fn default() -> Self {
        Self {
            encoding: PointEncoding::F32Metres,
            points_per_frame: 256,
        }
    }
}

impl SerialEncoder {
    pub fn new(encoding: PointEncoding, points_per_frame: usize) -> Self {
        Self {
            encoding,
            points_per_frame,
        }
    }

    /// The frames of `scan`, each a complete byte string (an empty scan is one
    /// frame with no points). Fails on a value the encoding cannot carry, an
    /// intensity list of the wrong length, a bad `points_per_frame`, or a scan
    /// needing more than 65535 frames.
    pub fn frames(&self, scan: &Scan) -> Result<Vec<Vec<u8>>, IngestError> {
        if !(1..=MAX_FRAME_POINTS).contains(&self.points_per_frame) {
            return Err(IngestError::Oversize {
                what: "points per frame",
                found: self.points_per_frame,
                limit: MAX_FRAME_POINTS,
            });
        }
        if let Some(intensity) = &scan.intensity {
            if intensity.len() != scan.points.len() {
                return Err(IngestError::Malformed {
                    what: "scan",
                    reason: format!(
                        "{} intensities for {} points",
                        intensity.len(),
                        scan.points.len()
                    ),
                });
            }
        }
        let count = scan.points.len().div_ceil(self.points_per_frame).max(1);
        let frame_count = u16::try_from(count).map_err(|_| IngestError::Oversize {
            what: "frames in a scan",
            found: count,
            limit: u16::MAX.into(),
        })?;
        let mut frames = Vec::with_capacity(count);
        for index in 0..count {
            let first = index * self.points_per_frame;
            let last = (first + self.points_per_frame).min(scan.points.len());
            let header = FrameHeader {
                encoding: self.encoding,
                intensity: scan.intensity.is_some(),
                sequence: scan.sequence,
                stamp_ns: scan.stamp_ns,
                frame_index: index as u16,
                frame_count,
                points: (last - first) as u16,
            };
            let mut frame = Vec::with_capacity(header.frame_len());
            header.write(&mut frame);
            let intensity = scan.intensity.as_deref().map(|i| &i[first..last]);
            write_payload(
                self.encoding,
                &scan.points[first..last],
                intensity,
                first,
                &mut frame,
            )?;
            let crc = crc32_trailer(&frame);
            frame.extend_from_slice(&crc.to_le_bytes());
            frames.push(frame);
        }
        Ok(frames)
    }

    /// All frames of `scan`, back to back.
    pub fn encode(&self, scan: &Scan) -> Result<Vec<u8>, IngestError> {
        Ok(self.frames(scan)?.concat())
    }
}
