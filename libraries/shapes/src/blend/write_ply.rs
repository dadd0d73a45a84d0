//! Writing a blended model as binary little-endian PLY with normals and, for
//! viewers that colour by property, the source of each point (0 parent, 1 child,
//! 2 transition). Pure: returns the bytes.

use super::merge::Merged;

/// PLY bytes of `cloud`: float x y z nx ny nz, uchar source.
pub fn write_ply_with_normals(cloud: &Merged) -> Vec<u8> {
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by shroud blend\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\n\
         property uchar source\nend_header\n",
        cloud.len()
    );
    let mut out = header.into_bytes();
    out.reserve(cloud.len() * 25);
    for ((p, n), s) in cloud.points.iter().zip(&cloud.normals).zip(&cloud.sources) {
        for v in [p.x, p.y, p.z, n.x, n.y, n.z] {
            out.extend_from_slice(&(v as f32).to_le_bytes());
        }
        out.push(*s as u8);
    }
    out
}
