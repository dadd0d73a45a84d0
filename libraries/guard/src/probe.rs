//! The core of a shape as seen by the clearance search: a point (sphere centre)
//! or a segment (capsule axis) in frame coordinates, and its exact Euclidean
//! distance to an axis-aligned box (boxes may be unbounded in height).

/// A point or segment in frame coordinates `(u, v, h)`.
pub(crate) trait Probe {
    /// `([u_min, u_max], [v_min, v_max])` of the core.
    fn uv_bounds(&self) -> ([f64; 2], [f64; 2]);
    /// Squared distance from the core to the box `lo..=hi` (0 when they meet).
    fn dist2_to_box(&self, lo: &[f64; 3], hi: &[f64; 3]) -> f64;
    /// Whether [`Self::dist2_to_box`] is certainly at least `limit` squared
    /// for every box inside `outer`, as computed: a whole row of cells is
    /// skipped on it. `false` when that is not known.
    fn beyond(&self, outer: &CellBox, limit: f64) -> bool;
}

use super::envelope::CellBox;

/// A sphere's centre.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PointProbe(pub [f64; 3]);

/// A capsule's axis `a + x (b - a)`, `x in [0, 1]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SegmentProbe {
    pub a: [f64; 3],
    pub b: [f64; 3],
}

/// Distance from `x` to the interval `lo..=hi` (either end may be infinite).
#[inline(always)]
fn gap(x: f64, lo: f64, hi: f64) -> f64 {
    (lo - x).max(x - hi).max(0.0)
}

#[inline(always)]
pub(crate) fn point_box_dist2(p: &[f64; 3], lo: &[f64; 3], hi: &[f64; 3]) -> f64 {
    let (a, b, c) = (
        gap(p[0], lo[0], hi[0]),
        gap(p[1], lo[1], hi[1]),
        gap(p[2], lo[2], hi[2]),
    );
    a * a + b * b + c * c
}

impl Probe for PointProbe {
    #[inline]
    fn uv_bounds(&self) -> ([f64; 2], [f64; 2]) {
        ([self.0[0]; 2], [self.0[1]; 2])
    }

    #[inline]
    fn dist2_to_box(&self, lo: &[f64; 3], hi: &[f64; 3]) -> f64 {
        point_box_dist2(&self.0, lo, hi)
    }

    /// Each gap to a box inside `outer` is at least the gap to `outer`, and
    /// rounding keeps that order (every operation is monotone), so the
    /// squared distances compare the same way bit for bit.
    #[inline]
    fn beyond(&self, outer: &CellBox, limit: f64) -> bool {
        point_box_dist2(&self.0, &outer.lo, &outer.hi) >= limit * limit
    }
}

impl Probe for SegmentProbe {
    fn uv_bounds(&self) -> ([f64; 2], [f64; 2]) {
        let range = |k: usize| [self.a[k].min(self.b[k]), self.a[k].max(self.b[k])];
        (range(0), range(1))
    }

    /// The squared distance along the segment is convex and piecewise quadratic,
    /// with breaks where a coordinate crosses a face plane of the box (at most
    /// six). On each piece the set of violated faces is fixed, so its minimiser
    /// is the clamped vertex of one quadratic; the distance is then evaluated
    /// directly at that parameter. The smallest over the pieces is the minimum.
    fn dist2_to_box(&self, lo: &[f64; 3], hi: &[f64; 3]) -> f64 {
        let (a, b) = (&self.a, &self.b);
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let mut breaks = [0.0f64; 8];
        let mut n = 1;
        for k in 0..3 {
            if d[k] == 0.0 {
                continue;
            }
            for bound in [lo[k], hi[k]] {
                let x = (bound - a[k]) / d[k];
                if x > 0.0 && x < 1.0 {
                    breaks[n] = x;
                    n += 1;
                }
            }
        }
        breaks[n] = 1.0;
        n += 1;
        breaks[..n].sort_unstable_by(f64::total_cmp);
        let at = |x: f64| [a[0] + d[0] * x, a[1] + d[1] * x, a[2] + d[2] * x];
        let mut best = f64::INFINITY;
        for w in breaks[..n].windows(2) {
            let (x0, x1) = (w[0], w[1]);
            let mid = at(0.5 * (x0 + x1));
            // (a_k - bound + d_k x)^2 summed over the violated faces: A x^2 + B x + C.
            let (mut qa, mut qb) = (0.0, 0.0);
            for k in 0..3 {
                let bound = if mid[k] < lo[k] {
                    lo[k]
                } else if mid[k] > hi[k] {
                    hi[k]
                } else {
                    continue;
                };
                qa += d[k] * d[k];
                qb += 2.0 * d[k] * (a[k] - bound);
            }
            let x = if qa > 0.0 {
                (-qb / (2.0 * qa)).clamp(x0, x1)
            } else {
                x0
            };
            best = best.min(point_box_dist2(&at(x), lo, hi));
        }
        best
    }

    /// Not known without a rounding analysis of the piecewise search:
    /// nothing is skipped.
    fn beyond(&self, _outer: &CellBox, _limit: f64) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn sampled(seg: &SegmentProbe, lo: &[f64; 3], hi: &[f64; 3]) -> f64 {
        (0..=20_000)
            .map(|i| {
                let x = i as f64 / 20_000.0;
                let p = [0, 1, 2].map(|k| seg.a[k] + (seg.b[k] - seg.a[k]) * x);
                point_box_dist2(&p, lo, hi)
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn point_distance_with_unbounded_heights() {
        let lo = [0.0, 0.0, f64::NEG_INFINITY];
        let hi = [1.0, 1.0, 2.0];
        assert_eq!(point_box_dist2(&[0.5, 0.5, -1e300], &lo, &hi), 0.0);
        assert_eq!(point_box_dist2(&[0.5, 0.5, 5.0], &lo, &hi), 9.0);
        assert_eq!(point_box_dist2(&[2.0, -1.0, 3.0], &lo, &hi), 3.0);
    }

    #[test]
    fn segment_distance_matches_dense_sampling() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        for i in 0..300 {
            let lo = [0; 3].map(|_| rng.random_range(-1.0..0.0));
            let mut hi = lo.map(|l| l + rng.random_range(0.0..1.0));
            if i % 5 == 0 {
                hi[2] = f64::INFINITY;
            }
            let seg = SegmentProbe {
                a: [0; 3].map(|_| rng.random_range(-3.0..3.0)),
                b: [0; 3].map(|_| rng.random_range(-3.0..3.0)),
            };
            let exact = seg.dist2_to_box(&lo, &hi);
            let dense = sampled(&seg, &lo, &hi);
            // Exact is the minimum: never above a sample, and close to the best one.
            assert!(exact <= dense + 1e-12, "{exact} > {dense}");
            assert!(dense.sqrt() - exact.sqrt() < 1e-3, "{exact} vs {dense}");
        }
    }

    #[test]
    fn degenerate_segment_is_a_point() {
        let seg = SegmentProbe {
            a: [2.0, 0.5, 0.5],
            b: [2.0, 0.5, 0.5],
        };
        assert_eq!(seg.dist2_to_box(&[0.0; 3], &[1.0; 3]), 1.0);
        assert_eq!(seg.uv_bounds(), ([2.0, 2.0], [0.5, 0.5]));
    }
}
