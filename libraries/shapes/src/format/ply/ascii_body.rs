//! ASCII PLY bodies: one record per line (as every writer emits them), so a record
//! with too few or too many values is caught on its own line instead of shifting
//! every later record. Blank lines are skipped.

use super::header::{Element, Header, PropertyKind};
use super::layout::VertexLayout;
use super::PlyCloud;
use crate::format::scalar::ScalarType;
use crate::format::text_lines::TextLines;
use crate::format::FormatError;

/// Reads the vertex element of an ASCII PLY whose header is `header`.
pub fn read_vertices(
    bytes: &[u8],
    header: &Header,
    layout: &VertexLayout,
) -> Result<PlyCloud, FormatError> {
    let vertex = &header.elements[layout.element];
    let mut lines = BodyLines::of(bytes, header);
    let truncated = |got, lines: &BodyLines| FormatError::PlyTruncatedBody {
        expected: vertex.count,
        got,
        offset: lines.offset(),
    };
    for element in &header.elements[..layout.element] {
        for _ in 0..element.count {
            let (line, text) = lines.next_record()?.ok_or_else(|| truncated(0, &lines))?;
            let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
            check_record_shape(element, &tokens, line)?;
        }
    }
    // A record takes at least 6 bytes ("0 0 0\n"): do not trust the count for the allocation.
    let capacity = vertex.count.min(bytes.len() / 6);
    let mut cloud = PlyCloud::with_capacity(capacity, layout.intensity.is_some());
    for record in 0..vertex.count {
        let (line, text) = lines
            .next_record()?
            .ok_or_else(|| truncated(record, &lines))?;
        let tokens: Vec<&str> = text.split_ascii_whitespace().collect();
        check_record_shape(vertex, &tokens, line)?;
        // The shape check above guarantees a token for every property.
        let value = |index: usize, ty: ScalarType| {
            let token = tokens
                .get(token_index(vertex, index, &tokens))
                .copied()
                .unwrap_or_default();
            parse_value(token, ty, line)
        };
        let [x, y, z] = layout.xyz;
        let point = [
            value(x.index, x.ty)?,
            value(y.index, y.ty)?,
            value(z.index, z.ty)?,
        ];
        let intensity = layout.intensity.map(|s| value(s.index, s.ty)).transpose()?;
        cloud.push(point, intensity);
    }
    Ok(cloud)
}

/// Non-blank lines of the body with their 1-based line numbers.
pub(super) struct BodyLines<'a>(TextLines<'a>);

impl<'a> BodyLines<'a> {
    /// The lines of the body that follows `header` in `bytes`.
    pub(super) fn of(bytes: &'a [u8], header: &Header) -> Self {
        Self(TextLines::new(bytes, header.body_offset, header.body_line))
    }

    /// Byte offset of the next unread line.
    pub(super) fn offset(&self) -> usize {
        self.0.offset()
    }

    pub(super) fn next_record(&mut self) -> Result<Option<(usize, &'a str)>, FormatError> {
        self.0
            .next_non_blank()
            .map_err(|line| FormatError::PlyBadAsciiRecord {
                line,
                reason: "the line is not UTF-8 text".into(),
            })
    }
}

/// Checks that `tokens` are exactly one record of `element`, list lengths included.
pub(super) fn check_record_shape(
    element: &Element,
    tokens: &[&str],
    line: usize,
) -> Result<(), FormatError> {
    let too_few = || FormatError::PlyBadAsciiRecord {
        line,
        reason: format!(
            "a '{}' record needs more than the {} values on this line",
            element.name,
            tokens.len()
        ),
    };
    let mut next = 0;
    for property in &element.properties {
        match property.kind {
            PropertyKind::Scalar(_) => next += 1,
            PropertyKind::List { count, .. } => {
                let token = tokens.get(next).copied().ok_or_else(too_few)?;
                let length = parse_value(token, count, line)? as f64;
                if length < 0.0 || length.fract() != 0.0 {
                    let reason = format!("list '{}' has invalid length '{token}'", property.name);
                    return Err(FormatError::PlyBadAsciiRecord { line, reason });
                }
                // Saturating: an absurd length must fail the check below, not overflow.
                next = next.saturating_add(1).saturating_add(length as usize);
            }
        }
        if next > tokens.len() {
            return Err(too_few());
        }
    }
    if next != tokens.len() {
        let reason = format!(
            "a '{}' record has {next} values, this line has {}",
            element.name,
            tokens.len()
        );
        return Err(FormatError::PlyBadAsciiRecord { line, reason });
    }
    Ok(())
}

/// Token index of property `index`, walking list lengths before it.
pub(super) fn token_index(element: &Element, index: usize, tokens: &[&str]) -> usize {
    let mut next = 0;
    for property in element.properties.iter().take(index) {
        let span = match property.kind {
            PropertyKind::Scalar(_) => 1,
            PropertyKind::List { .. } => {
                let length = tokens
                    .get(next)
                    .and_then(|t| t.parse::<f64>().ok())
                    .unwrap_or(0.0);
                (length as usize).saturating_add(1)
            }
        };
        next = next.saturating_add(span);
    }
    next
}

/// A number of type `ty`. `float` properties are parsed straight to f32 so that a
/// shortest-representation writer round-trips bit for bit; other types go
/// through f64 (exact for every integer type).
fn parse_value(token: &str, ty: ScalarType, line: usize) -> Result<f32, FormatError> {
    parse_number(token, ty, line).map(|v| v as f32)
}

/// A number of type `ty` at full precision (see [`ScalarType::parse_text`]).
pub(super) fn parse_number(token: &str, ty: ScalarType, line: usize) -> Result<f64, FormatError> {
    ty.parse_text(token)
        .ok_or_else(|| FormatError::PlyBadAsciiNumber {
            line,
            token: token.into(),
        })
}
