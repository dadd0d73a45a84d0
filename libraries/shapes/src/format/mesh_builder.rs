//! Building a triangle mesh from the vertices and polygons a reader finds:
//! every check and the fan triangulation, shared by the OBJ and PLY readers.

use super::mesh::TriangleMesh;
use super::FormatError;

/// Collects vertices and polygons, checks them and fan-triangulates.
#[derive(Debug, Default)]
pub(super) struct MeshBuilder {
    mesh: TriangleMesh,
}

impl MeshBuilder {
    /// A builder with room for the given counts (callers bound them by the input size).
    pub(super) fn with_capacity(vertices: usize, triangles: usize) -> Self {
        Self {
            mesh: TriangleMesh {
                vertices: Vec::with_capacity(vertices),
                triangles: Vec::with_capacity(triangles),
            },
        }
    }

    /// A builder holding `vertices` (moved, not copied: a reader that has
    /// them all already does not hold them twice), each checked as
    /// [`Self::vertex`] checks it; `location` names the k-th (0-based) in an error.
    pub(super) fn from_vertices(
        vertices: Vec<[f64; 3]>,
        location: impl FnOnce(usize) -> String,
    ) -> Result<Self, FormatError> {
        if vertices.len() > MAX_VERTICES {
            return Err(FormatError::MeshTooManyVertices {
                count: MAX_VERTICES + 1,
                max: MAX_VERTICES,
            });
        }
        let non_finite = vertices.iter().enumerate().find_map(|(i, xyz)| {
            let k = xyz.iter().position(|c| !c.is_finite())?;
            Some((i, k, xyz[k]))
        });
        if let Some((i, k, value)) = non_finite {
            return Err(FormatError::MeshNonFiniteVertex {
                location: location(i),
                axis: ['x', 'y', 'z'][k],
                value,
            });
        }
        let triangles = Vec::new();
        Ok(Self {
            mesh: TriangleMesh {
                vertices,
                triangles,
            },
        })
    }

    /// Adds a vertex; `location` names it in an error.
    pub(super) fn vertex(
        &mut self,
        xyz: [f64; 3],
        location: impl FnOnce() -> String,
    ) -> Result<(), FormatError> {
        if let Some(k) = xyz.iter().position(|c| !c.is_finite()) {
            return Err(FormatError::MeshNonFiniteVertex {
                location: location(),
                axis: ['x', 'y', 'z'][k],
                value: xyz[k],
            });
        }
        if self.mesh.vertices.len() >= MAX_VERTICES {
            return Err(FormatError::MeshTooManyVertices {
                count: self.mesh.vertices.len() + 1,
                max: MAX_VERTICES,
            });
        }
        self.mesh.vertices.push(xyz);
        Ok(())
    }

    /// Adds a polygon of vertex indices (each already checked by the caller to be
    /// a valid index of the finished mesh) as a triangle fan around its first vertex.
    pub(super) fn face(
        &mut self,
        indices: &[u32],
        location: impl FnOnce() -> String,
    ) -> Result<(), FormatError> {
        let [first, rest @ ..] = indices else {
            return Err(degenerate(location(), 0));
        };
        if rest.len() < 2 {
            return Err(degenerate(location(), indices.len()));
        }
        self.mesh
            .triangles
            .extend(rest.windows(2).map(|pair| [*first, pair[0], pair[1]]));
        Ok(())
    }

    /// The mesh, if it has vertices and at least one face whose indices are all
    /// in range (re-checked here, whatever the format checked before).
    pub(super) fn finish(self) -> Result<TriangleMesh, FormatError> {
        let vertices = self.mesh.vertices.len();
        if vertices == 0 {
            return Err(FormatError::MeshNoVertices);
        }
        if self.mesh.triangles.is_empty() {
            return Err(FormatError::MeshNoFaces { vertices });
        }
        let bad = self.mesh.triangles.iter().enumerate().find_map(|(t, tri)| {
            tri.iter()
                .find(|&&i| i as usize >= vertices)
                .map(|&i| (t, i))
        });
        if let Some((triangle, index)) = bad {
            return Err(FormatError::MeshIndexOutOfRange {
                location: format!("triangle {triangle}"),
                index: i64::from(index),
                vertices,
            });
        }
        Ok(self.mesh)
    }
}

/// Vertex count limit: every index must fit in the `u32` of [`TriangleMesh`].
const MAX_VERTICES: usize = u32::MAX as usize;

fn degenerate(location: String, count: usize) -> FormatError {
    FormatError::MeshDegenerateFace { location, count }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moved_vertices_are_checked_as_added_ones() {
        let vertices = vec![[0.0, 0.0, 0.0], [1.0, f64::NAN, 0.0]];
        let err = MeshBuilder::from_vertices(vertices, |k| format!("vertex {k}")).unwrap_err();
        assert!(
            matches!(
                &err,
                FormatError::MeshNonFiniteVertex { location, axis: 'y', value }
                    if location == "vertex 1" && value.is_nan()
            ),
            "{err:?}"
        );
        let vertices = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let mut builder = MeshBuilder::from_vertices(vertices, |k| k.to_string()).unwrap();
        builder.face(&[0, 1, 2], String::new).unwrap();
        let mesh = builder.finish().unwrap();
        assert_eq!((mesh.vertices.len(), mesh.triangles), (3, vec![[0, 1, 2]]));
    }
}
