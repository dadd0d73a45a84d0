//! The point records that the PLY and PCD writers share: x, y, z as f32 and
//! then each further field's value of the point, either packed little-endian or
//! as one ASCII line per point.

/// `intensity` if it holds exactly one value per point, `None` otherwise (a
/// writer then leaves the field out rather than misalign it).
pub(crate) fn per_point<'a>(
    points: &[[f32; 3]],
    intensity: Option<&'a [f32]>,
) -> Option<&'a [f32]> {
    intensity.filter(|values| values.len() == points.len())
}

/// The values of one field after x, y, z, one per point.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Column<'a> {
    F32(&'a [f32]),
    U8(&'a [u8]),
}

impl Column<'_> {
    pub(crate) fn len(self) -> usize {
        match self {
            Column::F32(values) => values.len(),
            Column::U8(values) => values.len(),
        }
    }

    /// Packed bytes per value.
    fn width(self) -> usize {
        match self {
            Column::F32(_) => 4,
            Column::U8(_) => 1,
        }
    }

    fn push(self, i: usize, out: &mut Vec<u8>, ascii: bool) {
        match self {
            Column::F32(values) => push_f32(values[i], out, ascii),
            Column::U8(values) if ascii => out.extend_from_slice(values[i].to_string().as_bytes()),
            Column::U8(values) => out.push(values[i]),
        }
    }
}

fn push_f32(value: f32, out: &mut Vec<u8>, ascii: bool) {
    if ascii {
        out.extend_from_slice(value.to_string().as_bytes());
    } else {
        out.extend_from_slice(&value.to_le_bytes());
    }
}

/// Appends one record per point to `out`: ASCII lines of space-separated numbers,
/// each float in the shortest text that reads back to the same f32, or packed
/// little-endian values. A column without exactly one value per point is left
/// out (its writer leaves it out of the header too), so no record misaligns.
pub(crate) fn push_records(
    out: &mut Vec<u8>,
    points: &[[f32; 3]],
    columns: &[Column],
    ascii: bool,
) {
    let whole: Vec<Column> = columns
        .iter()
        .copied()
        .filter(|c| c.len() == points.len())
        .collect();
    let columns = whole.as_slice();
    let packed = 12 + columns.iter().map(|c| c.width()).sum::<usize>();
    // ASCII takes about three times the packed size (12 characters per float).
    out.reserve(points.len() * if ascii { 3 * packed } else { packed });
    for (i, p) in points.iter().enumerate() {
        for (k, &axis) in p.iter().enumerate() {
            if ascii && k > 0 {
                out.push(b' ');
            }
            push_f32(axis, out, ascii);
        }
        for column in columns {
            if ascii {
                out.push(b' ');
            }
            column.push(i, out, ascii);
        }
        if ascii {
            out.push(b'\n');
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_ascii_lines_and_packed_floats() {
        let points = [[1.0, -0.1, 3e-8], [4.0, 5.0, 6.0]];
        let mut text = Vec::new();
        let columns = [Column::F32(&[7.0, 0.5]), Column::U8(&[2, 255])];
        push_records(&mut text, &points, &columns, true);
        assert_eq!(text, b"1 -0.1 0.00000003 7 2\n4 5 6 0.5 255\n");
        let mut packed = Vec::new();
        push_records(&mut packed, &points, &[], false);
        assert_eq!(packed.len(), 24);
        assert_eq!(packed[4..8], (-0.1f32).to_le_bytes());
        // A column of another length than the points is left out, not misread.
        push_records(&mut packed, &points[..1], &columns[1..], false);
        assert_eq!(packed.len(), 24 + 12);
        push_records(&mut packed, &points, &columns[1..], false);
        assert_eq!(packed.len(), 36 + 2 * 13);
        assert_eq!((packed[48], packed[61]), (2, 255));
        assert_eq!(per_point(&points, Some(&[1.0])), None);
        assert_eq!(per_point(&points, Some(&[1.0, 2.0])), Some(&[1.0, 2.0][..]));
    }
}
