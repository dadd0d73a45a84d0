//! Bernstein polynomials for the ray query. Along a ray `s`, `t` and `w` are
//! linear (Section 1 of the paper), so on one cell `f(s(τ), t(τ)) - w(τ)` is a
//! polynomial of degree 6. Its Bernstein coefficients are built exactly from the
//! cell's bicubic Bézier patch by blossoming, and bound it by the convex hull
//! property, which is what makes "no hit" a proof rather than a sample.

use shroud_geometry::spline::BezierPatch;

/// Degree of a bicubic patch restricted to a line.
pub const DEGREE: usize = 6;

/// `C(3,a) C(3,b) / C(6,a+b)`: the weight of the restricted patch's control point
/// `(a, b)` in coefficient `a + b` of its diagonal (the product of two cubic
/// Bernstein bases). Each anti-diagonal sums to one, so coefficients are convex
/// combinations of the net.
const DIAGONAL_WEIGHTS: [[f64; 4]; 4] = [
    [1.0, 0.5, 0.2, 0.05],
    [0.5, 0.6, 0.45, 0.2],
    [0.2, 0.45, 0.6, 0.5],
    [0.05, 0.2, 0.5, 1.0],
];

/// A polynomial of degree 6 on `[0, 1]` in Bernstein form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bernstein6(pub [f64; DEGREE + 1]);

#[inline]
fn lerp(a: f64, b: f64, x: f64) -> f64 {
    a + (b - a) * x
}

/// The cubic `p` reparametrised from `[x0, x1]` onto `[0, 1]`: its blossom values
/// `p[x0,x0,x0], p[x0,x0,x1], p[x0,x1,x1], p[x1,x1,x1]`. Works for any `x0`, `x1`
/// (reversed or equal), unlike a split-based restriction.
#[inline]
pub fn cubic_on_interval(p: [f64; 4], x0: f64, x1: f64) -> [f64; 4] {
    let a = [
        lerp(p[0], p[1], x0),
        lerp(p[1], p[2], x0),
        lerp(p[2], p[3], x0),
    ];
    let aa = [lerp(a[0], a[1], x0), lerp(a[1], a[2], x0)];
    let ab = [lerp(a[0], a[1], x1), lerp(a[1], a[2], x1)];
    let b = [
        lerp(p[0], p[1], x1),
        lerp(p[1], p[2], x1),
        lerp(p[2], p[3], x1),
    ];
    let bb = [lerp(b[0], b[1], x1), lerp(b[1], b[2], x1)];
    [
        lerp(aa[0], aa[1], x0),
        lerp(aa[0], aa[1], x1),
        lerp(ab[0], ab[1], x1),
        lerp(bb[0], bb[1], x1),
    ]
}

/// The patch restricted to `[s0, s1] x [t0, t1]` (any order) by blossoming.
#[inline]
pub fn patch_on_rect(patch: &BezierPatch, s: [f64; 2], t: [f64; 2]) -> [[f64; 4]; 4] {
    let rows = patch.0.map(|row| cubic_on_interval(row, s[0], s[1]));
    let mut out = [[0.0; 4]; 4];
    for q in 0..4 {
        let col = cubic_on_interval([rows[0][q], rows[1][q], rows[2][q], rows[3][q]], t[0], t[1]);
        for (r, value) in col.into_iter().enumerate() {
            out[r][q] = value;
        }
    }
    out
}

impl Bernstein6 {
    /// `τ -> patch(s0 + τ (s1 - s0), t0 + τ (t1 - t0))` for local cell coordinates:
    /// restrict the patch to the segment's bounding rectangle (corner to corner),
    /// then take the diagonal of the tensor product.
    pub fn along_segment(patch: &BezierPatch, s: [f64; 2], t: [f64; 2]) -> Self {
        let net = patch_on_rect(patch, s, t);
        let mut c = [0.0; DEGREE + 1];
        for (b, row) in net.iter().enumerate() {
            for (a, value) in row.iter().enumerate() {
                c[a + b] += DIAGONAL_WEIGHTS[a][b] * value;
            }
        }
        Self(c)
    }

    /// Subtracts the linear function from `w0` at 0 to `w1` at 1 (degree-elevated:
    /// its coefficients are `w0 + (w1 - w0) k / 6`).
    #[inline]
    pub fn minus_linear(mut self, w0: f64, w1: f64) -> Self {
        for (k, c) in self.0.iter_mut().enumerate() {
            *c -= lerp(w0, w1, k as f64 / DEGREE as f64);
        }
        self
    }

    /// Value at `x` by de Casteljau.
    pub fn eval(&self, x: f64) -> f64 {
        let mut c = self.0;
        for level in 1..=DEGREE {
            for i in 0..=DEGREE - level {
                c[i] = lerp(c[i], c[i + 1], x);
            }
        }
        c[0]
    }

    /// The two halves over `[0, 1/2]` and `[1/2, 1]`, each reparametrised onto `[0, 1]`.
    #[inline]
    pub fn split_half(&self) -> (Self, Self) {
        let mut left = [0.0; DEGREE + 1];
        let mut right = [0.0; DEGREE + 1];
        let mut c = self.0;
        for level in 0..=DEGREE {
            left[level] = c[0];
            right[DEGREE - level] = c[DEGREE - level];
            for i in 0..DEGREE - level {
                c[i] = 0.5 * (c[i] + c[i + 1]);
            }
        }
        (Self(left), Self(right))
    }

    /// Smallest and largest coefficient: bounds of the polynomial on `[0, 1]`.
    #[inline]
    pub fn hull(&self) -> (f64, f64) {
        self.0
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &c| {
                (lo.min(c), hi.max(c))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_geometry::spline::{bezier_patch, UniformCubicSurface};

    fn patch() -> BezierPatch {
        let b: Vec<f64> = (0..25).map(|i| ((i * 13) % 7) as f64 * 0.4 - 1.1).collect();
        bezier_patch(&UniformCubicSurface::new(5, 5, b).unwrap(), 1, 2)
    }

    #[test]
    fn diagonal_weights_are_convex_per_degree() {
        for k in 0..=DEGREE {
            let sum: f64 = (0..4)
                .filter(|a| k >= *a && k - a < 4)
                .map(|a| DIAGONAL_WEIGHTS[a][k - a])
                .sum();
            assert!((sum - 1.0).abs() < 1e-15, "k = {k}");
        }
    }

    #[test]
    fn interval_restriction_handles_any_order() {
        let p = [0.3, -1.0, 2.0, 0.5];
        let cubic = |x: f64| shroud_geometry::spline::BezierPatch([p; 4]).eval(x, 0.0);
        for (x0, x1) in [(0.2, 0.7), (0.9, 0.1), (0.4, 0.4), (-0.1, 1.2)] {
            let q = cubic_on_interval(p, x0, x1);
            for i in 0..=10 {
                let tau = i as f64 / 10.0;
                let direct = cubic(x0 + tau * (x1 - x0));
                let restricted = shroud_geometry::spline::BezierPatch([q; 4]).eval(tau, 0.0);
                assert!((direct - restricted).abs() < 1e-13, "[{x0}, {x1}] at {tau}");
            }
        }
    }

    #[test]
    fn segment_polynomial_equals_the_patch_on_the_segment() {
        let p = patch();
        let segments = [
            ([0.1, 0.9], [0.2, 0.6]),
            ([1.0, 0.0], [0.3, 0.3]),
            ([0.5, 0.5], [0.9, 0.1]),
            ([0.4, 0.4], [0.7, 0.7]),
        ];
        for (s, t) in segments {
            let poly = Bernstein6::along_segment(&p, s, t).minus_linear(0.25, -0.75);
            for i in 0..=20 {
                let tau = i as f64 / 20.0;
                let direct =
                    p.eval(s[0] + tau * (s[1] - s[0]), t[0] + tau * (t[1] - t[0])) - (0.25 - tau);
                assert!(
                    (poly.eval(tau) - direct).abs() < 1e-13,
                    "{s:?} {t:?} at {tau}"
                );
            }
            let (lo, hi) = poly.hull();
            assert!(lo <= poly.eval(0.37) && poly.eval(0.37) <= hi);
        }
    }

    #[test]
    fn halves_reproduce_the_polynomial() {
        let poly = Bernstein6::along_segment(&patch(), [0.1, 0.8], [0.9, 0.2]);
        let (left, right) = poly.split_half();
        for i in 0..=10 {
            let x = i as f64 / 10.0;
            assert!((left.eval(x) - poly.eval(0.5 * x)).abs() < 1e-13);
            assert!((right.eval(x) - poly.eval(0.5 + 0.5 * x)).abs() < 1e-13);
        }
    }
}
