//! The greedy fit's system (Eq. 1) solved through a Cholesky factor of the
//! projected matrix `Q^T A Q` (see [`super::projection`]) that grows with the
//! centres: adding `k` centres to `n` borders the factor,
//! `L21 = B21 L11^-T` and `L22 L22^T = B22 - L21 L21^T`, so the whole greedy fit
//! costs about one factorisation of the final size instead of one per round.
//! The caller checks every solution's backward error, as for the dense solve.

use super::eval::Rbf;
use super::projection::{pick_base, Projected, Projection};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Accum, Mat, Par, Side};
use glam::DVec3;

/// The factor could not be extended: the bordered block is not numerically
/// positive definite (near-coincident centres, or rounding).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Breakdown;

/// A growing fit in a fixed frame (the RBF's scaled coordinates).
pub(super) struct GrowingFit {
    shift: DVec3,
    scale: f64,
    projection: Projection,
    base_values: [f64; 4],
    /// The non-base centres, in factor order, and their values.
    centres: Vec<Projected>,
    values: Vec<f64>,
    /// `Q^T f`, one entry per non-base centre.
    rhs: Vec<f64>,
    /// Lower Cholesky factor of `Q^T A Q` over `centres`.
    factor: Mat<f64>,
}

fn parallelism(work: usize) -> Par {
    // Below a few hundred rows threads cost more than they save.
    if work >= 256 {
        Par::rayon(0)
    } else {
        Par::Seq
    }
}

impl GrowingFit {
    /// Starts a fit in the frame `(shift, scale)` with four base centres
    /// chosen among `points` (which are not otherwise added); `None` when
    /// `points` has no four centres in general position.
    pub(super) fn new(
        shift: DVec3,
        scale: f64,
        points: &[DVec3],
        values: &[f64],
    ) -> Option<(Self, [usize; 4])> {
        let local: Vec<DVec3> = points.iter().map(|&p| (p - shift) / scale).collect();
        let picked = pick_base(&local)?;
        let projection = Projection::new(picked.map(|i| local[i]))?;
        let fit = Self {
            shift,
            scale,
            projection,
            base_values: picked.map(|i| values[i]),
            centres: Vec::new(),
            values: Vec::new(),
            rhs: Vec::new(),
            factor: Mat::zeros(0, 0),
        };
        Some((fit, picked))
    }

    /// Adds centres at `points` (world) with `values`; on failure the fit is
    /// left unusable.
    pub(super) fn extend(&mut self, points: &[DVec3], values: &[f64]) -> Result<(), Breakdown> {
        let n = self.centres.len();
        let fresh: Vec<Projected> = points
            .iter()
            .map(|&p| self.projection.project((p - self.shift) / self.scale))
            .collect();
        let k = fresh.len();
        let par = parallelism(n + k);
        // L21^T = L11^-1 B12.
        let mut border = Mat::from_fn(n, k, |i, j| Projection::entry(&self.centres[i], &fresh[j]));
        solve_lower_triangular_in_place(self.factor.as_ref(), border.as_mut(), par);
        let mut corner = Mat::from_fn(k, k, |i, j| Projection::entry(&fresh[i], &fresh[j]));
        matmul(
            corner.as_mut(),
            Accum::Add,
            border.transpose(),
            border.as_ref(),
            -1.0,
            par,
        );
        let corner = corner.llt(Side::Lower).map_err(|_| Breakdown)?;
        self.factor.resize_with(n + k, n + k, |_, _| 0.0);
        self.factor
            .as_mut()
            .submatrix_mut(n, 0, k, n)
            .copy_from(border.transpose());
        self.factor
            .as_mut()
            .submatrix_mut(n, n, k, k)
            .copy_from(corner.L());
        for (c, &v) in fresh.iter().zip(values) {
            self.rhs.push(self.projection.rhs(c, v, &self.base_values));
        }
        self.centres.extend(fresh);
        self.values.extend_from_slice(values);
        Ok(())
    }

    /// The RBF of the current centres: `mu = (L L^T)^-1 Q^T f`, `lambda = Q mu`,
    /// and the polynomial from the base centres' rows of Eq. 1.
    pub(super) fn rbf(&self) -> Rbf {
        let n = self.centres.len();
        let par = parallelism(n);
        let mut mu = Mat::from_fn(n, 1, |i, _| self.rhs[i]);
        solve_lower_triangular_in_place(self.factor.as_ref(), mu.as_mut(), par);
        solve_upper_triangular_in_place(self.factor.transpose(), mu.as_mut(), par);
        let mu: Vec<f64> = (0..n).map(|i| mu[(i, 0)]).collect();
        let mut base_weights = [0.0; 4];
        // (A lambda) at the base centres, from the non-base centres first.
        let mut at_base = [0.0; 4];
        for (c, &m) in self.centres.iter().zip(&mu) {
            for k in 0..4 {
                base_weights[k] -= c.lagrange[k] * m;
                at_base[k] += c.to_base[k] * m;
            }
        }
        for k in 0..4 {
            at_base[k] += (0..4)
                .map(|l| self.projection.base_kernel[k][l] * base_weights[l])
                .sum::<f64>();
        }
        let rest = std::array::from_fn(|k| self.base_values[k] - at_base[k]);
        let points: Vec<DVec3> = self
            .projection
            .base
            .iter()
            .copied()
            .chain(self.centres.iter().map(|c| c.point))
            .collect();
        Rbf {
            shift: self.shift,
            scale: self.scale,
            xs: points.iter().map(|p| p.x).collect(),
            ys: points.iter().map(|p| p.y).collect(),
            zs: points.iter().map(|p| p.z).collect(),
            weights: base_weights.iter().copied().chain(mu).collect(),
            poly: self.projection.polynomial(rest),
        }
    }

    /// The values in the RBF's centre order (base first).
    pub(super) fn values(&self) -> Vec<f64> {
        self.base_values
            .iter()
            .chain(&self.values)
            .copied()
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A jittered 5 x 5 x 3 grid (so no two centres come closer than 0.2 of
    /// a step, and the system stays well conditioned) with arbitrary values.
    fn data(jitter: &[(f64, f64, f64)], values: &[f64]) -> (Vec<DVec3>, Vec<f64>) {
        let points = (0..75)
            .map(|i| {
                let (x, y, z) = jitter[i];
                let cell = DVec3::new((i % 5) as f64, ((i / 5) % 5) as f64, (i / 25) as f64);
                (cell + 0.4 * DVec3::new(x, y, z)) * 0.4 - DVec3::new(0.8, 0.8, 0.4)
            })
            .collect();
        (points, values.to_vec())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]

        /// The grown factor, fed in three blocks, gives the interpolant of the
        /// dense LBL^T solve. Both solutions have a backward error below 1e-9;
        /// the interpolant is unique, so they differ by rounding amplified by
        /// the system's condition (about 1e6 here): 1e-7 of the data's scale
        /// leaves margin, while any wrong entry of `Q^T A Q` or of the
        /// polynomial's recovery gives errors of the data's order.
        #[test]
        fn grown_factor_matches_the_dense_solve(
            jitter in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), 75),
            values in prop::collection::vec(-1.0..1.0f64, 75),
            first in 6usize..30,
            second in 30usize..60,
        ) {
            let (points, values) = data(&jitter, &values);
            let (mut fit, base) = GrowingFit::new(DVec3::ZERO, 1.0, &points[..first], &values[..first])
                .expect("a grid spans space");
            let rest: Vec<usize> = (0..first).filter(|i| !base.contains(i)).collect();
            let pick = |ids: &[usize]| -> (Vec<DVec3>, Vec<f64>) {
                ids.iter().map(|&i| (points[i], values[i])).unzip()
            };
            for block in [rest, (first..second).collect(), (second..75).collect()] {
                let (p, v) = pick(&block);
                fit.extend(&p, &v).expect("positive definite");
            }
            let grown = fit.rbf();
            let dense = Rbf::interpolate(&points, &values).expect("regular");
            for (i, &p) in points.iter().enumerate() {
                let probe = p + DVec3::new(0.05, -0.07, 0.03) * (i % 3) as f64;
                let (a, b) = (grown.value(probe), dense.value(probe));
                prop_assert!((a - b).abs() < 1e-7, "at {probe}: grown {a}, dense {b}");
            }
        }
    }
}
