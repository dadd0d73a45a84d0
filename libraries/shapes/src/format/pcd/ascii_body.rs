//! `ascii` PCD bodies: one line per point holding every field's values in header
//! order (a field of COUNT n takes n values). A line with another number of
//! values is an error naming its line and point, as is a line after the last
//! point. Blank lines are skipped.

use super::header::Header;
use super::layout::{starts, PointLayout, Slot};
use super::push_point;
use crate::format::ply::PlyCloud;
use crate::format::text_lines::TextLines;
use crate::format::FormatError;

/// Reads the points of an `ascii` body.
pub fn read_points(
    bytes: &[u8],
    header: &Header,
    layout: &PointLayout,
) -> Result<PlyCloud, FormatError> {
    let token_index = starts(&header.fields, |f| f.count);
    let values_per_point: usize = header.fields.iter().map(|f| f.count).sum();
    let mut lines = TextLines::new(bytes, header.body_offset, header.body_line);
    // A value takes at least 2 bytes ("0 "): the count alone does not size the cloud.
    let body_len = bytes.len().saturating_sub(header.body_offset);
    let capacity = header
        .points
        .min(body_len / values_per_point.saturating_mul(2));
    let mut cloud = PlyCloud::with_capacity(capacity, layout.intensity.is_some());
    for point in 0..header.points {
        let not_text = |line| bad_record(line, point, "the line is not UTF-8 text".into());
        let Some((line, text)) = lines.next_non_blank().map_err(not_text)? else {
            return Err(FormatError::PcdMissingPoints {
                expected: header.points,
                got: point,
                offset: lines.offset(),
            });
        };
        let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
        if tokens.len() != values_per_point {
            let reason = format!(
                "a point has {values_per_point} values, this line has {}",
                tokens.len()
            );
            return Err(bad_record(line, point, reason));
        }
        let value = |slot: Slot| {
            // The length check above guarantees a token for every field.
            let token = token_index
                .get(slot.field)
                .and_then(|&i| tokens.get(i))
                .copied()
                .unwrap_or_default();
            slot.ty
                .parse_text(token)
                .ok_or_else(|| FormatError::PcdBadAsciiNumber {
                    line,
                    point,
                    field: header.fields[slot.field].name.clone(),
                    token: token.into(),
                })
        };
        let [x, y, z] = layout.xyz;
        let intensity = layout.intensity.map(value).transpose()?;
        push_point(&mut cloud, [value(x)?, value(y)?, value(z)?], intensity);
    }
    let extra = match lines.next_non_blank() {
        Ok(None) => None,
        Ok(Some((line, _))) | Err(line) => Some(line),
    };
    if let Some(line) = extra {
        let reason = format!("a line after the last of the {} points", header.points);
        return Err(bad_record(line, header.points, reason));
    }
    Ok(cloud)
}

fn bad_record(line: usize, point: usize, reason: String) -> FormatError {
    FormatError::PcdBadAsciiRecord {
        line,
        point,
        reason,
    }
}
