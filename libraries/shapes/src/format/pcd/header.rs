//! The PCD header (PCL's `pcd_io`, format v0.7 and the older v0.5/v0.6): one
//! `KEYWORD values...` line each, `#` comment lines anywhere, up to the `DATA`
//! line after which the body starts. Keywords may come in any order; each may
//! appear once.

use super::fields::{build_fields, Field};
use super::raw_header::{malformed, Line, RawHeader};
use super::PcdEncoding;
use crate::format::text_lines::TextLines;
use crate::format::FormatError;

/// What the header says about the body.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Header {
    pub fields: Vec<Field>,
    pub width: usize,
    pub height: usize,
    /// WIDTH x HEIGHT, as POINTS must say.
    pub points: usize,
    pub encoding: PcdEncoding,
    /// Bytes of one packed point: the sum of every field's SIZE x COUNT.
    pub record_size: usize,
    /// Byte offset of the body (just after the `DATA` line).
    pub body_offset: usize,
    /// 1-based number of the first body line (for ASCII error messages).
    pub body_line: usize,
}

/// Header versions read: PCL writes `0.7` (`.7` in some old files).
const VERSIONS: [&str; 6] = ["0.7", ".7", "0.6", ".6", "0.5", ".5"];

/// Whether `bytes` start like a PCD header: after `#` comment lines and blank
/// lines, a `VERSION` or `FIELDS` line.
pub fn has_pcd_header(bytes: &[u8]) -> bool {
    let mut lines = TextLines::new(bytes, 0, 1);
    while let Ok(Some((_, text))) = lines.next_non_blank() {
        let keyword = text.split_ascii_whitespace().next().unwrap_or_default();
        if !keyword.starts_with('#') {
            return matches!(keyword, "VERSION" | "FIELDS");
        }
    }
    false
}

/// Parses the header at the start of `bytes`.
pub fn parse_header(bytes: &[u8]) -> Result<Header, FormatError> {
    let mut lines = TextLines::new(bytes, 0, 1);
    let mut raw = RawHeader::default();
    loop {
        let (number, text) = lines
            .next_non_blank()
            .map_err(|line| malformed(line, "the header must be ASCII text".into()))?
            .ok_or(FormatError::PcdMissingData)?;
        let mut tokens = text.split_ascii_whitespace();
        let keyword = tokens.next().unwrap_or_default();
        if keyword.starts_with('#') {
            continue;
        }
        let line = Line {
            number,
            values: tokens.collect(),
        };
        if keyword == "DATA" {
            let encoding = data_encoding(&line)?;
            return finish(raw, encoding, lines.offset(), number + 1);
        }
        let slot = raw
            .slot(keyword)
            .ok_or_else(|| malformed(number, format!("unknown keyword '{keyword}'")))?;
        if slot.is_some() {
            return Err(malformed(number, format!("a second '{keyword}' line")));
        }
        *slot = Some(line);
    }
}

fn data_encoding(line: &Line) -> Result<PcdEncoding, FormatError> {
    let [name] = line.values[..] else {
        return Err(malformed(
            line.number,
            "expected 'DATA ascii|binary|binary_compressed'".into(),
        ));
    };
    PcdEncoding::from_name(name).ok_or_else(|| FormatError::PcdUnknownData {
        line: line.number,
        found: name.into(),
    })
}

fn finish(
    raw: RawHeader,
    encoding: PcdEncoding,
    body_offset: usize,
    body_line: usize,
) -> Result<Header, FormatError> {
    if let Some(line) = &raw.version {
        let known = matches!(line.values[..], [v] if VERSIONS.contains(&v));
        if !known {
            let reason = "VERSION must be 0.7, 0.6 or 0.5".into();
            return Err(malformed(line.number, reason));
        }
    }
    if let Some(line) = &raw.viewpoint {
        let numbers = line.values.iter().filter(|v| v.parse::<f64>().is_ok());
        if line.values.len() != 7 || numbers.count() != 7 {
            let reason = "VIEWPOINT must be 7 numbers: tx ty tz qw qx qy qz".into();
            return Err(malformed(line.number, reason));
        }
    }
    let fields = build_fields(&raw)?;
    let (width, height, points) = dimensions(&raw)?;
    let record_size = fields
        .iter()
        .try_fold(0usize, |sum, field| sum.checked_add(field.bytes))
        .ok_or_else(|| FormatError::PcdAbsurdSize {
            what: "the point record (sum of SIZE x COUNT)".into(),
        })?;
    Ok(Header {
        fields,
        width,
        height,
        points,
        encoding,
        record_size,
        body_offset,
        body_line,
    })
}

/// WIDTH, HEIGHT and POINTS. Older headers may leave out WIDTH and HEIGHT
/// together (the cloud is then POINTS x 1), or POINTS (it is then WIDTH x
/// HEIGHT); when all three are given they must agree.
fn dimensions(raw: &RawHeader) -> Result<(usize, usize, usize), FormatError> {
    let width = raw.width.as_ref().map(count_value).transpose()?;
    let height = raw.height.as_ref().map(count_value).transpose()?;
    let points = raw.points.as_ref().map(count_value).transpose()?;
    let (width, height) = match (width, height, points) {
        (Some(w), Some(h), _) => (w, h),
        (None, None, Some(p)) => (p, 1),
        (None, None, None) => return Err(FormatError::PcdMissingKeyword { keyword: "POINTS" }),
        (None, _, _) => return Err(FormatError::PcdMissingKeyword { keyword: "WIDTH" }),
        (Some(_), None, _) => return Err(FormatError::PcdMissingKeyword { keyword: "HEIGHT" }),
    };
    let product = width
        .checked_mul(height)
        .ok_or_else(|| FormatError::PcdAbsurdSize {
            what: format!("WIDTH {width} x HEIGHT {height}"),
        })?;
    match points {
        Some(points) if points != product => Err(FormatError::PcdPointsMismatch {
            points,
            width,
            height,
        }),
        _ => Ok((width, height, product)),
    }
}

/// The single non-negative integer of a WIDTH, HEIGHT or POINTS line.
fn count_value(line: &Line) -> Result<usize, FormatError> {
    match line.values[..] {
        [value] => value.parse().map_err(|_| {
            let reason = format!("'{value}' is not a non-negative integer");
            malformed(line.number, reason)
        }),
        _ => Err(malformed(
            line.number,
            format!("expected one value, found {}", line.values.len()),
        )),
    }
}
