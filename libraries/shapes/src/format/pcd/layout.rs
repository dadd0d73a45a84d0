//! Where x, y, z and the optional intensity sit among a PCD point's fields, and
//! where each field starts in a packed record or an ASCII line.

use super::fields::Field;
use crate::format::scalar::ScalarType;
use crate::format::FormatError;

/// The field name read as intensity (ASCII case-insensitive, like x, y and z).
const INTENSITY: &str = "intensity";

/// One wanted field: its index among the fields and its type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Slot {
    pub field: usize,
    pub ty: ScalarType,
}

/// The slots of x, y, z and the optional intensity.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PointLayout {
    pub xyz: [Slot; 3],
    pub intensity: Option<Slot>,
}

impl PointLayout {
    /// Finds the fields; x, y and z are required. A wanted field must hold one
    /// value per point (COUNT 1).
    pub fn of(fields: &[Field]) -> Result<Self, FormatError> {
        let coordinate = |axis: char| {
            slot(fields, &axis.to_string())?.ok_or(FormatError::PcdMissingCoordinate { axis })
        };
        Ok(Self {
            xyz: [coordinate('x')?, coordinate('y')?, coordinate('z')?],
            intensity: slot(fields, INTENSITY)?,
        })
    }
}

fn slot(fields: &[Field], name: &str) -> Result<Option<Slot>, FormatError> {
    let Some(index) = fields
        .iter()
        .position(|f| f.name.eq_ignore_ascii_case(name))
    else {
        return Ok(None);
    };
    let field = &fields[index];
    if field.count != 1 {
        return Err(FormatError::PcdFieldNotScalar {
            field: field.name.clone(),
            count: field.count,
        });
    }
    Ok(Some(Slot {
        field: index,
        ty: field.ty,
    }))
}

/// Where each field starts when the fields follow each other, each taking
/// `span(field)`: byte offsets in a record (`|f| f.bytes`), token indices in an
/// ASCII line (`|f| f.count`). The sums are bounded by the record size, which
/// the header checked for overflow.
pub fn starts(fields: &[Field], span: impl Fn(&Field) -> usize) -> Vec<usize> {
    fields
        .iter()
        .scan(0usize, |next, field| {
            let start = *next;
            *next = next.saturating_add(span(field));
            Some(start)
        })
        .collect()
}
