//! Binary PLY bodies (either byte order): elements before `vertex` are walked
//! record by record (their list properties have per-record lengths), then the
//! vertices are read; whatever follows them is not needed and not read.

use super::header::{Element, Header, PropertyKind};
use super::layout::{Slot, VertexLayout};
use super::PlyCloud;
use crate::format::scalar::ScalarType;
use crate::format::FormatError;

/// Why a record could not be walked.
pub(super) enum RecordError {
    /// The bytes end inside the record.
    Truncated,
    /// A list length that is negative or not an integer.
    BadListLength(f64),
}

/// Reads the vertex element of a binary PLY whose header is `header`.
pub fn read_vertices(
    bytes: &[u8],
    header: &Header,
    layout: &VertexLayout,
    big_endian: bool,
) -> Result<PlyCloud, FormatError> {
    let vertex = &header.elements[layout.element];
    let truncated = |got, offset| FormatError::PlyTruncatedBody {
        expected: vertex.count,
        got,
        offset,
    };
    let mut pos = header.body_offset;
    for element in &header.elements[..layout.element] {
        pos = skip_element(bytes, pos, element, big_endian).map_err(|(record, e)| match e {
            RecordError::Truncated => truncated(0, pos),
            RecordError::BadListLength(length) => FormatError::PlyBadListLength {
                element: element.name.clone(),
                record,
                length,
            },
        })?;
    }
    match vertex.fixed_record_size() {
        Some(stride) => read_fixed_records(bytes, pos, vertex, stride, layout, big_endian),
        None => read_varying_records(bytes, pos, vertex, layout, big_endian),
    }
}

/// The position after all records of `element` from `pos`, or the failing record
/// and why. Fixed-size records are skipped in one step, so a huge count of empty
/// records costs nothing.
pub(super) fn skip_element(
    bytes: &[u8],
    mut pos: usize,
    element: &Element,
    big_endian: bool,
) -> Result<usize, (usize, RecordError)> {
    if let Some(size) = element.fixed_record_size() {
        let end = size
            .checked_mul(element.count)
            .and_then(|span| pos.checked_add(span));
        return end
            .filter(|&end| end <= bytes.len())
            .ok_or((0, RecordError::Truncated));
    }
    // Every record holds a list length of at least one byte: the loop is bounded
    // by the body size.
    for record in 0..element.count {
        pos = walk_record(bytes, pos, element, big_endian, |_, _| {}, |_, _, _| {})
            .map_err(|e| (record, e))?;
    }
    Ok(pos)
}

/// The common case: every vertex record has the same size, so the body length is
/// checked once and each wanted property sits at a fixed offset in its record.
fn read_fixed_records(
    bytes: &[u8],
    pos: usize,
    vertex: &Element,
    stride: usize,
    layout: &VertexLayout,
    big_endian: bool,
) -> Result<PlyCloud, FormatError> {
    let count = vertex.count;
    let body = bytes.get(pos..).unwrap_or_default();
    let complete = body.len() / stride;
    if complete < count {
        let offset = pos + complete * stride;
        return Err(FormatError::PlyTruncatedBody {
            expected: count,
            got: complete,
            offset,
        });
    }
    let offsets = vertex.record_offsets();
    let at = |slot: Slot| (slot.ty, offsets.get(slot.index).copied().unwrap_or(stride));
    let [x, y, z] = layout.xyz.map(at);
    let intensity = layout.intensity.map(at);
    let mut cloud = PlyCloud::with_capacity(count, intensity.is_some());
    for (record, data) in body.chunks_exact(stride).take(count).enumerate() {
        // Offsets lie inside the record by construction; a miss is reported as
        // truncation rather than trusted.
        let value = |(ty, offset): (ScalarType, usize)| {
            data.get(offset..)
                .and_then(|b| ty.decode(b, big_endian))
                .ok_or(FormatError::PlyTruncatedBody {
                    expected: count,
                    got: record,
                    offset: pos + record * stride,
                })
        };
        let intensity = intensity.map(value).transpose()?;
        cloud.push(
            [value(x)? as f32, value(y)? as f32, value(z)? as f32],
            intensity.map(|i| i as f32),
        );
    }
    Ok(cloud)
}

/// Vertex records with list properties: walked one by one.
fn read_varying_records(
    bytes: &[u8],
    mut pos: usize,
    vertex: &Element,
    layout: &VertexLayout,
    big_endian: bool,
) -> Result<PlyCloud, FormatError> {
    let mut cloud = PlyCloud::with_capacity(
        vertex.count.min(bytes.len() / 3),
        layout.intensity.is_some(),
    );
    let mut values = [0.0f64; 4];
    for record in 0..vertex.count {
        let store = |index: usize, value: f64| {
            if let Some(k) = layout.slots().position(|s| s.index == index) {
                values[k] = value;
            }
        };
        let walked = walk_record(bytes, pos, vertex, big_endian, store, |_, _, _| {});
        pos = walked.map_err(|e| match e {
            RecordError::Truncated => FormatError::PlyTruncatedBody {
                expected: vertex.count,
                got: record,
                offset: pos,
            },
            RecordError::BadListLength(length) => FormatError::PlyBadListLength {
                element: vertex.name.clone(),
                record,
                length,
            },
        })?;
        let [x, y, z, intensity] = values.map(|v| v as f32);
        cloud.push([x, y, z], layout.intensity.map(|_| intensity));
    }
    Ok(cloud)
}

/// Walks one record starting at `pos`, handing each scalar property's index and
/// value to `store` and each list property's index, item type and item bytes
/// (exactly `length * item.size()` of them) to `list`; returns the position just
/// after the record.
pub(super) fn walk_record(
    bytes: &[u8],
    mut pos: usize,
    element: &Element,
    big_endian: bool,
    mut store: impl FnMut(usize, f64),
    mut list: impl FnMut(usize, ScalarType, &[u8]),
) -> Result<usize, RecordError> {
    for (index, property) in element.properties.iter().enumerate() {
        let data = bytes.get(pos..).ok_or(RecordError::Truncated)?;
        match property.kind {
            PropertyKind::Scalar(ty) => {
                store(
                    index,
                    ty.decode(data, big_endian).ok_or(RecordError::Truncated)?,
                );
                pos += ty.size();
            }
            PropertyKind::List { count, item } => {
                let length = count
                    .decode(data, big_endian)
                    .ok_or(RecordError::Truncated)?;
                // Integer count types decode to integral values; only the sign can be wrong.
                if length < 0.0 {
                    return Err(RecordError::BadListLength(length));
                }
                let span = (length as usize)
                    .checked_mul(item.size())
                    .ok_or(RecordError::BadListLength(length))?;
                let start = pos + count.size();
                pos = start.checked_add(span).ok_or(RecordError::Truncated)?;
                list(
                    index,
                    item,
                    bytes.get(start..pos).ok_or(RecordError::Truncated)?,
                );
            }
        }
    }
    if pos > bytes.len() {
        return Err(RecordError::Truncated);
    }
    Ok(pos)
}
