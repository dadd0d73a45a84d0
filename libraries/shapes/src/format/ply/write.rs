//! Writing point clouds as PLY (binary little endian by default, or ASCII).

use crate::format::point_rows::{per_point, push_records};

/// A PLY file of `points` with float x, y, z and, when `intensity` holds exactly
/// one value per point, a float `intensity` property (otherwise it is left out).
/// ASCII numbers use the shortest representation that reads back to the same f32.
pub fn write_ply_points(points: &[[f32; 3]], intensity: Option<&[f32]>, ascii: bool) -> Vec<u8> {
    let intensity = per_point(points, intensity);
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
    let mut out = header.into_bytes();
    push_records(&mut out, points, intensity, ascii);
    out
}
