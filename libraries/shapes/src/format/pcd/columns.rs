//! Points whose values sit at fixed strides in a byte buffer: packed records
//! (`binary`: a field at its offset in every record) or field-major blocks
//! (`binary_compressed` once decompressed: all values of a field in a row).

use super::fields::Field;
use super::layout::{PointLayout, Slot};
use super::push_point;
use crate::format::ply::PlyCloud;
use crate::format::FormatError;

/// Where point `i`'s value of a field starts: `base + i * stride`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Placement {
    pub base: usize,
    pub stride: usize,
}

/// Reads `points` points from `data`, with `place(field index)` giving where
/// each field's values are. The caller has checked that `data` holds every
/// value; a value that still falls outside is reported as truncation, with
/// offsets counted from `data_offset`.
pub fn read_points(
    data: &[u8],
    data_offset: usize,
    points: usize,
    fields: &[Field],
    layout: &PointLayout,
    place: impl Fn(usize) -> Placement,
) -> Result<PlyCloud, FormatError> {
    let column = |slot: Slot| (slot, place(slot.field));
    let xyz = layout.xyz.map(column);
    let intensity = layout.intensity.map(column);
    let value = |(slot, at): (Slot, Placement), point: usize| {
        let offset = point
            .checked_mul(at.stride)
            .and_then(|o| o.checked_add(at.base));
        offset
            .and_then(|o| data.get(o..))
            .and_then(|bytes| slot.ty.decode(bytes, false))
            .ok_or_else(|| FormatError::PcdTruncatedBody {
                point,
                field: fields[slot.field].name.clone(),
                needed: slot.ty.size(),
                offset: data_offset.saturating_add(offset.unwrap_or(usize::MAX)),
                available: data.len().saturating_sub(offset.unwrap_or(usize::MAX)),
            })
    };
    let mut cloud = PlyCloud::with_capacity(points, intensity.is_some());
    for point in 0..points {
        let [x, y, z] = xyz;
        let coordinates = [value(x, point)?, value(y, point)?, value(z, point)?];
        let intensity = intensity.map(|i| value(i, point)).transpose()?;
        push_point(&mut cloud, coordinates, intensity);
    }
    Ok(cloud)
}
