//! The point records that the PLY and PCD writers share: x, y, z and, when
//! given, the intensity of each point as f32, either packed little-endian or as
//! one ASCII line per point.

/// `intensity` if it holds exactly one value per point, `None` otherwise (a
/// writer then leaves the field out rather than misalign it).
pub(crate) fn per_point<'a>(
    points: &[[f32; 3]],
    intensity: Option<&'a [f32]>,
) -> Option<&'a [f32]> {
    intensity.filter(|values| values.len() == points.len())
}

/// Appends one record per point to `out`: ASCII lines of space-separated numbers,
/// each in the shortest text that reads back to the same f32, or packed
/// little-endian f32. `intensity` must come from [`per_point`].
pub(crate) fn push_records(
    out: &mut Vec<u8>,
    points: &[[f32; 3]],
    intensity: Option<&[f32]>,
    ascii: bool,
) {
    let values_per_point = 3 + usize::from(intensity.is_some());
    out.reserve(points.len() * values_per_point * if ascii { 12 } else { 4 });
    for (i, p) in points.iter().enumerate() {
        let value = intensity.and_then(|all| all.get(i).copied());
        let values = p.iter().copied().chain(value);
        if ascii {
            for (k, v) in values.enumerate() {
                if k > 0 {
                    out.push(b' ');
                }
                out.extend_from_slice(v.to_string().as_bytes());
            }
            out.push(b'\n');
        } else {
            values.for_each(|v| out.extend_from_slice(&v.to_le_bytes()));
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
        push_records(&mut text, &points, Some(&[7.0, 0.5]), true);
        assert_eq!(text, b"1 -0.1 0.00000003 7\n4 5 6 0.5\n");
        let mut packed = Vec::new();
        push_records(&mut packed, &points, None, false);
        assert_eq!(packed.len(), 24);
        assert_eq!(packed[4..8], (-0.1f32).to_le_bytes());
        assert_eq!(per_point(&points, Some(&[1.0])), None);
        assert_eq!(per_point(&points, Some(&[1.0, 2.0])), Some(&[1.0, 2.0][..]));
    }
}
