//! Reading triangle meshes: Wavefront OBJ text and PLY (ascii or binary, with a
//! `face` element), told apart by content. Polygons are fan-triangulated; every
//! defect (bad index, NaN coordinate, face of fewer than 3 vertices, truncated
//! body, no faces at all) is a [`FormatError`] naming the line or record.

use super::mesh::TriangleMesh;
use super::mesh_builder::MeshBuilder;
use super::ply::{has_ply_magic, parse_ply_mesh};
use super::{parse_obj_polygons, Corners, FormatError, ObjDefect};

/// Reads a triangle mesh from the bytes of an OBJ or PLY file: a file that starts
/// with the PLY magic line is PLY, anything else must be OBJ text (UTF-8).
///
/// * OBJ: `v x y z [more numbers, ignored]` and `f a b c ...` lines; face references may be
///   `a`, `a/t`, `a//n` or `a/t/n`, 1-based or negative (relative to the last
///   vertex defined so far). Comments (`#`) and every other statement (`vt`, `vn`,
///   `g`, `o`, `s`, `usemtl`, `l`, ...) are ignored.
/// * PLY: the `vertex` element's x, y, z (any scalar types) and the `face`
///   element's `vertex_indices` (or `vertex_index`, or else its first) list.
///
/// Polygons with more than three vertices become a fan around their first vertex,
/// so a written mesh ([`TriangleMesh::to_obj`], [`TriangleMesh::to_ply`]) reads back
/// with the same triangles. Faces whose indices repeat (zero area) are kept.
pub fn parse_triangle_mesh(bytes: &[u8]) -> Result<TriangleMesh, FormatError> {
    if has_ply_magic(bytes) {
        parse_ply_mesh(bytes)
    } else {
        parse_obj(bytes)
    }
}

/// Wavefront OBJ: `v` and `f` statements read by the shared parser
/// ([`super::obj`]), polygons of at least 3 vertices fan-triangulated.
fn parse_obj(bytes: &[u8]) -> Result<TriangleMesh, FormatError> {
    let mut read = parse_obj_polygons(bytes, Corners::AtLeast(3)).map_err(obj_error)?;
    let vertices = std::mem::take(&mut read.vertices);
    let mut builder = MeshBuilder::from_vertices(vertices, |k| format!("OBJ vertex {}", k + 1))?;
    for (line, polygon) in read.polygons() {
        builder.face(polygon, || format!("OBJ line {line}"))?;
    }
    builder.finish()
}

/// The [`FormatError`] of an OBJ defect.
fn obj_error(defect: ObjDefect) -> FormatError {
    let bad = |line: usize, reason: String| FormatError::ObjBadLine { line, reason };
    let at = |line: usize| format!("OBJ line {line}");
    match defect {
        ObjDefect::NotUtf8 { line } => FormatError::ObjNotUtf8 { line },
        ObjDefect::NotAsciiSpace { line, space } => bad(
            line,
            format!(
                "whitespace U+{:04X} is not an OBJ separator (use ASCII spaces or tabs)",
                u32::from(space)
            ),
        ),
        ObjDefect::VertexNotNumber { line, token } => {
            bad(line, format!("vertex value '{token}' is not a number"))
        }
        ObjDefect::VertexTooFewValues { line, count } => bad(
            line,
            format!("a vertex needs x, y and z, this one has {count} values"),
        ),
        ObjDefect::VertexNotFinite { line, axis, value } => FormatError::MeshNonFiniteVertex {
            location: at(line),
            axis,
            value,
        },
        ObjDefect::TooManyVertices { count } => FormatError::MeshTooManyVertices {
            count,
            max: u32::MAX as usize,
        },
        ObjDefect::ReferenceNotIndex { line, token } => {
            bad(line, format!("face reference '{token}' is not a vertex index"))
        }
        ObjDefect::ReferenceZero { line, .. } => bad(
            line,
            "vertex index 0 is invalid: OBJ indices start at 1".into(),
        ),
        ObjDefect::ReferenceBeforeFirst {
            line,
            index,
            defined,
        } => bad(
            line,
            format!(
                "relative vertex index {index} reaches before the first vertex ({defined} defined so far)"
            ),
        ),
        ObjDefect::ReferenceTooLarge {
            line,
            index,
            defined,
            ..
        } => FormatError::MeshIndexOutOfRange {
            location: at(line),
            index,
            vertices: defined,
        },
        ObjDefect::FaceCorners { line, count } => FormatError::MeshDegenerateFace {
            location: at(line),
            count,
        },
        ObjDefect::ReferenceOutOfRange {
            line,
            index,
            vertices,
        } => FormatError::MeshIndexOutOfRange {
            location: at(line),
            index,
            vertices,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> TriangleMesh {
        let vertices = (0..8)
            .map(|i| {
                [
                    (i & 1) as f64,
                    ((i >> 1) & 1) as f64 * 0.5,
                    (i >> 2) as f64 - 0.25,
                ]
            })
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        TriangleMesh::from_quads(vertices, &quads)
    }

    fn f32_vertices(mesh: &TriangleMesh) -> TriangleMesh {
        TriangleMesh {
            vertices: mesh
                .vertices
                .iter()
                .map(|v| v.map(|c| f64::from(c as f32)))
                .collect(),
            triangles: mesh.triangles.clone(),
        }
    }

    fn err(text: &str) -> FormatError {
        parse_triangle_mesh(text.as_bytes()).unwrap_err()
    }

    #[test]
    fn obj_round_trips_bit_for_bit() {
        let mut mesh = cube();
        mesh.vertices[3] = [0.1, -1e-300, 123456.789];
        assert_eq!(parse_triangle_mesh(&mesh.to_obj()).unwrap(), mesh);
    }

    #[test]
    fn ply_round_trips_in_both_encodings() {
        let mesh = cube();
        for ascii in [true, false] {
            let read = parse_triangle_mesh(&mesh.to_ply(ascii)).unwrap();
            assert_eq!(read, f32_vertices(&mesh), "ascii {ascii}");
        }
        let mut odd = cube();
        odd.vertices[5] = [0.1, 1.0 / 3.0, -7.3e5];
        for ascii in [true, false] {
            assert_eq!(
                parse_triangle_mesh(&odd.to_ply(ascii)).unwrap(),
                f32_vertices(&odd)
            );
        }
    }

    #[test]
    fn obj_polygons_references_and_comments() {
        let text = "# a quad and a triangle\r\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\n\
                    v 1 1 0 0.5 0.5 0.5\nv 0 1 0\nvt 0 0\nvn 0 0 1\ng quad\nusemtl red\ns off\n\
                    f 1/1/1 2/1/1 3//1 4 # fan\n\n   \nv 2 2 2\nf -1 -5 -4\nl 1 2\n";
        let mesh = parse_triangle_mesh(text.as_bytes()).unwrap();
        assert_eq!(mesh.vertices.len(), 5);
        assert_eq!(mesh.vertices[2], [1.0, 1.0, 0.0]);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3], [4, 0, 1]]);
    }

    #[test]
    fn obj_forward_references_are_resolved_at_the_end() {
        let mesh = parse_triangle_mesh(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
        assert_eq!(
            err("v 0 0 0\nv 1 0 0\nf 1 2 9\nv 0 1 0\n"),
            FormatError::MeshIndexOutOfRange {
                location: "OBJ line 3".into(),
                index: 9,
                vertices: 3
            }
        );
    }

    #[test]
    fn obj_errors_name_the_line_and_problem() {
        let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
        let cases: [(String, &str); 11] = [
            (format!("{tri}f 1 2 x\n"), "line 4: face reference 'x'"),
            (
                format!("{tri}f 1 0 2\n"),
                "line 4: vertex index 0 is invalid",
            ),
            (format!("{tri}f 1 -4 2\n"), "relative vertex index -4"),
            (
                format!("{tri}f 1 2\n"),
                "line 4: a face needs at least 3 vertices, this one has 2",
            ),
            (format!("{tri}f\n"), "this one has 0"),
            (
                "v 0 0\n".into(),
                "line 1: a vertex needs x, y and z, this one has 2",
            ),
            ("v 0 zero 0\n".into(), "vertex value 'zero' is not a number"),
            (
                format!("{tri}v 0 NaN 0\nf 1 2 3\n"),
                "line 4: coordinate y is NaN",
            ),
            (format!("v inf 0 0\n{tri}"), "line 1: coordinate x is inf"),
            (tri.into(), "3 vertices but no faces"),
            ("# nothing\n\n".into(), "no vertices"),
        ];
        for (text, expected) in cases {
            let message = err(&text).to_string();
            assert!(message.contains(expected), "{text:?}: {message}");
        }
        assert_eq!(err(""), FormatError::MeshNoVertices);
        assert_eq!(
            parse_triangle_mesh(b"v 0 0 0\nv 1 0 0\n\xff\xfe\n").unwrap_err(),
            FormatError::ObjNotUtf8 { line: 3 }
        );
        assert!(err(&format!("{tri}f 1 2 99999999999\n"))
            .to_string()
            .contains("99999999999"));
    }

    #[test]
    fn obj_reports_the_first_defect_in_file_order() {
        // A defect before an invalid UTF-8 line is the one reported.
        assert!(matches!(
            parse_triangle_mesh(b"v 0 0\n\xff\n").unwrap_err(),
            FormatError::ObjBadLine { line: 1, .. }
        ));
        // `v` and `f` lines are separated by ASCII whitespace only.
        for text in ["v\u{a0}0 0 0\n", "v 0\u{b}0 0\n"] {
            let message = err(text).to_string();
            assert!(message.contains("is not an OBJ separator"), "{message}");
        }
        assert!(
            parse_triangle_mesh("g a\u{a0}b\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".as_bytes())
                .is_ok()
        );
    }

    /// A PLY header with float vertices and the given face list property.
    fn ply_header(encoding: &str, vertices: usize, faces: usize, list: &str) -> String {
        format!(
            "ply\nformat {encoding} 1.0\nelement vertex {vertices}\nproperty float x\nproperty float y\n\
             property float z\nelement face {faces}\n{list}\nend_header\n"
        )
    }

    #[test]
    fn ply_polygons_types_and_byte_orders() {
        // A quad as one face of type `list ushort double`, vertices as doubles,
        // a camera element before and an edge element after.
        for big in [false, true] {
            let encoding = if big {
                "binary_big_endian"
            } else {
                "binary_little_endian"
            };
            let header = format!(
                "ply\nformat {encoding} 1.0\nelement camera 1\nproperty list uchar float k\n\
                 element vertex 4\nproperty double x\nproperty uchar flags\nproperty double y\n\
                 property double z\nelement face 1\nproperty uchar kind\nproperty list ushort double vertex_index\n\
                 element edge 1\nproperty int a\nend_header\n"
            );
            let mut bytes = header.into_bytes();
            let push = |bytes: &mut Vec<u8>, le: &[u8]| {
                let mut v = le.to_vec();
                if big {
                    v.reverse();
                }
                bytes.extend(v);
            };
            push(&mut bytes, &[2]);
            push(&mut bytes, &1.5f32.to_le_bytes());
            push(&mut bytes, &2.5f32.to_le_bytes());
            let corners = [
                [0.0, 0.0, 0.1],
                [1.0, 0.0, 0.2],
                [1.0, 1.0, 0.3],
                [0.0, 1.0, 0.4],
            ];
            for [x, y, z] in corners {
                push(&mut bytes, &f64::to_le_bytes(x));
                push(&mut bytes, &[7]);
                push(&mut bytes, &f64::to_le_bytes(y));
                push(&mut bytes, &f64::to_le_bytes(z));
            }
            push(&mut bytes, &[9]);
            push(&mut bytes, &4u16.to_le_bytes());
            for i in [3.0f64, 2.0, 1.0, 0.0] {
                push(&mut bytes, &i.to_le_bytes());
            }
            let mesh = parse_triangle_mesh(&bytes).unwrap();
            assert_eq!(mesh.vertices, corners);
            // The edge record after the faces is missing: it is not needed.
            assert_eq!(mesh.triangles, vec![[3, 2, 1], [3, 1, 0]]);
        }
        let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty int x\nproperty int y\nproperty short z\n\
                    element face 2\nproperty list uchar uint vertex_indices\nproperty float quality\nend_header\n\
                    0 0 0\n1 0 0\n\n1 1 -5\n0 1 0\n4 0 1 2 3 0.5\n3 3 2 1 1\n";
        let mesh = parse_triangle_mesh(text.as_bytes()).unwrap();
        assert_eq!(mesh.vertices[2], [1.0, 1.0, -5.0]);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3], [3, 2, 1]]);
    }

    #[test]
    fn ply_errors_name_the_problem() {
        let list = "property list uchar int vertex_indices";
        let ascii =
            |faces: usize, body: &str| format!("{}{body}", ply_header("ascii", 3, faces, list));
        let vertices = "0 0 0\n1 0 0\n0 1 0\n";
        let cases = [
            (ascii(1, &format!("{vertices}3 0 1 3\n")), "PLY face 0: vertex index 3 is out of range (the mesh has 3 vertices)"),
            (ascii(1, &format!("{vertices}3 0 -1 2\n")), "PLY face 0: vertex index -1 is not a non-negative integer"),
            (ascii(1, &format!("{vertices}2 0 1\n")), "PLY face 0: a face needs at least 3 vertices, this one has 2"),
            (ascii(1, "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), "PLY vertex 1: coordinate y is NaN"),
            (ascii(2, &format!("{vertices}3 0 1 2\n")), "element 'face' is truncated: expected 2 records, got 1"),
            (ascii(1, "0 0 0\n"), "element 'vertex' is truncated: expected 3 records, got 1"),
            (ascii(0, vertices), "no 'face' element"),
            (ascii(1, &format!("{vertices}3 0 1\n")), "needs more than"),
            (
                format!("{}{vertices}", ply_header("ascii", 3, 1, "property float area")),
                "no list property of vertex indices",
            ),
            (
                format!("{}{vertices}3 0 1.5 2\n", ply_header("ascii", 3, 1, "property list uchar float vertex_indices")),
                "vertex index 1.5 is not a non-negative integer",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n".into(),
                "no 'face' element",
            ),
        ];
        for (text, expected) in cases {
            let message = parse_triangle_mesh(text.as_bytes())
                .unwrap_err()
                .to_string();
            assert!(message.contains(expected), "{text:?}: {message}");
        }
        // Binary: an index out of range, a negative list length, a truncated face.
        let mut bytes = ply_header(
            "binary_little_endian",
            3,
            1,
            "property list char int vertex_indices",
        )
        .into_bytes();
        for v in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
            v.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
        }
        let good = |indices: [i32; 3]| {
            let mut b = bytes.clone();
            b.push(3);
            indices.iter().for_each(|i| b.extend(i.to_le_bytes()));
            b
        };
        assert!(parse_triangle_mesh(&good([0, 1, 2])).is_ok());
        let message = parse_triangle_mesh(&good([0, 7, 2]))
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("vertex index 7 is out of range"),
            "{message}"
        );
        let mut negative = bytes.clone();
        negative.push(0xff);
        assert!(matches!(
            parse_triangle_mesh(&negative),
            Err(FormatError::PlyBadListLength { record: 0, .. })
        ));
        let whole = good([0, 1, 2]);
        for len in 0..whole.len() {
            assert!(parse_triangle_mesh(&whole[..len]).is_err(), "cut at {len}");
        }
        assert!(matches!(
            parse_triangle_mesh(&whole[..whole.len() - 1]),
            Err(FormatError::PlyTruncatedElement {
                got: 0,
                expected: 1,
                ..
            })
        ));
    }

    #[test]
    fn random_and_corrupted_bytes_never_panic() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let valid = [cube().to_obj(), cube().to_ply(true), cube().to_ply(false)];
        for base in &valid {
            for _ in 0..2000 {
                let mut bytes = base.clone();
                for _ in 0..rng.random_range(1..4) {
                    let at = rng.random_range(0..bytes.len());
                    bytes[at] = rng.random();
                }
                let cut = rng.random_range(0..=bytes.len());
                let _ = parse_triangle_mesh(&bytes);
                let _ = parse_triangle_mesh(&bytes[..cut]);
            }
        }
        for _ in 0..2000 {
            let len = rng.random_range(0..200);
            let bytes: Vec<u8> = (0..len).map(|_| rng.random_range(0..128)).collect();
            let _ = parse_triangle_mesh(&bytes);
        }
    }

    #[test]
    fn huge_face_counts_neither_hang_nor_allocate() {
        let header = ply_header(
            "binary_little_endian",
            3,
            usize::MAX / 2,
            "property list uchar int vertex_indices",
        );
        let mut bytes = header.into_bytes();
        bytes.extend([0u8; 36]);
        bytes.extend([3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0]);
        assert!(matches!(
            parse_triangle_mesh(&bytes),
            Err(FormatError::PlyTruncatedElement { got: 1, .. })
        ));
    }
}
