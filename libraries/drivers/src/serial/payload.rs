//! A frame's payload: its points in the header's encoding, then (if flagged) one
//! little-endian u16 intensity per point. Writing checks ranges, reading checks
//! that every coordinate is finite.

use super::header::{FrameHeader, PointEncoding};
use crate::IngestError;

/// Appends the payload of `points` (and `intensity`, when given) to `out`.
/// `first_index` is the scan index of `points[0]`, for error messages.
pub fn write_payload(
    encoding: PointEncoding,
    points: &[[f32; 3]],
    intensity: Option<&[f32]>,
    first_index: usize,
    out: &mut Vec<u8>,
) -> Result<(), IngestError> {
    const AXES: [&str; 3] = ["x", "y", "z"];
    for (offset, point) in points.iter().enumerate() {
        let index = first_index + offset;
        for (axis, &value) in point.iter().enumerate() {
            if !value.is_finite() {
                return Err(IngestError::NonFinite {
                    field: AXES[axis],
                    index,
                });
            }
            let range = |ok: bool| {
                ok.then_some(()).ok_or(IngestError::OutOfRange {
                    field: AXES[axis],
                    index,
                    value,
                })
            };
            let mm = (f64::from(value) * 1000.0).round();
            match encoding {
                PointEncoding::F32Metres => out.extend_from_slice(&value.to_le_bytes()),
                PointEncoding::I32Millimetres => {
                    range(mm >= f64::from(i32::MIN) && mm <= f64::from(i32::MAX))?;
                    out.extend_from_slice(&(mm as i32).to_le_bytes());
                }
                PointEncoding::I16Millimetres => {
                    range(mm >= f64::from(i16::MIN) && mm <= f64::from(i16::MAX))?;
                    out.extend_from_slice(&(mm as i16).to_le_bytes());
                }
            }
        }
    }
    for (offset, &value) in intensity.unwrap_or(&[]).iter().enumerate() {
        let index = first_index + offset;
        if !value.is_finite() {
            return Err(IngestError::NonFinite {
                field: "intensity",
                index,
            });
        }
        let raw = value.round();
        if !(0.0..=f32::from(u16::MAX)).contains(&raw) {
            return Err(IngestError::OutOfRange {
                field: "intensity",
                index,
                value,
            });
        }
        out.extend_from_slice(&(raw as u16).to_le_bytes());
    }
    Ok(())
}

/// Decodes a payload of exactly `header.payload_len()` bytes, appending to
/// `points` and (when the header says so) `intensity`. On error nothing is
/// appended. A non-finite f32 coordinate is an error.
pub fn read_payload(
    header: &FrameHeader,
    payload: &[u8],
    points: &mut Vec<[f32; 3]>,
    intensity: &mut Vec<f32>,
) -> Result<(), IngestError> {
    debug_assert_eq!(payload.len(), header.payload_len());
    let n = usize::from(header.points);
    let size = header.encoding.point_bytes();
    let (coords, intensities) = payload.split_at(n * size);
    let before = points.len();
    for (index, chunk) in coords.chunks_exact(size).enumerate() {
        let point = match header.encoding {
            PointEncoding::F32Metres => {
                let f = |i: usize| f32::from_le_bytes(chunk[i..i + 4].try_into().expect("4"));
                [f(0), f(4), f(8)]
            }
            PointEncoding::I32Millimetres => {
                let f = |i: usize| {
                    let mm = i32::from_le_bytes(chunk[i..i + 4].try_into().expect("4"));
                    (f64::from(mm) / 1000.0) as f32
                };
                [f(0), f(4), f(8)]
            }
            PointEncoding::I16Millimetres => {
                let f = |i: usize| f32::from(i16::from_le_bytes([chunk[i], chunk[i + 1]])) / 1000.0;
                [f(0), f(2), f(4)]
            }
        };
        if let Some(axis) = point.iter().position(|v| !v.is_finite()) {
            points.truncate(before);
            return Err(IngestError::NonFinite {
                field: ["x", "y", "z"][axis],
                index,
            });
        }
        points.push(point);
    }
    if header.intensity {
        intensity.extend(
            intensities
                .chunks_exact(2)
                .map(|c| f32::from(u16::from_le_bytes([c[0], c[1]]))),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(encoding: PointEncoding, points: u16, intensity: bool) -> FrameHeader {
        FrameHeader {
            encoding,
            intensity,
            sequence: 0,
            stamp_ns: 0,
            frame_index: 0,
            frame_count: 1,
            points,
        }
    }

    #[test]
    fn every_encoding_round_trips_within_its_resolution() {
        let pts = [[1.234f32, -5.678, 0.0], [-32.767, 32.767, 0.001]];
        for (encoding, tol) in [
            (PointEncoding::F32Metres, 0.0),
            (PointEncoding::I32Millimetres, 5e-4),
            (PointEncoding::I16Millimetres, 5e-4),
        ] {
            let mut bytes = Vec::new();
            write_payload(encoding, &pts, Some(&[3.0, 65535.0]), 0, &mut bytes).unwrap();
            let h = header(encoding, 2, true);
            assert_eq!(bytes.len(), h.payload_len());
            let (mut back, mut inten) = (Vec::new(), Vec::new());
            read_payload(&h, &bytes, &mut back, &mut inten).unwrap();
            for (a, b) in pts.iter().flatten().zip(back.iter().flatten()) {
                assert!((a - b).abs() <= tol, "{encoding:?} {a} {b}");
            }
            assert_eq!(inten, vec![3.0, 65535.0]);
        }
    }

    #[test]
    fn writing_rejects_what_the_encoding_cannot_carry() {
        let mut out = Vec::new();
        let e = write_payload(
            PointEncoding::I16Millimetres,
            &[[0.0, 33.0, 0.0]],
            None,
            5,
            &mut out,
        );
        assert!(matches!(
            e,
            Err(IngestError::OutOfRange {
                field: "y",
                index: 5,
                ..
            })
        ));
        let e = write_payload(
            PointEncoding::F32Metres,
            &[[f32::NAN, 0.0, 0.0]],
            None,
            0,
            &mut out,
        );
        assert!(matches!(e, Err(IngestError::NonFinite { field: "x", .. })));
        let e = write_payload(
            PointEncoding::F32Metres,
            &[[0.0; 3]],
            Some(&[-2.0]),
            0,
            &mut out,
        );
        assert!(matches!(
            e,
            Err(IngestError::OutOfRange {
                field: "intensity",
                ..
            })
        ));
        let e = write_payload(
            PointEncoding::F32Metres,
            &[[0.0; 3]],
            Some(&[f32::INFINITY]),
            0,
            &mut out,
        );
        assert!(matches!(
            e,
            Err(IngestError::NonFinite {
                field: "intensity",
                ..
            })
        ));
    }

    #[test]
    fn reading_rejects_non_finite_coordinates_and_appends_nothing() {
        let mut bytes = Vec::new();
        for v in [1.0f32, 2.0, 3.0, 4.0, f32::INFINITY, 6.0] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let mut points = vec![[9.0; 3]];
        let e = read_payload(
            &header(PointEncoding::F32Metres, 2, false),
            &bytes,
            &mut points,
            &mut Vec::new(),
        );
        assert!(matches!(
            e,
            Err(IngestError::NonFinite {
                field: "y",
                index: 1
            })
        ));
        assert_eq!(points, vec![[9.0; 3]]);
    }
}
