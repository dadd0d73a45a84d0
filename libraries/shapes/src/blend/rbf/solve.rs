//! The dense interpolation system of Eq. 1: `[A P; P^T 0] [lambda; c] = [f; 0]` with
//! `A_ij = |x_i - x_j|^3` and `P_i = [1, x_i]`, solved with faer's Bunch-Kaufman
//! LBL^T (symmetric indefinite), falling back to LU with partial pivoting, and
//! checked by its residual: a singular system is an error, never garbage.

use super::eval::Rbf;
use super::projection::cube;
use crate::blend::error::BlendError;
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use glam::DVec3;
use rayon::prelude::*;
use shroud_geometry::cloud::{fit_plane, NeighbourIndex};

/// Backward error above which a solution is rejected.
pub(super) const MAX_BACKWARD_ERROR: f64 = 1e-9;

impl Rbf {
    /// Interpolates `values` at `centres` exactly (up to rounding).
    ///
    /// Errors: fewer than 5 centres or centres/values of different lengths
    /// ([`BlendError::TooFewCentres`]), centres closer than 1e-9 of their extent,
    /// all-coplanar centres (the linear polynomial is then undetermined), or a
    /// numerically singular matrix ([`BlendError::SingularSystem`]).
    pub fn interpolate(centres: &[DVec3], values: &[f64]) -> Result<Self, BlendError> {
        let n = centres.len();
        if n < 5 || values.len() != n {
            return Err(BlendError::TooFewCentres {
                count: n.min(values.len()),
                min: 5,
            });
        }
        if centres.iter().any(|c| !c.is_finite()) || values.iter().any(|v| !v.is_finite()) {
            return Err(BlendError::SingularSystem { residual: f64::NAN });
        }
        let shift = centres.iter().copied().sum::<DVec3>() / n as f64;
        let scale = centres
            .iter()
            .map(|c| c.distance(shift))
            .fold(0.0, f64::max);
        if !(scale > 0.0) {
            return Err(BlendError::SingularSystem {
                residual: f64::INFINITY,
            });
        }
        // Unisolvency for the linear polynomial: the centres must not be coplanar.
        let spread = fit_plane(centres.iter().copied()).map_or([0.0; 3], |f| f.spread);
        if !(spread[0] > 1e-14 * spread[2]) {
            return Err(BlendError::SingularSystem {
                residual: f64::INFINITY,
            });
        }
        let local: Vec<DVec3> = centres.iter().map(|&c| (c - shift) / scale).collect();
        check_distinct(&local)?;
        let m = n + 4;
        let matrix = Mat::<f64>::from_fn(m, m, |i, j| entry(&local, i, j));
        let rhs = Mat::<f64>::from_fn(m, 1, |i, _| if i < n { values[i] } else { 0.0 });
        let from_solution = |solution: Mat<f64>| Rbf {
            shift,
            scale,
            xs: local.iter().map(|p| p.x).collect(),
            ys: local.iter().map(|p| p.y).collect(),
            zs: local.iter().map(|p| p.z).collect(),
            weights: (0..n).map(|i| solution[(i, 0)]).collect(),
            poly: std::array::from_fn(|k| solution[(n + k, 0)]),
        };
        let mut rbf = from_solution(matrix.lblt(Side::Lower).solve(&rhs));
        if !(backward_error(&rbf, values) <= MAX_BACKWARD_ERROR) {
            rbf = from_solution(matrix.partial_piv_lu().solve(&rhs));
        }
        let error = backward_error(&rbf, values);
        if !(error <= MAX_BACKWARD_ERROR) {
            return Err(BlendError::SingularSystem { residual: error });
        }
        Ok(rbf)
    }
}

/// Coincident centres make two equal rows: singular.
pub(super) fn check_distinct(local: &[DVec3]) -> Result<(), BlendError> {
    let index = NeighbourIndex::new(local.to_vec());
    if local
        .iter()
        .any(|&p| index.nearest(p, 2).get(1).is_some_and(|&(_, d)| d < 1e-9))
    {
        return Err(BlendError::SingularSystem {
            residual: f64::INFINITY,
        });
    }
    Ok(())
}

/// Entry `(i, j)` of the symmetric saddle-point matrix.
fn entry(local: &[DVec3], i: usize, j: usize) -> f64 {
    let n = local.len();
    match (i < n, j < n) {
        (true, true) => cube(local[i], local[j]),
        (true, false) => poly_term(local[i], j - n),
        (false, true) => poly_term(local[j], i - n),
        (false, false) => 0.0,
    }
}

fn poly_term(p: DVec3, k: usize) -> f64 {
    match k {
        0 => 1.0,
        1 => p.x,
        2 => p.y,
        _ => p.z,
    }
}

/// Normwise backward error `|K x - b| / (|K| |x| + |b|)` in the max norm of
/// `rbf` as a solution of Eq. 1's saddle-point system `K` at its own centres
/// with `values`, from the kernel sums (without forming `K`); NaN-safe
/// (non-finite solutions give infinity).
pub(super) fn backward_error(rbf: &Rbf, values: &[f64]) -> f64 {
    let n = rbf.centres();
    if values.len() != n {
        return f64::INFINITY;
    }
    // |A| row sums: the same kernel sums with unit weights and no polynomial.
    let ones = Rbf {
        weights: vec![1.0; n],
        poly: [0.0; 4],
        ..rbf.clone()
    };
    let local = rbf.local_centres();
    let rows: Vec<(f64, f64)> = local
        .par_iter()
        .with_min_len(32)
        .zip(values)
        .map(|(&q, &f)| {
            let p = rbf.shift + rbf.scale * q;
            let row = ones.value(p) + 1.0 + q.x.abs() + q.y.abs() + q.z.abs();
            (rbf.value(p) - f, row)
        })
        .collect();
    let mut residual: f64 = 0.0;
    let mut a_norm: f64 = 0.0;
    for &(r, row) in &rows {
        residual = residual.max(r.abs());
        a_norm = a_norm.max(row);
    }
    // The side condition's rows: P^T lambda = 0.
    for k in 0..4 {
        let term = |i: usize| [1.0, local[i].x, local[i].y, local[i].z][k];
        let r: f64 = (0..n).map(|i| rbf.weights[i] * term(i)).sum();
        residual = residual.max(r.abs());
        a_norm = a_norm.max((0..n).map(|i| term(i).abs()).sum());
    }
    let x_norm = rbf
        .weights
        .iter()
        .chain(&rbf.poly)
        .fold(0.0f64, |m, w| m.max(w.abs()));
    let b_norm = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(residual.is_finite() && x_norm.is_finite()) {
        return f64::INFINITY;
    }
    let denominator = a_norm * x_norm + b_norm;
    if denominator > 0.0 {
        residual / denominator
    } else {
        0.0
    }
}
