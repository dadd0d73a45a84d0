//! A validated quad mesh: vertex positions and counter-clockwise quads.

use super::error::MeshError;
use super::half_edge::HalfEdgeMesh;

/// A manifold, consistently oriented quad mesh (possibly with boundary). Built only
/// through [`QuadMesh::new`], so the topology is always valid and its half-edge
/// adjacency is available without further checks.
#[derive(Debug, Clone, PartialEq)]
pub struct QuadMesh {
    vertices: Vec<[f64; 3]>,
    faces: Vec<[u32; 4]>,
    topology: HalfEdgeMesh,
}

impl QuadMesh {
    /// Validates and builds a quad mesh: at least one face, finite coordinates,
    /// indices in range, no repeated vertex in a face, every edge shared by at most two
    /// faces in opposite directions, every vertex used and its faces forming one fan.
    pub fn new(vertices: Vec<[f64; 3]>, faces: Vec<[u32; 4]>) -> Result<Self, MeshError> {
        if faces.is_empty() {
            return Err(MeshError::NoFaces);
        }
        if vertices.len() > u32::MAX as usize {
            return Err(MeshError::TooManyVertices {
                count: vertices.len(),
            });
        }
        if let Some(vertex) = vertices
            .iter()
            .position(|p| p.iter().any(|c| !c.is_finite()))
        {
            return Err(MeshError::NonFiniteVertex { vertex });
        }
        let topology = HalfEdgeMesh::build(vertices.len(), &faces)?;
        Ok(Self {
            vertices,
            faces,
            topology,
        })
    }

    /// Vertex positions.
    pub fn vertices(&self) -> &[[f64; 3]] {
        &self.vertices
    }

    /// Quads as vertex indices, counter-clockwise seen from outside.
    pub fn faces(&self) -> &[[u32; 4]] {
        &self.faces
    }

    /// The half-edge adjacency, built during validation.
    pub fn half_edges(&self) -> &HalfEdgeMesh {
        &self.topology
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// Number of undirected edges.
    pub fn edge_count(&self) -> usize {
        self.topology.edge_count()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// Whether the mesh has no boundary.
    pub fn is_closed(&self) -> bool {
        self.topology.boundary_loops().is_empty()
    }

    /// Euler characteristic V - E + F.
    pub fn euler_characteristic(&self) -> i64 {
        self.vertices.len() as i64 - self.edge_count() as i64 + self.faces.len() as i64
    }

    /// Gives back the vertices and faces.
    pub fn into_parts(self) -> (Vec<[f64; 3]>, Vec<[u32; 4]>) {
        (self.vertices, self.faces)
    }
}
