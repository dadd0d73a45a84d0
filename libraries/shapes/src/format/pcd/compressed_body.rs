//! `binary_compressed` PCD bodies (PCL 1.5 on): the compressed and the
//! uncompressed size (u32 little endian each), then that many bytes of LZF.
//! Decompressed, the data is field-major: every point's bytes of the first
//! field, then every point's bytes of the second, and so on, `_` padding fields
//! included. Sizes are checked before anything is allocated: the uncompressed
//! size must be exactly POINTS x record size, at most 2^31 - 1 bytes, and no
//! more than LZF can expand the compressed bytes to. Only zero bytes may follow
//! the compressed data.

use super::check_padding;
use super::columns::{read_points as read_columns, Placement};
use super::header::Header;
use super::layout::{starts, PointLayout};
use super::lzf;
use crate::format::ply::PlyCloud;
use crate::format::FormatError;

/// Reads the points of a `binary_compressed` body.
pub fn read_points(
    bytes: &[u8],
    header: &Header,
    layout: &PointLayout,
) -> Result<PlyCloud, FormatError> {
    let start = header.body_offset;
    let bad = |offset: usize, reason: String| FormatError::PcdBadCompressedBody { offset, reason };
    let size_at = |offset: usize| {
        let rest = bytes.get(offset..).unwrap_or_default();
        let word = &rest[..rest.len().min(4)];
        let available = word.len();
        word.try_into().map(u32::from_le_bytes).map_err(|_| {
            let reason = format!("a size needs 4 bytes, only {available} remain");
            bad(offset, reason)
        })
    };
    let compressed = size_at(start)? as usize;
    let uncompressed = size_at(start + 4)? as usize;
    let expected = header.points.checked_mul(header.record_size);
    if expected != Some(uncompressed) {
        let reason = format!(
            "the uncompressed size is {uncompressed} bytes, but POINTS {} x {} bytes per point is {}",
            header.points,
            header.record_size,
            expected.map_or("beyond any size".into(), |e| e.to_string())
        );
        return Err(bad(start + 4, reason));
    }
    if uncompressed > lzf::MAX_UNCOMPRESSED {
        let reason = format!(
            "the uncompressed size {uncompressed} is beyond the {} bytes this reader decompresses",
            lzf::MAX_UNCOMPRESSED
        );
        return Err(bad(start + 4, reason));
    }
    let data_start = start + 8;
    let available = bytes.len() - data_start;
    if compressed > available {
        let reason = format!(
            "the compressed size {compressed} reaches beyond the file ({available} bytes remain)"
        );
        return Err(bad(start, reason));
    }
    check_padding(bytes, data_start + compressed, header.points)?;
    if uncompressed > compressed.saturating_mul(lzf::MAX_RATIO) {
        let reason = format!(
            "{compressed} compressed bytes cannot hold {uncompressed} (LZF expands at most {} times)",
            lzf::MAX_RATIO
        );
        return Err(bad(start, reason));
    }
    let data = lzf::decompress(&bytes[data_start..data_start + compressed], uncompressed)
        .map_err(|e| bad(data_start, e))?;
    let blocks = starts(&header.fields, |f| f.bytes);
    // Each block start is at most the uncompressed size, checked above.
    let place = |field: usize| Placement {
        base: blocks[field] * header.points,
        stride: header.fields[field].bytes,
    };
    read_columns(&data, 0, header.points, &header.fields, layout, place)
}
