//! Evaluating the RBF of Eq. 1 and its gradient. Centres are stored shifted and
//! scaled to the unit ball (for the conditioning of the solve), as structure of
//! arrays so the kernel sum vectorises.

use glam::DVec3;
use rayon::prelude::*;

/// `s(x) = c0 + c . y + sum_i w_i |y - y_i|^3` with `y = (x - shift) / scale`.
#[derive(Debug, Clone, PartialEq)]
pub struct Rbf {
    pub(super) shift: DVec3,
    pub(super) scale: f64,
    pub(super) xs: Vec<f64>,
    pub(super) ys: Vec<f64>,
    pub(super) zs: Vec<f64>,
    pub(super) weights: Vec<f64>,
    /// `[c0, cx, cy, cz]` of the linear polynomial, in scaled coordinates.
    pub(super) poly: [f64; 4],
}

const LANES: usize = 4;

impl Rbf {
    /// Number of centres.
    pub fn centres(&self) -> usize {
        self.weights.len()
    }

    /// The centres in world coordinates.
    pub fn centre_points(&self) -> Vec<DVec3> {
        (0..self.centres())
            .map(|i| self.shift + self.scale * DVec3::new(self.xs[i], self.ys[i], self.zs[i]))
            .collect()
    }

    /// The centres in the scaled coordinates.
    pub(super) fn local_centres(&self) -> Vec<DVec3> {
        (0..self.centres())
            .map(|i| DVec3::new(self.xs[i], self.ys[i], self.zs[i]))
            .collect()
    }

    pub(super) fn local(&self, p: DVec3) -> DVec3 {
        (p - self.shift) / self.scale
    }

    /// `s(p)`.
    pub fn value(&self, p: DVec3) -> f64 {
        let q = self.local(p);
        let [sum, ..] = self.kernel_sums::<false>(q);
        sum + self.poly[0] + self.poly[1] * q.x + self.poly[2] * q.y + self.poly[3] * q.z
    }

    /// `s(p)` and its gradient (world units) at `p`:
    /// `grad |y - y_i|^3 = 3 |y - y_i| (y - y_i)`.
    pub fn value_gradient(&self, p: DVec3) -> (f64, DVec3) {
        let q = self.local(p);
        let [sum, gx, gy, gz] = self.kernel_sums::<true>(q);
        let value =
            sum + self.poly[0] + self.poly[1] * q.x + self.poly[2] * q.y + self.poly[3] * q.z;
        let gradient =
            DVec3::new(gx + self.poly[1], gy + self.poly[2], gz + self.poly[3]) / self.scale;
        (value, gradient)
    }

    /// `sum_i w_i |q - y_i|^3` and, with `GRADIENT`, `sum_i 3 w_i |d| d` at the
    /// scaled point `q`. LANES independent accumulators over exact chunks (no
    /// bounds checks), so that the sum vectorises; one accumulator would
    /// serialise on the adds.
    #[inline(always)]
    fn kernel_sums<const GRADIENT: bool>(&self, q: DVec3) -> [f64; 4] {
        let n = self.weights.len();
        let whole = n - n % LANES;
        let mut acc = [[0.0f64; LANES]; 4];
        let lanes = self.xs[..whole]
            .chunks_exact(LANES)
            .zip(self.ys[..whole].chunks_exact(LANES))
            .zip(self.zs[..whole].chunks_exact(LANES))
            .zip(self.weights[..whole].chunks_exact(LANES));
        for (((x, y), z), w) in lanes {
            for l in 0..LANES {
                let terms = kernel_terms::<GRADIENT>(q - DVec3::new(x[l], y[l], z[l]), w[l]);
                let used = if GRADIENT { 4 } else { 1 };
                for (a, t) in acc.iter_mut().zip(terms).take(used) {
                    a[l] += t;
                }
            }
        }
        let mut total = acc.map(|a| a.iter().sum::<f64>());
        for i in whole..n {
            let d = q - DVec3::new(self.xs[i], self.ys[i], self.zs[i]);
            for (t, x) in total
                .iter_mut()
                .zip(kernel_terms::<GRADIENT>(d, self.weights[i]))
            {
                *t += x;
            }
        }
        total
    }

    /// `s` at many points, in parallel.
    pub fn values(&self, points: &[DVec3]) -> Vec<f64> {
        points
            .par_iter()
            .with_min_len(64)
            .map(|&p| self.value(p))
            .collect()
    }

    /// Distance estimate `|s| / |grad s|` from `p` to the zero set (first order).
    pub fn distance_estimate(&self, p: DVec3) -> f64 {
        let (v, g) = self.value_gradient(p);
        let len = g.length();
        if len > 0.0 {
            v.abs() / len
        } else {
            f64::INFINITY
        }
    }
}

/// One centre's term of `s` and (with `GRADIENT`) of its gradient, at offset
/// `d = q - y_i` with weight `w`: `w |d|^3` and `3 w |d| d`.
#[inline(always)]
fn kernel_terms<const GRADIENT: bool>(d: DVec3, w: f64) -> [f64; 4] {
    let r2 = d.length_squared();
    let r = r2.sqrt();
    if !GRADIENT {
        return [w * r2 * r, 0.0, 0.0, 0.0];
    }
    let g = 3.0 * w * r;
    [w * r2 * r, g * d.x, g * d.y, g * d.z]
}
