//! Writing a blended model as binary little-endian PLY with normals and, for
//! viewers that colour by property, the source of each point (0 parent, 1 child,
//! 2 transition). Pure: returns the bytes. The header and records are written by
//! the format module's PLY writer; this only lays `Merged` out as its columns.

use super::merge::Merged;
use crate::format::{write_ply_vertices, PlyProperty, PlyVertices};
use glam::DVec3;

/// PLY bytes of `cloud`: float x y z nx ny nz, uchar source.
pub fn write_ply_with_normals(cloud: &Merged) -> Vec<u8> {
    let points = narrow(&cloud.points);
    let normals = narrow(&cloud.normals);
    let [nx, ny, nz] = [0, 1, 2].map(|k| normals.iter().map(|n| n[k]).collect::<Vec<_>>());
    let sources: Vec<u8> = cloud.sources.iter().map(|&s| s as u8).collect();
    let properties = [
        PlyProperty::float("nx", &nx),
        PlyProperty::float("ny", &ny),
        PlyProperty::float("nz", &nz),
        PlyProperty::uchar("source", &sources),
    ];
    let vertices = PlyVertices {
        comment: "written by shroud blend",
        points: &points,
        properties: &properties,
    };
    write_ply_vertices(&vertices, false)
}

/// PLY floats are f32, which viewers expect.
fn narrow(vectors: &[DVec3]) -> Vec<[f32; 3]> {
    vectors.iter().map(|v| v.as_vec3().to_array()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::blend::Source;
    use crate::format::parse_ply;

    fn tiny() -> Merged {
        Merged {
            points: vec![DVec3::new(1.0, -2.5, 0.1), DVec3::new(1e6, 0.0, -0.0)],
            normals: vec![DVec3::Z, DVec3::new(0.6, -0.8, 0.0)],
            sources: vec![Source::Parent, Source::Transition],
        }
    }

    /// The bytes the hand-written blend writer produced before it became a call
    /// into the format module's writer: blend output must not change.
    #[test]
    fn bytes_are_unchanged() {
        let mut expected =
            b"ply\nformat binary_little_endian 1.0\ncomment written by shroud blend\n\
            element vertex 2\nproperty float x\nproperty float y\nproperty float z\n\
            property float nx\nproperty float ny\nproperty float nz\n\
            property uchar source\nend_header\n"
                .to_vec();
        let body = "0000803f000020c0cdcccc3d00000000000000000000803f00\
                    0024744900000000000000809a99193fcdcc4cbf0000000002";
        expected.extend(
            (0..body.len())
                .step_by(2)
                .map(|i| u8::from_str_radix(&body[i..i + 2], 16).unwrap()),
        );
        assert_eq!(write_ply_with_normals(&tiny()), expected);
    }

    #[test]
    fn reads_back_as_the_points() {
        let cloud = parse_ply(&write_ply_with_normals(&tiny())).unwrap();
        assert_eq!(cloud.points, narrow(&tiny().points));
        assert_eq!(cloud.intensity, None);
        let empty = parse_ply(&write_ply_with_normals(&Merged::default())).unwrap();
        assert!(empty.points.is_empty());
    }
}
