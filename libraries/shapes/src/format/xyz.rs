//! Text point clouds: XYZ, CSV and TSV. One point per line; the first three columns
//! are x, y, z and any further columns are ignored.
//!
//! A line is split on `;` if it has one (then a decimal comma is accepted, as in
//! European CSV), else on `,`, else on whitespace (spaces and tabs). Blank lines and
//! lines starting with `#` or `//` are skipped, a UTF-8 byte order mark is
//! ignored, and the first content line may be a header whose every field is
//! non-numeric (`x,y,z,intensity`). Any other line that does not start with three
//! numbers is an error naming its line number.

use super::FormatError;

const BYTE_ORDER_MARK: &[u8] = b"\xEF\xBB\xBF";

/// Parses an XYZ / CSV / TSV text cloud; an input without points is
/// [`FormatError::NoPoints`].
pub fn parse_xyz(text: &[u8]) -> Result<Vec<[f32; 3]>, FormatError> {
    let text = text.strip_prefix(BYTE_ORDER_MARK).unwrap_or(text);
    // A typical point line takes 20-40 bytes; the vector grows if lines are shorter.
    let mut points = Vec::with_capacity(text.len() / 32);
    let mut before_first_content = true;
    for (index, raw) in text.split(|&b| b == b'\n').enumerate() {
        let line = index + 1;
        let content = std::str::from_utf8(raw)
            .map_err(|_| FormatError::XyzBadLine {
                line,
                reason: "the line is not UTF-8 text".into(),
            })?
            .trim();
        if content.is_empty() || content.starts_with('#') || content.starts_with("//") {
            continue;
        }
        let is_first_content = std::mem::replace(&mut before_first_content, false);
        match parse_point(content) {
            Ok(point) => points.push(point),
            Err(_) if is_first_content && is_header(content) => {}
            Err(reason) => return Err(FormatError::XyzBadLine { line, reason }),
        }
    }
    if points.is_empty() {
        return Err(FormatError::NoPoints);
    }
    Ok(points)
}

/// The cloud as text, one `x y z` line per point, each number in the shortest form
/// that reads back to the same f32.
pub fn write_xyz(points: &[[f32; 3]]) -> Vec<u8> {
    let mut out = Vec::with_capacity(points.len() * 36);
    for p in points {
        let line = format!("{} {} {}\n", p[0], p[1], p[2]);
        out.extend_from_slice(line.as_bytes());
    }
    out
}

/// How the fields of a line are separated.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Separator {
    Semicolon,
    Comma,
    Whitespace,
}

impl Separator {
    fn of(line: &str) -> Self {
        if line.contains(';') {
            Self::Semicolon
        } else if line.contains(',') {
            Self::Comma
        } else {
            Self::Whitespace
        }
    }
}

/// The fields of a line. With an explicit separator an empty field stays a field
/// (a missing value), with whitespace runs of blanks separate.
fn fields(line: &str) -> impl Iterator<Item = (&str, Separator)> {
    let separator = Separator::of(line);
    line.split(move |c: char| match separator {
        Separator::Semicolon => c == ';',
        Separator::Comma => c == ',',
        Separator::Whitespace => c.is_ascii_whitespace(),
    })
    .filter(move |f| separator != Separator::Whitespace || !f.is_empty())
    .map(move |f| (f.trim().trim_matches('"'), separator))
}

fn parse_number(field: &str, separator: Separator) -> Option<f32> {
    field.parse().ok().or_else(|| match separator {
        Separator::Semicolon if field.contains(',') => field.replace(',', ".").parse().ok(),
        _ => None,
    })
}

/// The first three fields as a point, or why they are not one.
fn parse_point(line: &str) -> Result<[f32; 3], String> {
    let mut point = [0.0; 3];
    let mut fields = fields(line);
    for (column, value) in point.iter_mut().enumerate() {
        let Some((field, separator)) = fields.next() else {
            return Err(format!(
                "expected 3 numbers x y z, found {column} column(s)"
            ));
        };
        *value = parse_number(field, separator)
            .ok_or_else(|| format!("column {} ('{field}') is not a number", column + 1))?;
    }
    Ok(point)
}

/// A header line: no field is a number.
fn is_header(line: &str) -> bool {
    fields(line).all(|(field, separator)| parse_number(field, separator).is_none())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_every_separator_and_skips_comments_and_extra_columns() {
        let text = "\u{feff}x;y;z;label\n# comment\n\n// comment\n1;2;3;a\n4,5;6,5;-7e-1\r\n";
        assert_eq!(
            parse_xyz(text.as_bytes()).unwrap(),
            vec![[1.0, 2.0, 3.0], [4.5, 6.5, -0.7]]
        );
        let csv = "X, Y, Z\n1.5, 2, 3, 9\n\"4\",5,6\n";
        assert_eq!(
            parse_xyz(csv.as_bytes()).unwrap(),
            vec![[1.5, 2.0, 3.0], [4.0, 5.0, 6.0]]
        );
        let tsv = "1\t2\t3\n  4   5 6 100 200\n";
        assert_eq!(
            parse_xyz(tsv.as_bytes()).unwrap(),
            vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]
        );
    }

    #[test]
    fn names_the_bad_line() {
        let bad = |t: &[u8]| match parse_xyz(t) {
            Err(FormatError::XyzBadLine { line, .. }) => line,
            other => panic!("expected a bad line, got {other:?}"),
        };
        assert_eq!(bad(b"1 2 3\nx y z\n"), 2, "a header only at the top");
        assert_eq!(bad(b"x y z\nu v w\n1 2 3"), 2, "a single header");
        assert_eq!(bad(b"1 2 3\n\n4 5\n"), 3, "too few columns");
        assert_eq!(bad(b"1,,3\n"), 1, "an empty field is missing, not skipped");
        assert_eq!(bad(b"x 1 2\n"), 1, "a mixed line is no header");
        assert_eq!(bad(b"1 2 3\n\xff\n"), 2, "not UTF-8");
    }

    #[test]
    fn empty_inputs_have_no_points() {
        for text in ["", "\n\n", "# only a comment\n", "x,y,z\n"] {
            assert_eq!(
                parse_xyz(text.as_bytes()),
                Err(FormatError::NoPoints),
                "{text:?}"
            );
        }
    }

    #[test]
    fn written_text_reads_back_bit_for_bit() {
        let points = vec![
            [0.1, -2.5e-7, 3.4028235e38],
            [1.0 / 3.0, f32::MIN_POSITIVE, -0.0],
        ];
        assert_eq!(parse_xyz(&write_xyz(&points)).unwrap(), points);
    }
}
