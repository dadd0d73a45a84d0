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
use super::thin_plate::thin_plate_gram;
use crate::mesh::{G1Basis, G1Domain, PATCH_COEFFICIENTS};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use rayon::prelude::*;

/// One patch's share of the normal equations: lower-triangle entries of the
/// matrix and right-hand-side entries (`k dim + d`, value).
type FaceSystem = (Vec<Triplet<usize, usize, f64>>, Vec<(usize, f64)>);

/// A data point's parameters: a patch and a point of its unit square.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub face: usize,
    pub u: f64,
    pub v: f64,
}

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
        let (bu, bv) = (bernstein5(u), bernstein5(v));
        let base = face * PATCH_COEFFICIENTS;
        let mut out = vec![0.0; self.dim];
        for j in 0..6 {
            for i in 0..6 {
                let w = bu[i] * bv[j];
                let c = (base + 6 * j + i) * self.dim;
                for (d, o) in out.iter_mut().enumerate() {
                    *o += w * self.coefficients[c + d];
                }
            }
        }
        out
    }

    /// Eq. (28): smallest, largest and root-mean-square distance between each
    /// sample's value and the surface at its parameters.
    pub fn errors(&self, samples: &[Sample], values: &[f64]) -> FitErrors {
        let dist: Vec<f64> = samples
            .par_iter()
            .enumerate()
            .map(|(n, s)| {
                let q = self.evaluate(s.face, s.u, s.v);
                let p = &values[n * self.dim..(n + 1) * self.dim];
                q.iter()
                    .zip(p)
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>()
                    .sqrt()
            })
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
            domain,
            basis,
            per_face,
            thin: thin_plate_gram(),
        })
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
            for a in 0..P {
                let ba = b[a];
                let row = &mut gram[a * P..(a + 1) * P];
                for (g, bb) in row.iter_mut().zip(&b) {
                    *g += ba * bb;
                }
                for d in 0..dim {
                    right[a * dim + d] += ba * values[n * dim + d];
                }
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

impl SmoothSurface {
    /// A graph surface (`dim` 1 over a planar domain) as a quad mesh: each
    /// patch sampled on an `n x n` grid, at the domain's bilinear position with
    /// the fitted value as height. Patches keep their own border vertices.
    pub fn tessellate_graph(
        &self,
        domain: &crate::mesh::QuadMesh,
        n: usize,
    ) -> Result<crate::mesh::QuadMesh, crate::mesh::MeshError> {
        self.tessellate(domain, n, |mut p, value| {
            p[2] = value;
            p
        })
    }

    /// A radial surface (`dim` 1 over a closed mesh around the origin, such as
    /// the cube-sphere) as a quad mesh: the fitted value is the distance from
    /// the origin along the domain point's direction.
    pub fn tessellate_radial(
        &self,
        domain: &crate::mesh::QuadMesh,
        n: usize,
    ) -> Result<crate::mesh::QuadMesh, crate::mesh::MeshError> {
        self.tessellate(domain, n, |p, value| {
            let norm = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
                .sqrt()
                .max(f64::MIN_POSITIVE);
            p.map(|x| x / norm * value)
        })
    }

    fn tessellate(
        &self,
        domain: &crate::mesh::QuadMesh,
        n: usize,
        place: impl Fn([f64; 3], f64) -> [f64; 3],
    ) -> Result<crate::mesh::QuadMesh, crate::mesh::MeshError> {
        let n = n.max(1);
        let v = domain.vertices();
        let mut vertices = Vec::new();
        let mut quads = Vec::new();
        for (f, quad) in domain.faces().iter().enumerate() {
            let base = vertices.len() as u32;
            for b in 0..=n {
                for a in 0..=n {
                    let (u, w) = (a as f64 / n as f64, b as f64 / n as f64);
                    let weights = [(1.0 - u) * (1.0 - w), u * (1.0 - w), u * w, (1.0 - u) * w];
                    let mut p = [0.0; 3];
                    for (k, &corner) in quad.iter().enumerate() {
                        for (c, x) in p.iter_mut().enumerate() {
                            *x += weights[k] * v[corner as usize][c];
                        }
                    }
                    vertices.push(place(p, self.evaluate(f, u, w)[0]));
                }
            }
            let at = |a: usize, b: usize| base + (b * (n + 1) + a) as u32;
            for b in 0..n {
                for a in 0..n {
                    quads.push([at(a, b), at(a + 1, b), at(a + 1, b + 1), at(a, b + 1)]);
                }
            }
        }
        crate::mesh::QuadMesh::new(vertices, quads)
    }
}
