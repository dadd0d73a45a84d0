//! The fields of a PCD point: `FIELDS` names them; `SIZE`, `TYPE` and `COUNT`
//! give each one's byte size, type letter and number of values. PCL's defaults
//! for older headers that leave a line out: `SIZE 4`, `TYPE F`, `COUNT 1`.

use super::raw_header::{malformed, Line, RawHeader};
use crate::format::scalar::ScalarType;
use crate::format::FormatError;

/// PCL's name for padding bytes (`_`); it may appear several times.
pub const PADDING: &str = "_";

/// One field of every point: `count` values of type `ty`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Field {
    pub name: String,
    pub ty: ScalarType,
    pub count: usize,
    /// SIZE x COUNT: the field's bytes in one point.
    pub bytes: usize,
}

/// The fields of the header's FIELDS line with their sizes, types and counts.
pub(super) fn build_fields(raw: &RawHeader) -> Result<Vec<Field>, FormatError> {
    let names = raw
        .fields
        .as_ref()
        .ok_or(FormatError::PcdMissingKeyword { keyword: "FIELDS" })?;
    if names.values.is_empty() {
        return Err(malformed(names.number, "FIELDS names no field".into()));
    }
    for (i, name) in names.values.iter().enumerate() {
        let earlier = &names.values[..i];
        if *name != PADDING && earlier.iter().any(|n| n.eq_ignore_ascii_case(name)) {
            let reason = format!("a second field named '{name}'");
            return Err(malformed(names.number, reason));
        }
    }
    let names = &names.values;
    let sizes = per_field(raw.size.as_ref(), "SIZE", names, 4, positive)?;
    let kinds = per_field(raw.ty.as_ref(), "TYPE", names, 'F', type_letter)?;
    let counts = per_field(raw.count.as_ref(), "COUNT", names, 1, positive)?;
    let type_line = [&raw.ty, &raw.size, &raw.fields]
        .into_iter()
        .find_map(|line| line.as_ref().map(|l| l.number))
        .unwrap_or_default();
    let fields = names.iter().zip(sizes).zip(kinds).zip(counts);
    fields
        .map(|(((name, size), kind), count)| {
            let ty = ScalarType::from_pcd(kind, size).ok_or_else(|| {
                FormatError::PcdUnsupportedType {
                    line: type_line,
                    field: (*name).into(),
                    kind: kind.into(),
                    size,
                }
            })?;
            let bytes = size
                .checked_mul(count)
                .ok_or_else(|| FormatError::PcdAbsurdSize {
                    what: format!("field '{name}' (SIZE {size} x COUNT {count})"),
                })?;
            Ok(Field {
                name: (*name).into(),
                ty,
                count,
                bytes,
            })
        })
        .collect()
}

/// One value per field from `line`, or `default` for every field when the
/// header has no such line.
fn per_field<T: Copy>(
    line: Option<&Line>,
    keyword: &'static str,
    names: &[&str],
    default: T,
    parse: fn(&str) -> Result<T, &'static str>,
) -> Result<Vec<T>, FormatError> {
    let Some(line) = line else {
        return Ok(vec![default; names.len()]);
    };
    if line.values.len() != names.len() {
        return Err(FormatError::PcdFieldCountMismatch {
            line: line.number,
            keyword,
            got: line.values.len(),
            expected: names.len(),
        });
    }
    let parsed = names.iter().zip(&line.values).map(|(name, value)| {
        parse(value).map_err(|expected| {
            let reason = format!("{keyword} of field '{name}' is '{value}', not {expected}");
            malformed(line.number, reason)
        })
    });
    parsed.collect()
}

fn positive(value: &str) -> Result<usize, &'static str> {
    value
        .parse()
        .ok()
        .filter(|&n| n > 0)
        .ok_or("a positive integer")
}

fn type_letter(value: &str) -> Result<char, &'static str> {
    match value {
        "I" => Ok('I'),
        "U" => Ok('U'),
        "F" => Ok('F'),
        _ => Err("I, U or F"),
    }
}
