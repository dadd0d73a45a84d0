//! The dimension of the G1 ACC space of biquintic patches over a quad mesh
//! (Marsala et al., Corollary 1), feature by feature as Section 4 builds its
//! basis, and the domain preparation it presumes: isolated extraordinary
//! vertices (Section 3.1), obtained by one Catmull-Clark step when missing.

use super::catmull_clark::catmull_clark;
use super::classify::{classify, MeshClassification, VertexKind};
use super::error::MeshError;
use super::quad_mesh::QuadMesh;

/// Basis functions per feature (Sections 4.1-4.3) and their total.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct G1Dimension {
    /// Vertex functions: N + 3 at an inner EV of valence N (value, two first
    /// derivatives, N cross derivatives), kappa + 3 = N + 2 at a boundary EV
    /// with kappa patches, 4 at a regular vertex, boundary or inner, and a corner.
    pub vertex: usize,
    /// Edge functions: 2 on an extraordinary edge (eq. 21), 4 on a regular inner
    /// edge (corank of eq. 22) and on a boundary edge.
    pub edge: usize,
    /// Face functions: the 4 central Bezier coefficients of each patch.
    pub face: usize,
}

impl G1Dimension {
    /// Corollary 1: `sum N_EV + 3 n_IEV + 2 (n_BEV + n_EE) + 4 (n_RE + n_BE +
    /// n_RV + n_C + n_F)`, with `n_RV` counting boundary regular vertices too
    /// (Section 4.1.3 gives them four functions).
    pub fn of(c: &MeshClassification) -> Self {
        let vertex = c
            .vertices
            .iter()
            .zip(&c.valences)
            .map(|(kind, &n)| match kind {
                VertexKind::InnerExtraordinary => n + 3,
                VertexKind::BoundaryExtraordinary => n + 2,
                VertexKind::InnerRegular | VertexKind::BoundaryRegular | VertexKind::Corner => 4,
            })
            .sum();
        Self {
            vertex,
            edge: 2 * c.n_ee + 4 * (c.n_re + c.n_be),
            face: 4 * c.n_f,
        }
    }

    pub fn total(&self) -> usize {
        self.vertex + self.edge + self.face
    }
}

/// A mesh ready to carry the G1 space, with its classification.
#[derive(Debug, Clone)]
pub struct G1Domain {
    pub mesh: QuadMesh,
    pub classification: MeshClassification,
    /// Whether the input had adjacent extraordinary vertices and was refined
    /// once (after one Catmull-Clark step every EV is surrounded by regular
    /// vertices) — the caller tells the user.
    pub refined: bool,
}

impl G1Domain {
    pub fn new(mesh: QuadMesh) -> Result<Self, MeshError> {
        let classification = classify(&mesh);
        if classification.has_isolated_evs() {
            return Ok(Self {
                mesh,
                classification,
                refined: false,
            });
        }
        let mesh = catmull_clark(&mesh)?;
        let classification = classify(&mesh);
        Ok(Self {
            mesh,
            classification,
            refined: true,
        })
    }

    pub fn dimension(&self) -> G1Dimension {
        G1Dimension::of(&self.classification)
    }
}
