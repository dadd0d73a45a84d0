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

    pub(super) fn local(&self, p: DVec3) -> DVec3 {
        (p - self.shift) / self.scale
    }

    /// `s(p)`.
    pub fn value(&self, p: DVec3) -> f64 {
        let q = self.local(p);
        let n = self.weights.len();
        let split = n - n % LANES;
        let mut acc = [0.0f64; LANES];
        for base in (0..split).step_by(LANES) {
            for l in 0..LANES {
                let i = base + l;
                let (dx, dy, dz) = (q.x - self.xs[i], q.y - self.ys[i], q.z - self.zs[i]);
                let r2 = dx * dx + dy * dy + dz * dz;
                acc[l] += self.weights[i] * r2 * r2.sqrt();
            }
        }
        let mut sum = acc.iter().sum::<f64>();
        for i in split..n {
            let (dx, dy, dz) = (q.x - self.xs[i], q.y - self.ys[i], q.z - self.zs[i]);
            let r2 = dx * dx + dy * dy + dz * dz;
            sum += self.weights[i] * r2 * r2.sqrt();
        }
        sum + self.poly[0] + self.poly[1] * q.x + self.poly[2] * q.y + self.poly[3] * q.z
    }

    /// `s(p)` and its gradient (world units) at `p`:
    /// `grad |y - y_i|^3 = 3 |y - y_i| (y - y_i)`.
    pub fn value_gradient(&self, p: DVec3) -> (f64, DVec3) {
        let q = self.local(p);
        let n = self.weights.len();
        let split = n - n % LANES;
        // LANES independent accumulators, as in `value`, so that the sum
        // vectorises (one accumulator would serialise on the adds).
        let mut acc = [[0.0f64; LANES]; 4];
        for base in (0..split).step_by(LANES) {
            for l in 0..LANES {
                let [s, gx, gy, gz] = self.kernel_terms(q, base + l);
                acc[0][l] += s;
                acc[1][l] += gx;
                acc[2][l] += gy;
                acc[3][l] += gz;
            }
        }
        let mut total = acc.map(|a| a.iter().sum::<f64>());
        for i in split..n {
            let terms = self.kernel_terms(q, i);
            for (t, x) in total.iter_mut().zip(terms) {
                *t += x;
            }
        }
        let [sum, gx, gy, gz] = total;
        let value =
            sum + self.poly[0] + self.poly[1] * q.x + self.poly[2] * q.y + self.poly[3] * q.z;
        let gradient =
            DVec3::new(gx + self.poly[1], gy + self.poly[2], gz + self.poly[3]) / self.scale;
        (value, gradient)
    }

    /// Centre `i`'s term of `s` and of its gradient at the scaled point `q`:
    /// `w |d|^3` and `3 w |d| d` with `d = q - y_i`.
    #[inline(always)]
    fn kernel_terms(&self, q: DVec3, i: usize) -> [f64; 4] {
        let (dx, dy, dz) = (q.x - self.xs[i], q.y - self.ys[i], q.z - self.zs[i]);
        let r2 = dx * dx + dy * dy + dz * dz;
        let r = r2.sqrt();
        let w = self.weights[i];
        let g = 3.0 * w * r;
        [w * r2 * r, g * dx, g * dy, g * dz]
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
