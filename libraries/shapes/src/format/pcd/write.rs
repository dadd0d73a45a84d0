//! Writing point clouds as PCD v0.7, with the header PCL's `PCDWriter` writes:
//! fields `x y z` and, when given, `intensity`, each `F 4` (PCL's
//! `pcl::PointXYZ` / `pcl::PointXYZI` without their padding), an unorganised
//! cloud (`HEIGHT 1`) and the identity `VIEWPOINT`.

use super::lzf;
use super::PcdEncoding;
use crate::format::point_rows::{per_point, push_records, Column};
use crate::format::FormatError;

/// A PCD file of `points` and, when `intensity` holds exactly one value per
/// point, their intensity (otherwise it is left out). ASCII numbers use the
/// shortest text that reads back to the same f32. Only `binary_compressed`
/// can fail: its body holds at most 2^31 - 1 uncompressed bytes (the limit of
/// the reader; about 134 million points with intensity).
pub fn write_pcd(
    points: &[[f32; 3]],
    intensity: Option<&[f32]>,
    encoding: PcdEncoding,
) -> Result<Vec<u8>, FormatError> {
    let intensity = per_point(points, intensity);
    let mut out = header(points.len(), intensity.is_some(), encoding).into_bytes();
    let columns = intensity.map(Column::F32);
    match encoding {
        PcdEncoding::Ascii => push_records(&mut out, points, columns.as_slice(), true),
        PcdEncoding::Binary => push_records(&mut out, points, columns.as_slice(), false),
        PcdEncoding::BinaryCompressed => push_compressed(&mut out, points, intensity)?,
    }
    Ok(out)
}

fn header(points: usize, has_intensity: bool, encoding: PcdEncoding) -> String {
    let (fields, sizes, types, counts) = if has_intensity {
        ("x y z intensity", "4 4 4 4", "F F F F", "1 1 1 1")
    } else {
        ("x y z", "4 4 4", "F F F", "1 1 1")
    };
    format!(
        "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS {fields}\n\
         SIZE {sizes}\nTYPE {types}\nCOUNT {counts}\nWIDTH {points}\nHEIGHT 1\n\
         VIEWPOINT 0 0 0 1 0 0 0\nPOINTS {points}\nDATA {}\n",
        encoding.name()
    )
}

/// The field-major values (all x, all y, all z, all intensities), LZF
/// compressed after their compressed and uncompressed sizes.
fn push_compressed(
    out: &mut Vec<u8>,
    points: &[[f32; 3]],
    intensity: Option<&[f32]>,
) -> Result<(), FormatError> {
    let fields = 3 + usize::from(intensity.is_some());
    let size = points.len().saturating_mul(4 * fields);
    if size > lzf::MAX_UNCOMPRESSED {
        return Err(FormatError::PcdTooLargeToCompress {
            bytes: size,
            max: lzf::MAX_UNCOMPRESSED,
        });
    }
    let mut fields_first = Vec::with_capacity(size);
    for axis in 0..3 {
        points
            .iter()
            .for_each(|p| fields_first.extend_from_slice(&p[axis].to_le_bytes()));
    }
    intensity
        .into_iter()
        .flatten()
        .for_each(|v| fields_first.extend_from_slice(&v.to_le_bytes()));
    let compressed = lzf::compress(&fields_first);
    // Both sizes are below 2^31 (the compressed one is at most 33/32 of the other).
    out.extend_from_slice(&(compressed.len() as u32).to_le_bytes());
    out.extend_from_slice(&(fields_first.len() as u32).to_le_bytes());
    out.extend_from_slice(&compressed);
    Ok(())
}
