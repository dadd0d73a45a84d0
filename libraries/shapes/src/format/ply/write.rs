//! Writing point clouds and triangle meshes as PLY (binary little endian by
//! default, or ASCII): the one place that writes PLY headers and records (plain
//! clouds here, blended models through `blend::write_ply_with_normals`, meshes
//! through `TriangleMesh::to_ply`).

use crate::format::point_rows::{push_records, Column};
use crate::format::TriangleMesh;

/// A property of every vertex after x, y, z: its PLY name and one value per point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlyProperty<'a> {
    pub name: &'a str,
    pub values: Column<'a>,
}

impl<'a> PlyProperty<'a> {
    pub(crate) fn float(name: &'a str, values: &'a [f32]) -> Self {
        let values = Column::F32(values);
        Self { name, values }
    }

    pub(crate) fn uchar(name: &'a str, values: &'a [u8]) -> Self {
        let values = Column::U8(values);
        Self { name, values }
    }

    fn type_name(&self) -> &'static str {
        match self.values {
            Column::F32(_) => "float",
            Column::U8(_) => "uchar",
        }
    }
}

/// The vertices of a PLY file: float x, y, z, then `properties` in order, with
/// `comment` (who wrote the file) as the header's comment line.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlyVertices<'a> {
    pub comment: &'a str,
    pub points: &'a [[f32; 3]],
    pub properties: &'a [PlyProperty<'a>],
}

/// A PLY file of `points` with float x, y, z and, when `intensity` holds exactly
/// one value per point, a float `intensity` property (otherwise it is left out).
/// ASCII numbers use the shortest representation that reads back to the same f32.
pub fn write_ply_points(points: &[[f32; 3]], intensity: Option<&[f32]>, ascii: bool) -> Vec<u8> {
    let intensity = intensity.map(|values| PlyProperty::float("intensity", values));
    let vertices = PlyVertices {
        comment: "written by shroud",
        points,
        properties: intensity.as_slice(),
    };
    write_ply_vertices(&vertices, ascii)
}

/// A PLY file of `vertices`. A property without exactly one value per point is
/// left out rather than misalign the records.
pub(crate) fn write_ply_vertices(vertices: &PlyVertices, ascii: bool) -> Vec<u8> {
    write_ply(vertices, None, ascii)
}

impl TriangleMesh {
    /// PLY with float x, y, z vertices and `list uchar int vertex_indices` faces,
    /// ASCII or binary little endian. Vertices are narrowed to f32, as viewers
    /// expect; `int` indices are the same bytes as u32 below 2^31 vertices.
    pub fn to_ply(&self, ascii: bool) -> Vec<u8> {
        let points: Vec<[f32; 3]> = self.vertices.iter().map(|v| v.map(|c| c as f32)).collect();
        let vertices = PlyVertices {
            comment: "written by shroud",
            points: &points,
            properties: &[],
        };
        write_ply(&vertices, Some(&self.triangles), ascii)
    }
}

/// A PLY file of `vertices` and, when `faces` is given, a `face` element of
/// three-index `list uchar int vertex_indices` records after them.
fn write_ply(vertices: &PlyVertices, faces: Option<&[[u32; 3]]>, ascii: bool) -> Vec<u8> {
    let properties: Vec<PlyProperty> = vertices
        .properties
        .iter()
        .filter(|p| p.values.len() == vertices.points.len())
        .copied()
        .collect();
    let face_count = faces.map(<[_]>::len);
    let mut out = header(vertices, &properties, face_count, ascii).into_bytes();
    let columns: Vec<Column> = properties.iter().map(|p| p.values).collect();
    push_records(&mut out, vertices.points, &columns, ascii);
    push_faces(&mut out, faces.unwrap_or_default(), ascii);
    out
}

/// One record per face: `3 a b c` lines, or a count byte and little-endian indices.
fn push_faces(out: &mut Vec<u8>, faces: &[[u32; 3]], ascii: bool) {
    if !ascii {
        out.reserve(faces.len() * 13);
    }
    for &[a, b, c] in faces {
        if ascii {
            out.extend_from_slice(format!("3 {a} {b} {c}\n").as_bytes());
        } else {
            out.push(3);
            [a, b, c]
                .iter()
                .for_each(|i| out.extend_from_slice(&i.to_le_bytes()));
        }
    }
}

/// The header of `vertices` with `properties` after x, y, z and, when `faces`
/// holds their count, the `face` element after the vertices.
fn header(
    vertices: &PlyVertices,
    properties: &[PlyProperty],
    faces: Option<usize>,
    ascii: bool,
) -> String {
    let encoding = if ascii {
        "ascii"
    } else {
        "binary_little_endian"
    };
    let mut header = format!(
        "ply\nformat {encoding} 1.0\ncomment {}\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\n",
        vertices.comment,
        vertices.points.len()
    );
    for property in properties {
        header.push_str(&format!(
            "property {} {}\n",
            property.type_name(),
            property.name
        ));
    }
    if let Some(count) = faces {
        header.push_str(&format!(
            "element face {count}\nproperty list uchar int vertex_indices\n"
        ));
    }
    header.push_str("end_header\n");
    header
}

#[cfg(test)]
mod tests {
    use super::*;

    const POINTS: [[f32; 3]; 2] = [[1.0, -0.1, 3e-8], [4.0, 5.0, 6.5]];
    const INTENSITY: [f32; 2] = [7.0, 0.5];

    fn hex(text: &str) -> Vec<u8> {
        (0..text.len())
            .step_by(2)
            .map(|i| u8::from_str_radix(&text[i..i + 2], 16).unwrap())
            .collect()
    }

    fn header_of(encoding: &str, intensity: bool) -> String {
        let extra = if intensity {
            "property float intensity\n"
        } else {
            ""
        };
        format!(
            "ply\nformat {encoding} 1.0\ncomment written by shroud\nelement vertex 2\n\
             property float x\nproperty float y\nproperty float z\n{extra}end_header\n"
        )
    }

    /// The bytes `write_ply_points` wrote before it became a call into
    /// `write_ply_vertices`: files saved earlier and by this version are the same.
    #[test]
    fn points_bytes_are_unchanged() {
        let cases = [
            (
                true,
                false,
                "31202d302e3120302e30303030303030330a34203520362e350a",
            ),
            (
                true,
                true,
                "31202d302e3120302e303030303030303320370a34203520362e3520302e350a",
            ),
            (
                false,
                false,
                "0000803fcdccccbd59d90033000080400000a0400000d040",
            ),
            (
                false,
                true,
                "0000803fcdccccbd59d900330000e040000080400000a0400000d0400000003f",
            ),
        ];
        for (ascii, has_intensity, body) in cases {
            let encoding = if ascii {
                "ascii"
            } else {
                "binary_little_endian"
            };
            let mut expected = header_of(encoding, has_intensity).into_bytes();
            expected.extend(hex(body));
            let intensity = has_intensity.then_some(&INTENSITY[..]);
            assert_eq!(write_ply_points(&POINTS, intensity, ascii), expected);
        }
        let short = write_ply_points(&POINTS, Some(&INTENSITY[..1]), true);
        assert_eq!(short, write_ply_points(&POINTS, None, true));
    }

    /// The bytes `to_ply` wrote before it moved beside the cloud writers, into
    /// `format::ply::write`: meshes saved earlier and by this version are the same.
    #[test]
    fn ply_bytes_are_unchanged() {
        let mesh = TriangleMesh {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.1, -2.5],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.25],
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        let header = |encoding: &str| {
            format!(
                "ply\nformat {encoding} 1.0\ncomment written by shroud\nelement vertex 4\n\
                 property float x\nproperty float y\nproperty float z\nelement face 2\n\
                 property list uchar int vertex_indices\nend_header\n"
            )
        };
        let ascii = header("ascii") + "0 0 0\n1 0.1 -2.5\n1 1 0\n0 1 0.25\n3 0 1 2\n3 0 2 3\n";
        assert_eq!(String::from_utf8(mesh.to_ply(true)).unwrap(), ascii);
        let body = "0000000000000000000000000000803fcdcccc3d000020c00000803f0000803f\
                    00000000000000000000803f0000803e03000000000100000002000000030000\
                    00000200000003000000";
        let mut binary = header("binary_little_endian").into_bytes();
        binary.extend(hex(body));
        assert_eq!(mesh.to_ply(false), binary);
        let empty = TriangleMesh::default().to_ply(true);
        let empty_header = header("ascii")
            .replace("vertex 4", "vertex 0")
            .replace("face 2", "face 0");
        assert_eq!(String::from_utf8(empty).unwrap(), empty_header);
    }
}
