//! Writing point clouds as PLY (binary little endian by default, or ASCII).

/// A PLY file of `points` with float x, y, z and, when `intensity` holds exactly
/// one value per point, a float `intensity` property (otherwise it is left out).
/// ASCII numbers use the shortest representation that reads back to the same f32.
pub fn write_ply_points(points: &[[f32; 3]], intensity: Option<&[f32]>, ascii: bool) -> Vec<u8> {
    let intensity = intensity.filter(|i| i.len() == points.len());
    let encoding = if ascii {
        "ascii"
    } else {
        "binary_little_endian"
    };
    let mut header = format!(
        "ply\nformat {encoding} 1.0\ncomment written by shroud\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\n",
        points.len()
    );
    if intensity.is_some() {
        header.push_str("property float intensity\n");
    }
    header.push_str("end_header\n");
    let values_per_point = 3 + usize::from(intensity.is_some());
    let mut out = header.into_bytes();
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
    out
}
