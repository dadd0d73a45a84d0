//! Bézier form of uniform cubic B-spline pieces: the control nets whose convex
//! hulls bound the surface, used by every conservative query.

use super::surface::UniformCubicSurface;

/// Bernstein coefficients of one cubic piece from its four B-spline coefficients
/// `b_{h-1}, b_h, b_{h+1}, b_{h+2}` (the classical B-spline to Bézier conversion).
#[inline]
pub fn cubic_bezier_of_interval(p: [f64; 4]) -> [f64; 4] {
    [
        (p[0] + 4.0 * p[1] + p[2]) / 6.0,
        (2.0 * p[1] + p[2]) / 3.0,
        (p[1] + 2.0 * p[2]) / 3.0,
        (p[1] + 4.0 * p[2] + p[3]) / 6.0,
    ]
}

/// A bicubic Bézier patch over the unit square, `[row (t)][col (s)]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BezierPatch(pub [[f64; 4]; 4]);

/// The Bézier patch of cell `(h, g)` of a surface.
pub fn bezier_patch(surface: &UniformCubicSurface, h: usize, g: usize) -> BezierPatch {
    let c = surface.cell_coefficients(h, g);
    // Convert along s within each row, then along t within each column.
    let rows: [[f64; 4]; 4] = c.map(cubic_bezier_of_interval);
    let mut out = [[0.0; 4]; 4];
    for q in 0..4 {
        let col = cubic_bezier_of_interval([rows[0][q], rows[1][q], rows[2][q], rows[3][q]]);
        for r in 0..4 {
            out[r][q] = col[r];
        }
    }
    BezierPatch(out)
}

impl BezierPatch {
    pub fn min(&self) -> f64 {
        self.0
            .iter()
            .flatten()
            .copied()
            .fold(f64::INFINITY, f64::min)
    }

    pub fn max(&self) -> f64 {
        self.0
            .iter()
            .flatten()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The patch restricted to `[s0, s1] x [t0, t1]` of the unit square (exact
    /// reparametrisation by de Casteljau), whose control net bounds it more tightly.
    pub fn restrict(&self, s0: f64, s1: f64, t0: f64, t1: f64) -> BezierPatch {
        let rows = self.0.map(|r| restrict_cubic(r, s0, s1));
        let mut out = [[0.0; 4]; 4];
        for q in 0..4 {
            let col = restrict_cubic([rows[0][q], rows[1][q], rows[2][q], rows[3][q]], t0, t1);
            for r in 0..4 {
                out[r][q] = col[r];
            }
        }
        BezierPatch(out)
    }

    pub fn eval(&self, u: f64, v: f64) -> f64 {
        let rows = self.0.map(|r| de_casteljau(r, u));
        de_casteljau(rows, v)
    }
}

/// Value of a cubic Bézier at `x`.
pub fn de_casteljau(p: [f64; 4], x: f64) -> f64 {
    split_cubic(p, x).0[3]
}

/// Splits a cubic Bézier at `x` into its left and right pieces.
pub fn split_cubic(p: [f64; 4], x: f64) -> ([f64; 4], [f64; 4]) {
    let l = |a: f64, b: f64| a + (b - a) * x;
    let (a1, b1, c1) = (l(p[0], p[1]), l(p[1], p[2]), l(p[2], p[3]));
    let (a2, b2) = (l(a1, b1), l(b1, c1));
    let a3 = l(a2, b2);
    ([p[0], a1, a2, a3], [a3, b2, c1, p[3]])
}

/// The cubic restricted to `[x0, x1]`, reparametrised over `[0, 1]`.
pub fn restrict_cubic(p: [f64; 4], x0: f64, x1: f64) -> [f64; 4] {
    let right = split_cubic(p, x0).1;
    if x0 >= 1.0 {
        return [right[0]; 4];
    }
    let rel = ((x1 - x0) / (1.0 - x0)).clamp(0.0, 1.0);
    split_cubic(right, rel).0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bezier_patch_agrees_with_spline() {
        let b: Vec<f64> = (0..20)
            .map(|i| ((i * 7) % 5) as f64 - 1.3 * (i % 3) as f64)
            .collect();
        let surf = UniformCubicSurface::new(5, 4, b).unwrap();
        for (h, g) in [(0, 0), (3, 2), (1, 1)] {
            let p = bezier_patch(&surf, h, g);
            for (u, v) in [(0.0, 0.0), (0.3, 0.9), (1.0, 0.5)] {
                let f = surf.eval(h as f64 + u, g as f64 + v);
                assert!((p.eval(u, v) - f).abs() < 1e-12);
                assert!(p.min() <= f + 1e-12 && f <= p.max() + 1e-12);
            }
            let r = p.restrict(0.2, 0.6, 0.1, 0.3);
            assert!((r.eval(0.5, 0.5) - p.eval(0.4, 0.2)).abs() < 1e-12);
            assert!((r.eval(1.0, 1.0) - p.eval(0.6, 0.3)).abs() < 1e-12);
        }
    }
}
