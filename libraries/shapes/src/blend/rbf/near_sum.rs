//! The near part of the split evaluation (see [`super::split_kernel`]): the
//! centres within the split radius of one lattice cell, copied out as padded
//! structure of arrays so that the sum over them vectorises (the near sums are
//! most of a sampling's arithmetic: every point meets a few hundred centres).

use super::eval::Rbf;
use super::split_kernel::SplitKernel;
use glam::DVec3;

const LANES: usize = 4;

/// Centres (scaled coordinates) and weights, padded to whole lanes with
/// zero-weight entries.
pub(super) struct NearCentres {
    xs: Vec<f64>,
    ys: Vec<f64>,
    zs: Vec<f64>,
    weights: Vec<f64>,
}

impl NearCentres {
    /// The centres `indices` of `rbf`.
    pub(super) fn new(rbf: &Rbf, indices: &[u32]) -> Self {
        let padded = indices.len().div_ceil(LANES) * LANES;
        let column = |source: &[f64], pad: f64| -> Vec<f64> {
            let mut out: Vec<f64> = indices.iter().map(|&i| source[i as usize]).collect();
            out.resize(padded, pad);
            out
        };
        Self {
            xs: column(&rbf.xs, 0.0),
            ys: column(&rbf.ys, 0.0),
            zs: column(&rbf.zs, 0.0),
            // A zero weight makes a padding entry's term vanish wherever it is.
            weights: column(&rbf.weights, 0.0),
        }
    }

    /// Entries held, padding included (for the cache's memory bound).
    pub(super) fn len(&self) -> usize {
        self.weights.len()
    }

    /// `sum_i w_i near(|q - y_i|)` at the scaled point `q` and, with
    /// `GRADIENT`, its gradient `sum_i w_i f_i (q - y_i)`.
    #[inline]
    pub(super) fn sum<const GRADIENT: bool>(&self, kernel: &SplitKernel, q: DVec3) -> (f64, DVec3) {
        let mut acc = [[0.0f64; LANES]; 4];
        let lanes = self
            .xs
            .chunks_exact(LANES)
            .zip(self.ys.chunks_exact(LANES))
            .zip(self.zs.chunks_exact(LANES))
            .zip(self.weights.chunks_exact(LANES));
        for (((x, y), z), w) in lanes {
            // Lane-wise array steps (rather than one lane at a time): the
            // gradient's four sums then vectorise too.
            let (mut dx, mut dy, mut dz, mut s) =
                ([0.0; LANES], [0.0; LANES], [0.0; LANES], [0.0; LANES]);
            for l in 0..LANES {
                dx[l] = q.x - x[l];
                dy[l] = q.y - y[l];
                dz[l] = q.z - z[l];
                s[l] = dx[l] * dx[l] + dy[l] * dy[l] + dz[l] * dz[l];
            }
            let (k, f) = kernel.near_lanes(s);
            for l in 0..LANES {
                acc[0][l] += w[l] * k[l];
            }
            if GRADIENT {
                for l in 0..LANES {
                    let g = w[l] * f[l];
                    acc[1][l] += g * dx[l];
                    acc[2][l] += g * dy[l];
                    acc[3][l] += g * dz[l];
                }
            }
        }
        let [value, gx, gy, gz] = acc.map(|a| a.iter().sum::<f64>());
        (value, DVec3::new(gx, gy, gz))
    }
}
