//! Eq. (26): the coefficients of the basis functions that minimise the squared
//! distances to the samples plus lambda times the thin-plate energy. Each
//! patch accumulates the 36 x 36 Gram matrix of its samples' Bernstein values
//! (plus lambda times the thin-plate form), which is then mapped onto the
//! basis functions alive on that patch; the sum over patches is a sparse
//! symmetric positive (semi)definite system, factorised by faer's sparse
//! Cholesky. Values have `dim` components: 1 for graphs, 3 for parametric
//! surfaces.

use super::bernstein::bernstein5;
use super::error::SmoothError;
use super::foot_point::PatchAdjacency;
use super::sample::Sample;
use super::thin_plate::thin_plate_gram;
use crate::mesh::{G1Basis, G1Domain, PATCH_COEFFICIENTS};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use rayon::prelude::*;

/// One patch's share of the normal equations: lower-triangle entries of the
/// matrix and right-hand-side entries (`k dim + d`, value).
type FaceSystem = (Vec<Triplet<usize, usize, f64>>, Vec<(usize, f64)>);

/// The error measures of eq. (28) over the samples.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FitErrors {
    pub min: f64,
    pub max: f64,
    pub rmse: f64,
}

/// A fitted multipatch: per face, 36 Bernstein coefficients of `dim` values.
#[derive(Debug, Clone, PartialEq)]
pub struct SmoothSurface {
    pub dim: usize,
    /// `coefficients[(36 face + 6 j + i) dim + d]`.
    pub coefficients: Vec<f64>,
    /// The basis weights, `weights[k dim + d]`.
    pub weights: Vec<f64>,
}

impl SmoothSurface {
    pub fn faces(&self) -> usize {
        self.coefficients.len() / (PATCH_COEFFICIENTS * self.dim)
    }

    /// The surface's value on `face` at `(u, v)`.
    pub fn evaluate(&self, face: usize, u: f64, v: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.dim];
        self.evaluate_into(face, u, v, &mut out);
        out
    }

    /// As [`Self::evaluate`], into `out` (`dim` values): no allocation in
    /// loops over many samples.
    fn evaluate_into(&self, face: usize, u: f64, v: f64, out: &mut [f64]) {
        let (bu, bv) = (bernstein5(u), bernstein5(v));
        let base = face * PATCH_COEFFICIENTS;
        out.fill(0.0);
        for j in 0..6 {
            for i in 0..6 {
                let w = bu[i] * bv[j];
                let c = (base + 6 * j + i) * self.dim;
                for (d, o) in out.iter_mut().enumerate() {
                    *o += w * self.coefficients[c + d];
                }
            }
        }
    }

    /// Eq. (28): smallest, largest and root-mean-square distance between each
    /// sample's value and the surface at its parameters.
    pub fn errors(&self, samples: &[Sample], values: &[f64]) -> FitErrors {
        let dist: Vec<f64> = samples
            .par_iter()
            .enumerate()
            .map_init(
                || vec![0.0; self.dim],
                |q, (n, s)| {
                    self.evaluate_into(s.face, s.u, s.v, q);
                    let p = &values[n * self.dim..(n + 1) * self.dim];
                    q.iter()
                        .zip(p)
                        .map(|(a, b)| (a - b) * (a - b))
                        .sum::<f64>()
                        .sqrt()
                },
            )
            .collect();
        if dist.is_empty() {
            return FitErrors::default();
        }
        FitErrors {
            min: dist.iter().copied().fold(f64::INFINITY, f64::min),
            max: dist.iter().copied().fold(0.0, f64::max),
            rmse: (dist.iter().map(|d| d * d).sum::<f64>() / dist.len() as f64).sqrt(),
        }
    }
}

/// The G1 space over a domain, ready to fit.
#[derive(Debug)]
pub struct SmoothFitter {
    pub domain: G1Domain,
    pub basis: G1Basis,
    /// Per face: the functions alive on it and their 36 local coefficients.
    per_face: Vec<Vec<(usize, [f64; PATCH_COEFFICIENTS])>>,
    thin: Vec<f64>,
    adjacency: PatchAdjacency,
}

impl SmoothFitter {
    pub fn new(domain: G1Domain) -> Result<Self, SmoothError> {
        let basis = G1Basis::new(&domain)?;
        let mut per_face: Vec<Vec<(usize, [f64; PATCH_COEFFICIENTS])>> =
            vec![Vec::new(); domain.mesh.face_count()];
        for (k, function) in basis.functions.iter().enumerate() {
            for &(index, value) in function {
                let (face, local) = (index / PATCH_COEFFICIENTS, index % PATCH_COEFFICIENTS);
                // A vertex function's coefficients alternate between its
                // faces: one entry per (function, face), found or added.
                let list = &mut per_face[face];
                let slot = match list.iter().position(|(kk, _)| *kk == k) {
                    Some(slot) => slot,
                    None => {
                        list.push((k, [0.0; PATCH_COEFFICIENTS]));
                        list.len() - 1
                    }
                };
                list[slot].1[local] = value;
            }
        }
        Ok(Self {
            adjacency: PatchAdjacency::new(&domain.mesh),
            domain,
            basis,
            per_face,
            thin: thin_plate_gram(),
        })
    }

    /// Non-zeros in the lower triangle of the normal matrix of eq. (26): the
    /// pairs of functions that share a patch (what the sparse factorisation
    /// and the memory of a fit grow with, beside the points).
    pub fn normal_matrix_nonzeros(&self) -> usize {
        let mut pairs: Vec<(usize, usize)> = self
            .per_face
            .iter()
            .flat_map(|active| {
                active.iter().flat_map(move |(kx, _)| {
                    active
                        .iter()
                        .filter(move |(ky, _)| ky <= kx)
                        .map(move |(ky, _)| (*kx, *ky))
                })
            })
            .collect();
        pairs.sort_unstable();
        pairs.dedup();
        pairs.len()
    }

    /// Which patch lies across each side of each patch.
    pub fn adjacency(&self) -> &PatchAdjacency {
        &self.adjacency
    }

    /// Minimises eq. (26) for `samples` with `dim` values each (`values[n dim + d]`).
    pub fn fit(
        &self,
        samples: &[Sample],
        values: &[f64],
        dim: usize,
        lambda: f64,
    ) -> Result<SmoothSurface, SmoothError> {
        self.check(samples, values, dim, lambda)?;
        let faces = self.domain.mesh.face_count();
        let mut by_face: Vec<Vec<usize>> = vec![Vec::new(); faces];
        for (n, s) in samples.iter().enumerate() {
            by_face[s.face].push(n);
        }
        let n = self.basis.len();
        let local: Vec<FaceSystem> = (0..faces)
            .into_par_iter()
            .map(|f| self.face_system(f, &by_face[f], samples, values, dim, lambda))
            .collect();
        let mut rhs = Mat::<f64>::zeros(n, dim);
        let mut triplets = Vec::new();
        for (t, r) in local {
            triplets.extend(t);
            for (at, value) in r {
                rhs[(at / dim, at % dim)] += value;
            }
        }
        // Patches share functions: sum the entries they both contribute.
        triplets.sort_unstable_by_key(|t| (t.col, t.row));
        let mut merged: Vec<Triplet<usize, usize, f64>> = Vec::with_capacity(triplets.len());
        for t in triplets {
            match merged.last_mut() {
                Some(m) if m.row == t.row && m.col == t.col => m.val += t.val,
                _ => merged.push(t),
            }
        }
        let matrix =
            SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &merged).map_err(|_| {
                SmoothError::Underdetermined {
                    points: samples.len(),
                    functions: n,
                }
            })?;
        let llt = matrix
            .sp_cholesky(Side::Lower)
            .map_err(|_| SmoothError::Underdetermined {
                points: samples.len(),
                functions: n,
            })?;
        let solution = llt.solve(&rhs);
        let mut weights = vec![0.0; n * dim];
        for k in 0..n {
            for d in 0..dim {
                weights[k * dim + d] = solution[(k, d)];
            }
        }
        if weights.iter().any(|w| !w.is_finite()) {
            return Err(SmoothError::Underdetermined {
                points: samples.len(),
                functions: n,
            });
        }
        Ok(SmoothSurface {
            dim,
            coefficients: self.patch_coefficients(&weights, dim),
            weights,
        })
    }

    fn check(
        &self,
        samples: &[Sample],
        values: &[f64],
        dim: usize,
        lambda: f64,
    ) -> Result<(), SmoothError> {
        if !(lambda.is_finite() && lambda >= 0.0) {
            return Err(SmoothError::Lambda(lambda));
        }
        if dim == 0 || values.len() != samples.len() * dim {
            return Err(SmoothError::ValueCount {
                values: values.len(),
                samples: samples.len(),
                dim,
            });
        }
        let faces = self.domain.mesh.face_count();
        let inside = |t: f64| (-1e-9..=1.0 + 1e-9).contains(&t);
        for (index, s) in samples.iter().enumerate() {
            let row = &values[index * dim..(index + 1) * dim];
            if !(s.u.is_finite() && s.v.is_finite()) || row.iter().any(|x| !x.is_finite()) {
                return Err(SmoothError::NonFinite { index });
            }
            if s.face >= faces {
                return Err(SmoothError::NoSuchFace {
                    index,
                    face: s.face,
                    faces,
                });
            }
            if !(inside(s.u) && inside(s.v)) {
                return Err(SmoothError::OutsidePatch {
                    index,
                    u: s.u,
                    v: s.v,
                });
            }
        }
        Ok(())
    }

    /// One patch's contribution: lower-triangle triplets of the normal matrix
    /// and right-hand-side entries (`k dim + d`, value).
    fn face_system(
        &self,
        face: usize,
        members: &[usize],
        samples: &[Sample],
        values: &[f64],
        dim: usize,
        lambda: f64,
    ) -> FaceSystem {
        const P: usize = PATCH_COEFFICIENTS;
        let mut gram = vec![0.0; P * P];
        let mut right = vec![0.0; P * dim];
        for &n in members {
            let s = samples[n];
            let (bu, bv) = (bernstein5(s.u), bernstein5(s.v));
            let mut b = [0.0; P];
            for j in 0..6 {
                for i in 0..6 {
                    b[6 * j + i] = bu[i] * bv[j];
                }
            }
            // The Gram matrix is symmetric: accumulate its lower triangle
            // only (half the work of the hottest loop), mirrored below.
            for a in 0..P {
                let ba = b[a];
                let row = &mut gram[a * P..a * P + a + 1];
                for (g, bb) in row.iter_mut().zip(&b) {
                    *g += ba * bb;
                }
                for d in 0..dim {
                    right[a * dim + d] += ba * values[n * dim + d];
                }
            }
        }
        for a in 0..P {
            for c in 0..a {
                gram[c * P + a] = gram[a * P + c];
            }
        }
        if lambda > 0.0 {
            gram.iter_mut()
                .zip(&self.thin)
                .for_each(|(g, t)| *g += lambda * t);
        }
        let active = &self.per_face[face];
        // G C, then C^T (G C): m functions.
        let gc: Vec<[f64; P]> = active
            .iter()
            .map(|(_, c)| {
                let mut out = [0.0; P];
                for (a, o) in out.iter_mut().enumerate() {
                    *o = (0..P).map(|b| gram[a * P + b] * c[b]).sum();
                }
                out
            })
            .collect();
        let mut triplets = Vec::new();
        for (kx, cx) in active.iter() {
            for (y, (ky, _)) in active.iter().enumerate() {
                // The lower triangle of the global matrix: row >= column.
                if ky > kx {
                    continue;
                }
                let value: f64 = cx.iter().zip(&gc[y]).map(|(a, b)| a * b).sum();
                if value != 0.0 {
                    triplets.push(Triplet::new(*kx, *ky, value));
                }
            }
        }
        let mut rhs = Vec::with_capacity(active.len() * dim);
        for (k, c) in active {
            for d in 0..dim {
                let value: f64 = (0..P).map(|a| c[a] * right[a * dim + d]).sum();
                rhs.push((k * dim + d, value));
            }
        }
        (triplets, rhs)
    }

    fn patch_coefficients(&self, weights: &[f64], dim: usize) -> Vec<f64> {
        let mut out = vec![0.0; self.domain.mesh.face_count() * PATCH_COEFFICIENTS * dim];
        for (k, function) in self.basis.functions.iter().enumerate() {
            for &(index, value) in function {
                for d in 0..dim {
                    out[index * dim + d] += value * weights[k * dim + d];
                }
            }
        }
        out
    }
}
