//! The G1 constraints across the edges of a biquintic multipatch (Marsala et
//! al., eq. 1 with the quadratic symmetric gluing data of eq. 2, written on
//! Bezier coefficients as eq. 3): a sparse linear system whose null space is
//! the G1 space. It checks a coefficient vector (`defect`) and, on small
//! meshes, lets the dimension of Corollary 1 be verified against the rank.

use super::classify::VertexKind;
use super::dimension::G1Domain;
use super::error::MeshError;

// Bernstein coefficients per patch (6 x 6); coefficient `(i, j)` of face `f`
// is entry `36 f + 6 j + i`, `i` along the face's first side (corner 0 to 1),
// `j` along its last side (corner 0 to 3).
// Defined with the message that carries the patches, so that both agree.
pub use shroud_msg::COEFFICIENTS_PER_PATCH as PATCH_COEFFICIENTS;
const D: usize = 5;

/// One linear constraint: `sum coefficient * x[index] = 0`.
pub type Row = Vec<(usize, f64)>;

/// The constraints of every inner edge of `domain`: 6 for the continuity of
/// the edge curve and 7 for the cross derivatives (eq. 3, degree-elevated to
/// the degree 6 of its right-hand side).
pub fn g1_constraints(domain: &G1Domain) -> Result<Vec<Row>, MeshError> {
    let mesh = &domain.mesh;
    let c = &domain.classification;
    let he = mesh.half_edges();
    let mut rows = Vec::new();
    for e in 0..he.edge_count() {
        if he.is_boundary_edge(e) {
            continue;
        }
        let h = he.edge_half_edge(e);
        let Some(o) = he.opposite(h) else { continue };
        let [a, b] = c.edge_vertices[e];
        // The gluing data's parameter starts at the extraordinary end (eq. 2
        // with N' = 4: the EVs are isolated).
        let (p, q) = if c.vertices[b as usize].is_extraordinary() {
            (b, a)
        } else {
            (a, b)
        };
        let a0 = gluing_a0(c.vertices[p as usize], c.valences[p as usize]);
        let side0 = CornerFrame::new(mesh.faces()[he.face(h)], he.face(h), p, q)?;
        let side1 = CornerFrame::new(mesh.faces()[he.face(o)], he.face(o), p, q)?;
        edge_rows(&side0, &side1, a0, &mut rows);
    }
    Ok(rows)
}

/// The coefficient `a0` of the gluing data (2) at an edge's first vertex.
/// An inner EV of valence N splits the full turn 2 pi into N equal sector
/// angles: `a0 = 2 cos(2 pi / N)`. A boundary EV with kappa = N - 1 patches
/// splits the half turn pi into kappa sectors: `a0 = 2 cos(pi / kappa)`, the
/// choice of the G1 ACC construction at the boundary, which gives the
/// kappa + 3 vertex functions of Section 4.1.3 and vanishes, as the C1
/// gluing does, at a regular boundary vertex (kappa = 2).
pub fn gluing_a0(kind: VertexKind, valence: usize) -> f64 {
    use std::f64::consts::PI;
    match kind {
        VertexKind::InnerExtraordinary => 2.0 * (2.0 * PI / valence as f64).cos(),
        VertexKind::BoundaryExtraordinary => 2.0 * (PI / (valence - 1) as f64).cos(),
        _ => 0.0,
    }
}

/// The largest violation of `rows` by `x`, relative to the largest `|x|`.
pub fn defect(rows: &[Row], x: &[f64]) -> f64 {
    let scale = x
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    rows.iter()
        .map(|row| row.iter().map(|&(k, w)| w * x[k]).sum::<f64>().abs())
        .fold(0.0, f64::max)
        / scale
}

/// A face seen from its corner `p` toward its neighbour corner `q`:
/// coefficient indices by (position along the side from `p`, layer into the
/// face).
pub(super) struct CornerFrame {
    base: usize,
    origin: (isize, isize),
    along: (isize, isize),
    inward: (isize, isize),
}

impl CornerFrame {
    pub(super) fn new(corners: [u32; 4], face: usize, p: u32, q: u32) -> Result<Self, MeshError> {
        const POS: [(isize, isize); 4] = [(0, 0), (5, 0), (5, 5), (0, 5)];
        let k = corners
            .iter()
            .position(|&v| v == p)
            .ok_or(MeshError::Unsupported {
                what: "an edge whose endpoint is not a corner of its face",
            })?;
        let (next, prev) = ((k + 1) % 4, (k + 3) % 4);
        let (end, other) = if corners[next] == q {
            (next, prev)
        } else {
            (prev, next)
        };
        let unit = |to: usize| ((POS[to].0 - POS[k].0) / 5, (POS[to].1 - POS[k].1) / 5);
        Ok(Self {
            base: PATCH_COEFFICIENTS * face,
            origin: POS[k],
            along: unit(end),
            inward: unit(other),
        })
    }

    /// Index of the coefficient `s` along the edge, `t` layers in.
    pub(super) fn at(&self, s: usize, t: usize) -> usize {
        let (s, t) = (s as isize, t as isize);
        let i = self.origin.0 + s * self.along.0 + t * self.inward.0;
        let j = self.origin.1 + s * self.along.1 + t * self.inward.1;
        self.base + (6 * j + i) as usize
    }
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Eq. 3 on one edge: `e_i` the shared edge curve, `x_i = b_{i,1} - b_{i,0}`
/// the cross differences in each face; `x^(0) + x^(1)`, elevated to degree 6,
/// equals `a0 (1 - u)^2` times the edge curve's derivative differences.
fn edge_rows(s0: &CornerFrame, s1: &CornerFrame, a0: f64, rows: &mut Vec<Row>) {
    for i in 0..=D {
        rows.push(vec![(s0.at(i, 0), 1.0), (s1.at(i, 0), -1.0)]);
    }
    for k in 0..=D + 1 {
        let mut row: Row = Vec::new();
        // Degree elevation: L6_k = k/6 L_{k-1} + (1 - k/6) L_k.
        for (i, w) in [
            (k.wrapping_sub(1), k as f64 / 6.0),
            (k, 1.0 - k as f64 / 6.0),
        ] {
            if i > D || w == 0.0 {
                continue;
            }
            for s in [s0, s1] {
                row.push((s.at(i, 1), w));
                row.push((s.at(i, 0), -w));
            }
        }
        // (1 - u)^2 B4_k = C(4,k)/C(6,k) B6_k.
        if k < D && a0 != 0.0 {
            let w = a0 * binomial(4, k) / binomial(6, k);
            row.push((s0.at(k + 1, 0), -w));
            row.push((s0.at(k, 0), w));
        }
        rows.push(row);
    }
}
