//! A local basis of the G1 space (Marsala et al., Section 4), computed rather
//! than written out: the coefficients of each patch are split as in eq. (11)
//! into face blocks (the 2 x 2 centre), edge blocks (positions 2, 3 along a
//! side, layers 0, 1) and vertex blocks (the 2 x 2 corner), and each feature's
//! functions are the null space of the G1 constraints restricted to the
//! coefficients near it, with everything else zero:
//!
//! * face: the centre block, which no constraint touches (Section 4.3);
//! * edge: the edge blocks of its one or two faces (Section 4.2);
//! * vertex: the corner blocks of its faces and the edge blocks of its edges,
//!   minus the span of those edges' functions (Section 4.1).
//!
//! With isolated EVs these spaces are independent and together have the
//! dimension of Corollary 1; the tests check both, and the G1 relations.

use super::dimension::G1Domain;
use super::error::MeshError;
use super::g1_constraints::{g1_constraints, CornerFrame, Row, PATCH_COEFFICIENTS};
use faer::Mat;
use std::collections::HashMap;

/// One basis function: its non-zero Bernstein coefficients, as (global
/// coefficient index `36 face + 6 j + i`, value).
pub type BasisFunction = Vec<(usize, f64)>;

/// What a basis function is attached to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    Vertex(usize),
    Edge(usize),
    Face(usize),
}

/// The basis of the G1 space over a domain.
#[derive(Debug, Clone)]
pub struct G1Basis {
    pub functions: Vec<BasisFunction>,
    pub features: Vec<Feature>,
    /// Patches x 36 coefficients.
    pub coefficients: usize,
}

/// Relative size below which a singular value counts as zero.
const RANK_TOLERANCE: f64 = 1e-10;

impl G1Basis {
    pub fn new(domain: &G1Domain) -> Result<Self, MeshError> {
        let rows = g1_constraints(domain)?;
        let by_column = rows_by_column(&rows);
        let mesh = &domain.mesh;
        let he = mesh.half_edges();
        let mut basis = G1Basis {
            functions: Vec::new(),
            features: Vec::new(),
            coefficients: PATCH_COEFFICIENTS * mesh.face_count(),
        };
        for f in 0..mesh.face_count() {
            for (i, j) in [(2, 2), (3, 2), (2, 3), (3, 3)] {
                basis.push(
                    Feature::Face(f),
                    vec![(PATCH_COEFFICIENTS * f + 6 * j + i, 1.0)],
                );
            }
        }
        let blocks = Blocks::new(domain)?;
        let mut edge_spaces: Vec<Vec<Vec<f64>>> = Vec::with_capacity(he.edge_count());
        for e in 0..he.edge_count() {
            let vars = &blocks.edge[e];
            let space = null_space(&rows, &by_column, vars);
            for v in &space {
                basis.push(Feature::Edge(e), sparse(vars, v));
            }
            edge_spaces.push(space);
        }
        for v in 0..mesh.vertex_count() {
            let mut vars = blocks.vertex[v].clone();
            let mut edges_here: Vec<Vec<f64>> = Vec::new();
            for &e in &blocks.vertex_edges[v] {
                let offset = vars.len();
                vars.extend_from_slice(&blocks.edge[e]);
                for f in &edge_spaces[e] {
                    let mut full = vec![0.0; offset];
                    full.extend_from_slice(f);
                    edges_here.push(full);
                }
            }
            let total = vars.len();
            for f in &mut edges_here {
                f.resize(total, 0.0);
            }
            let space = null_space(&rows, &by_column, &vars);
            for function in complement(&space, &edges_here) {
                basis.push(Feature::Vertex(v), sparse(&vars, &function));
            }
        }
        Ok(basis)
    }

    fn push(&mut self, feature: Feature, function: BasisFunction) {
        self.functions.push(function);
        self.features.push(feature);
    }

    pub fn len(&self) -> usize {
        self.functions.len()
    }

    pub fn is_empty(&self) -> bool {
        self.functions.is_empty()
    }

    /// The patch coefficients of `sum w_k B_k`.
    pub fn combine(&self, weights: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.coefficients];
        for (function, &w) in self.functions.iter().zip(weights) {
            for &(k, value) in function {
                out[k] += w * value;
            }
        }
        out
    }
}

/// Coefficient indices of each feature's blocks.
struct Blocks {
    vertex: Vec<Vec<usize>>,
    edge: Vec<Vec<usize>>,
    vertex_edges: Vec<Vec<usize>>,
}

impl Blocks {
    fn new(domain: &G1Domain) -> Result<Self, MeshError> {
        let mesh = &domain.mesh;
        let he = mesh.half_edges();
        let mut vertex = vec![Vec::new(); mesh.vertex_count()];
        let mut edge = vec![Vec::new(); he.edge_count()];
        let mut vertex_edges = vec![Vec::new(); mesh.vertex_count()];
        for h in 0..he.half_edge_count() {
            let f = he.face(h);
            let (p, q) = (he.origin(h), he.target(h));
            let frame = CornerFrame::new(mesh.faces()[f], f, p, q)?;
            // Each half-edge owns its origin's corner block in its face once.
            for (s, t) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                vertex[p as usize].push(frame.at(s, t));
            }
            let e = he.edge(h);
            for (s, t) in [(2, 0), (3, 0), (2, 1), (3, 1)] {
                edge[e].push(frame.at(s, t));
            }
            vertex_edges[p as usize].push(e);
            vertex_edges[q as usize].push(e);
        }
        for list in vertex
            .iter_mut()
            .chain(edge.iter_mut())
            .chain(vertex_edges.iter_mut())
        {
            list.sort_unstable();
            list.dedup();
        }
        Ok(Self {
            vertex,
            edge,
            vertex_edges,
        })
    }
}

fn rows_by_column(rows: &[Row]) -> HashMap<usize, Vec<usize>> {
    let mut map: HashMap<usize, Vec<usize>> = HashMap::new();
    for (r, row) in rows.iter().enumerate() {
        for &(k, _) in row {
            map.entry(k).or_default().push(r);
        }
    }
    map
}

/// An orthonormal basis of `{x on vars : A x = 0}`, other coefficients zero.
fn null_space(
    rows: &[Row],
    by_column: &HashMap<usize, Vec<usize>>,
    vars: &[usize],
) -> Vec<Vec<f64>> {
    let local: HashMap<usize, usize> = vars.iter().enumerate().map(|(i, &k)| (k, i)).collect();
    let mut touched: Vec<usize> = vars
        .iter()
        .flat_map(|k| by_column.get(k).into_iter().flatten().copied())
        .collect();
    touched.sort_unstable();
    touched.dedup();
    let n = vars.len();
    if touched.is_empty() {
        return (0..n).map(|i| unit(n, i)).collect();
    }
    let mut a = Mat::<f64>::zeros(touched.len(), n);
    for (r, &row) in touched.iter().enumerate() {
        for &(k, w) in &rows[row] {
            if let Some(&c) = local.get(&k) {
                a[(r, c)] += w;
            }
        }
    }
    let Ok(svd) = a.svd() else {
        return Vec::new();
    };
    let s = svd.S().column_vector();
    let largest = if s.nrows() > 0 { s[0] } else { 0.0 };
    let rank = (0..s.nrows())
        .filter(|&i| s[i] > RANK_TOLERANCE * largest.max(1.0))
        .count();
    let v = svd.V();
    (rank..n)
        .map(|j| (0..n).map(|i| v[(i, j)]).collect())
        .collect()
}

/// An orthonormal basis of the part of span(`space`) orthogonal to `inner`
/// (a subspace of it).
fn complement(space: &[Vec<f64>], inner: &[Vec<f64>]) -> Vec<Vec<f64>> {
    if space.is_empty() {
        return Vec::new();
    }
    let n = space[0].len();
    // Project `space` off an orthonormal basis of `inner` (Gram-Schmidt).
    let mut q: Vec<Vec<f64>> = Vec::new();
    for v in inner {
        let mut w = v.clone();
        for u in &q {
            let d = dot(&w, u);
            w.iter_mut().zip(u).for_each(|(a, b)| *a -= d * b);
        }
        let norm = dot(&w, &w).sqrt();
        if norm > RANK_TOLERANCE {
            q.push(w.iter().map(|x| x / norm).collect());
        }
    }
    let mut p = Mat::<f64>::zeros(n, space.len());
    for (j, v) in space.iter().enumerate() {
        let mut w = v.clone();
        for u in &q {
            let d = dot(&w, u);
            w.iter_mut().zip(u).for_each(|(a, b)| *a -= d * b);
        }
        for i in 0..n {
            p[(i, j)] = w[i];
        }
    }
    let Ok(svd) = p.svd() else {
        return Vec::new();
    };
    let s = svd.S().column_vector();
    let keep = (0..s.nrows()).filter(|&i| s[i] > 1e-8).count();
    let u = svd.U();
    (0..keep)
        .map(|j| (0..n).map(|i| u[(i, j)]).collect())
        .collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn unit(n: usize, i: usize) -> Vec<f64> {
    let mut v = vec![0.0; n];
    v[i] = 1.0;
    v
}

/// `values` on `vars`, dropping round-off zeros.
fn sparse(vars: &[usize], values: &[f64]) -> BasisFunction {
    vars.iter()
        .zip(values)
        .filter(|(_, v)| v.abs() > 1e-14)
        .map(|(&k, &v)| (k, v))
        .collect()
}
