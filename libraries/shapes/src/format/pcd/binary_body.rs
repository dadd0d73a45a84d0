//! `binary` PCD bodies: one packed little-endian record per point, the fields in
//! header order with no gaps (PCL writes explicit `_` fields for padding). The
//! body must hold POINTS records; only zero bytes may follow them.

use super::check_padding;
use super::columns::{read_points as read_columns, Placement};
use super::header::Header;
use super::layout::{starts, PointLayout};
use crate::format::ply::PlyCloud;
use crate::format::FormatError;

/// Reads the points of a `binary` body.
pub fn read_points(
    bytes: &[u8],
    header: &Header,
    layout: &PointLayout,
) -> Result<PlyCloud, FormatError> {
    let body = bytes.get(header.body_offset..).unwrap_or_default();
    let stride = header.record_size;
    let complete = body.len() / stride;
    if complete < header.points {
        return Err(truncation(header, complete, body.len() - complete * stride));
    }
    // `complete >= points`, so the product does not overflow.
    check_padding(
        bytes,
        header.body_offset + header.points * stride,
        header.points,
    )?;
    let offsets = starts(&header.fields, |f| f.bytes);
    let place = |field: usize| Placement {
        base: offsets[field],
        stride,
    };
    read_columns(
        body,
        header.body_offset,
        header.points,
        &header.fields,
        layout,
        place,
    )
}

/// The error for a body that ends `remainder` bytes into the record of point
/// `point`: the field the end falls in, where it starts and what is left of it.
fn truncation(header: &Header, point: usize, remainder: usize) -> FormatError {
    let offsets = starts(&header.fields, |f| f.bytes);
    let cut = header
        .fields
        .iter()
        .zip(offsets)
        .find(|(field, start)| start + field.bytes > remainder);
    let record = header.body_offset + point * header.record_size;
    match cut {
        Some((field, start)) => FormatError::PcdTruncatedBody {
            point,
            field: field.name.clone(),
            needed: field.bytes,
            offset: record + start,
            available: remainder - start,
        },
        // `remainder` is less than the record size, so some field holds the cut.
        None => FormatError::PcdMissingPoints {
            expected: header.points,
            got: point,
            offset: record,
        },
    }
}
