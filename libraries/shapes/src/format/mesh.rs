//! Triangle meshes for viewing surrogates in MeshLab, Blender or any OBJ/PLY viewer.

/// An indexed triangle mesh in world coordinates. Triangles are counter-clockwise
/// seen from the side their normal points to.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriangleMesh {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

impl TriangleMesh {
    /// A mesh from quads (each split along its `a`-`c` diagonal into two triangles
    /// with the quad's orientation).
    pub fn from_quads(vertices: Vec<[f64; 3]>, quads: &[[u32; 4]]) -> Self {
        let triangles = quads
            .iter()
            .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
            .collect();
        Self {
            vertices,
            triangles,
        }
    }

    /// Appends `other`, re-indexing its triangles past this mesh's vertices.
    pub fn merge(&mut self, other: &TriangleMesh) {
        // Meshes stay far below 2^32 vertices (tessellation is bounded by the grid).
        let offset = self.vertices.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|i| i + offset)));
    }

    /// Wavefront OBJ text: `v x y z` lines (shortest round-trip f64) and 1-based
    /// `f a b c` lines.
    pub fn to_obj(&self) -> Vec<u8> {
        let mut out = String::with_capacity(self.vertices.len() * 48 + self.triangles.len() * 24);
        out.push_str("# written by shroud\n");
        for [x, y, z] in &self.vertices {
            out.push_str(&format!("v {x} {y} {z}\n"));
        }
        for [a, b, c] in &self.triangles {
            out.push_str(&format!(
                "f {} {} {}\n",
                *a as u64 + 1,
                *b as u64 + 1,
                *c as u64 + 1
            ));
        }
        out.into_bytes()
    }
    // `to_ply` is written beside the other PLY writers, in `format::ply::write`.
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::parse_ply;

    fn square() -> TriangleMesh {
        TriangleMesh {
            vertices: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.5],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.25],
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn merge_reindexes_the_appended_mesh() {
        let mut mesh = square();
        mesh.merge(&square());
        assert_eq!(mesh.vertices.len(), 8);
        assert_eq!(mesh.triangles[2..], [[4, 5, 6], [4, 6, 7]]);
    }

    #[test]
    fn obj_has_one_based_faces() {
        let text = String::from_utf8(square().to_obj()).unwrap();
        let faces: Vec<&str> = text.lines().filter(|l| l.starts_with("f ")).collect();
        assert_eq!(faces, ["f 1 2 3", "f 1 3 4"]);
        assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 4);
        assert!(text.contains("v 1 0 0.5\n"));
    }

    #[test]
    fn ply_reads_back_with_faces_skipped() {
        for ascii in [true, false] {
            let bytes = square().to_ply(ascii);
            let cloud = parse_ply(&bytes).unwrap();
            let expected: Vec<[f32; 3]> = square()
                .vertices
                .iter()
                .map(|v| v.map(|c| c as f32))
                .collect();
            assert_eq!(cloud.points, expected);
            let text = String::from_utf8_lossy(&bytes);
            assert!(text.contains("element face 2\nproperty list uchar int vertex_indices\n"));
            if ascii {
                assert!(text.ends_with("3 0 1 2\n3 0 2 3\n"));
            } else {
                assert_eq!(
                    bytes.len(),
                    text.find("end_header\n").unwrap() + 11 + 4 * 12 + 2 * 13
                );
            }
        }
    }
}
