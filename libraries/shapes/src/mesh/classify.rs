//! The paper's classification of vertices and edges (Section 2): regular and
//! extraordinary vertices (inner and boundary), corners, and regular, extraordinary
//! and boundary edges, with the counts the dimension formula uses.

use super::quad_mesh::QuadMesh;

/// Kind of a vertex. The valence N is the number of edges at the vertex; on the
/// boundary the paper counts patches instead, kappa = N - 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VertexKind {
    /// Inner vertex of valence 4 (RV).
    InnerRegular,
    /// Inner vertex of valence N != 4 (inner EV).
    InnerExtraordinary,
    /// Boundary vertex with two faces (valence 3).
    BoundaryRegular,
    /// Boundary vertex with a single face (valence 2).
    Corner,
    /// Boundary vertex with three or more faces (boundary EV, kappa = N - 1 >= 3).
    BoundaryExtraordinary,
}

impl VertexKind {
    /// Whether this is an extraordinary vertex, inner or on the boundary.
    pub fn is_extraordinary(self) -> bool {
        matches!(
            self,
            VertexKind::InnerExtraordinary | VertexKind::BoundaryExtraordinary
        )
    }
}

/// Kind of an edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EdgeKind {
    /// Inner edge whose two endpoints are not extraordinary.
    Regular,
    /// Inner edge with at least one extraordinary endpoint (where the gluing data
    /// differ from the C1 ones).
    Extraordinary,
    /// Edge of a single face.
    Boundary,
}

/// Per-vertex and per-edge kinds with the paper's counts.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshClassification {
    /// Kind of each vertex, by vertex index.
    pub vertices: Vec<VertexKind>,
    /// Valence N (number of edges) of each vertex.
    pub valences: Vec<usize>,
    /// Kind of each edge, by the edge indices of [`super::HalfEdgeMesh`].
    pub edges: Vec<EdgeKind>,
    /// Endpoints of each edge.
    pub edge_vertices: Vec<[u32; 2]>,
    /// n_V.
    pub n_v: usize,
    /// n_RV: inner regular vertices.
    pub n_rv: usize,
    /// n_IEV: inner extraordinary vertices.
    pub n_iev: usize,
    /// Regular boundary vertices (two faces).
    pub n_brv: usize,
    /// n_BEV: boundary extraordinary vertices.
    pub n_bev: usize,
    /// n_C: corners.
    pub n_c: usize,
    /// n_E.
    pub n_e: usize,
    /// n_RE: inner regular edges.
    pub n_re: usize,
    /// n_EE: inner extraordinary edges.
    pub n_ee: usize,
    /// n_BE: boundary edges.
    pub n_be: usize,
    /// n_F.
    pub n_f: usize,
}

impl MeshClassification {
    /// Whether the EVs are isolated in the paper's sense (Section 3.1: "EVs only
    /// attached to regular vertices"): no edge joins two extraordinary vertices.
    pub fn has_isolated_evs(&self) -> bool {
        self.edge_vertices.iter().all(|&[a, b]| {
            !(self.vertices[a as usize].is_extraordinary()
                && self.vertices[b as usize].is_extraordinary())
        })
    }

    /// Number of extraordinary vertices, inner and boundary.
    pub fn n_ev(&self) -> usize {
        self.n_iev + self.n_bev
    }
}

/// Classifies every vertex and edge of `mesh`.
pub fn classify(mesh: &QuadMesh) -> MeshClassification {
    let he = mesh.half_edges();
    let vertex_count = mesh.vertex_count();
    let mut vertices = Vec::with_capacity(vertex_count);
    let mut valences = Vec::with_capacity(vertex_count);
    for v in 0..vertex_count {
        let faces = he.faces_at(v);
        let kind = if he.is_boundary_vertex(v) {
            match faces {
                1 => VertexKind::Corner,
                2 => VertexKind::BoundaryRegular,
                _ => VertexKind::BoundaryExtraordinary,
            }
        } else if faces == 4 {
            VertexKind::InnerRegular
        } else {
            VertexKind::InnerExtraordinary
        };
        vertices.push(kind);
        valences.push(he.valence(v));
    }
    let edge_vertices: Vec<[u32; 2]> = (0..he.edge_count()).map(|e| he.edge_vertices(e)).collect();
    let edges: Vec<EdgeKind> = edge_vertices
        .iter()
        .enumerate()
        .map(|(e, &[a, b])| {
            if he.is_boundary_edge(e) {
                EdgeKind::Boundary
            } else if vertices[a as usize].is_extraordinary()
                || vertices[b as usize].is_extraordinary()
            {
                EdgeKind::Extraordinary
            } else {
                EdgeKind::Regular
            }
        })
        .collect();
    let count_v = |k: VertexKind| vertices.iter().filter(|&&x| x == k).count();
    let count_e = |k: EdgeKind| edges.iter().filter(|&&x| x == k).count();
    MeshClassification {
        n_v: vertex_count,
        n_rv: count_v(VertexKind::InnerRegular),
        n_iev: count_v(VertexKind::InnerExtraordinary),
        n_brv: count_v(VertexKind::BoundaryRegular),
        n_bev: count_v(VertexKind::BoundaryExtraordinary),
        n_c: count_v(VertexKind::Corner),
        n_e: edges.len(),
        n_re: count_e(EdgeKind::Regular),
        n_ee: count_e(EdgeKind::Extraordinary),
        n_be: count_e(EdgeKind::Boundary),
        n_f: mesh.face_count(),
        vertices,
        valences,
        edges,
        edge_vertices,
    }
}
