//! The dense interpolation system of Eq. 1: `[A P; P^T 0] [lambda; c] = [f; 0]` with
//! `A_ij = |x_i - x_j|^3` and `P_i = [1, x_i]`, solved with faer's Bunch-Kaufman
//! LBL^T (symmetric indefinite), falling back to LU with partial pivoting, and
//! checked by its residual: a singular system is an error, never garbage.

use super::eval::Rbf;
use crate::blend::error::BlendError;
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use glam::DVec3;
use shroud_geometry::cloud::{fit_plane, NeighbourIndex};

/// Backward error above which a solution is rejected.
const MAX_BACKWARD_ERROR: f64 = 1e-9;

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
        // Coincident centres make two equal rows: singular.
        let index = NeighbourIndex::new(local.clone());
        if local
            .iter()
            .any(|&p| index.nearest(p, 2).get(1).is_some_and(|&(_, d)| d < 1e-9))
        {
            return Err(BlendError::SingularSystem {
                residual: f64::INFINITY,
            });
        }
        let m = n + 4;
        let matrix = Mat::<f64>::from_fn(m, m, |i, j| entry(&local, i, j));
        let rhs = Mat::<f64>::from_fn(m, 1, |i, _| if i < n { values[i] } else { 0.0 });
        let mut solution = matrix.lblt(Side::Lower).solve(&rhs);
        let mut error = backward_error(&matrix, &solution, &rhs);
        if !(error <= MAX_BACKWARD_ERROR) {
            solution = matrix.partial_piv_lu().solve(&rhs);
            error = backward_error(&matrix, &solution, &rhs);
        }
        if !(error <= MAX_BACKWARD_ERROR) {
            return Err(BlendError::SingularSystem { residual: error });
        }
        let weights: Vec<f64> = (0..n).map(|i| solution[(i, 0)]).collect();
        Ok(Rbf {
            shift,
            scale,
            xs: local.iter().map(|p| p.x).collect(),
            ys: local.iter().map(|p| p.y).collect(),
            zs: local.iter().map(|p| p.z).collect(),
            weights,
            poly: [
                solution[(n, 0)],
                solution[(n + 1, 0)],
                solution[(n + 2, 0)],
                solution[(n + 3, 0)],
            ],
        })
    }
}

/// Entry `(i, j)` of the symmetric saddle-point matrix.
fn entry(local: &[DVec3], i: usize, j: usize) -> f64 {
    let n = local.len();
    match (i < n, j < n) {
        (true, true) => local[i].distance(local[j]).powi(3),
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

/// Normwise backward error `|Ax - b| / (|A| |x| + |b|)` in the max norm; NaN-safe
/// (non-finite solutions give infinity).
fn backward_error(a: &Mat<f64>, x: &Mat<f64>, b: &Mat<f64>) -> f64 {
    let ax = a * x;
    let m = a.nrows();
    let mut residual: f64 = 0.0;
    let (mut x_norm, mut b_norm, mut a_norm): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for i in 0..m {
        let r = ax[(i, 0)] - b[(i, 0)];
        if !r.is_finite() || !x[(i, 0)].is_finite() {
            return f64::INFINITY;
        }
        residual = residual.max(r.abs());
        x_norm = x_norm.max(x[(i, 0)].abs());
        b_norm = b_norm.max(b[(i, 0)].abs());
        let row: f64 = (0..m).map(|j| a[(i, j)].abs()).sum();
        a_norm = a_norm.max(row);
    }
    let denominator = a_norm * x_norm + b_norm;
    if denominator > 0.0 {
        residual / denominator
    } else {
        0.0
    }
}
