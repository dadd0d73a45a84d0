//! A uniform bicubic tensor-product spline function `f(s, t)`.

use super::basis::{basis_derivative_weights, basis_weights, knot_interval};
use serde::{Deserialize, Serialize};

/// `f(s, t) = sum_{k,j} b_{k j} N_j(s) N_k(t)` on `[0, cols-1] x [0, rows-1]`.
///
/// `s` runs along the frame's `u` axis (columns `j`), `t` along `v` (rows `k`);
/// coefficients are row-major, `b[k * cols + j]`, with repeated end rows and columns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UniformCubicSurface {
    pub cols: usize,
    pub rows: usize,
    pub coefficients: Vec<f64>,
}

impl UniformCubicSurface {
    /// `None` unless the grid is at least 2 x 2 and the coefficient count matches.
    pub fn new(cols: usize, rows: usize, coefficients: Vec<f64>) -> Option<Self> {
        (cols >= 2 && rows >= 2 && coefficients.len() == cols * rows).then_some(Self {
            cols,
            rows,
            coefficients,
        })
    }

    pub fn constant(cols: usize, rows: usize, value: f64) -> Option<Self> {
        Self::new(cols, rows, vec![value; cols * rows])
    }

    /// Coefficient at column `j`, row `k`, each in `-1 ..= len` (ends repeated).
    #[inline]
    pub fn coefficient(&self, j: isize, k: isize) -> f64 {
        let j = j.clamp(0, self.cols as isize - 1) as usize;
        let k = k.clamp(0, self.rows as isize - 1) as usize;
        self.coefficients[k * self.cols + j]
    }

    /// The 4 x 4 coefficients acting on cell `(h, g)` (`h` along s, `g` along t),
    /// indexed `[row][col]`.
    #[inline]
    pub fn cell_coefficients(&self, h: usize, g: usize) -> [[f64; 4]; 4] {
        let mut c = [[0.0; 4]; 4];
        for (r, row) in c.iter_mut().enumerate() {
            for (q, v) in row.iter_mut().enumerate() {
                *v = self.coefficient(h as isize + q as isize - 1, g as isize + r as isize - 1);
            }
        }
        c
    }

    pub fn eval(&self, s: f64, t: f64) -> f64 {
        self.eval_with(s, t, basis_weights, basis_weights)
    }

    /// `(df/ds, df/dt)` in parameter units.
    pub fn gradient(&self, s: f64, t: f64) -> (f64, f64) {
        (
            self.eval_with(s, t, basis_derivative_weights, basis_weights),
            self.eval_with(s, t, basis_weights, basis_derivative_weights),
        )
    }

    #[inline]
    fn eval_with(&self, s: f64, t: f64, ws: fn(f64) -> [f64; 4], wt: fn(f64) -> [f64; 4]) -> f64 {
        let (h, u) = knot_interval(s, self.cols);
        let (g, v) = knot_interval(t, self.rows);
        let (a, b) = (ws(u), wt(v));
        Self::cell_value(&a, &b, &self.cell_coefficients(h, g))
    }

    /// `sum_q a[q] sum_r b[r] c[r][q]` in the one order every evaluation uses:
    /// the four column sums first (independent, so they run as one vector
    /// operation), then the pairs `(p0 + p2) + (p1 + p3)`. Certification evaluates
    /// every point of the cloud through this function, so it agrees with
    /// [`Self::eval`] to the bit.
    #[inline(always)]
    pub fn cell_value(a: &[f64; 4], b: &[f64; 4], c: &[[f64; 4]; 4]) -> f64 {
        let p: [f64; 4] = std::array::from_fn(|q| {
            a[q] * (((b[0] * c[0][q] + b[1] * c[1][q]) + b[2] * c[2][q]) + b[3] * c[3][q])
        });
        (p[0] + p[2]) + (p[1] + p[3])
    }

    /// Number of knot intervals along s and t.
    pub fn cells(&self) -> (usize, usize) {
        (self.cols - 1, self.rows - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::UniformCubicCurve;

    #[test]
    fn tensor_product_of_curves() {
        // f(s,t) = x(s) * y(t) when b_kj = x_j * y_k.
        let x = vec![1.0, 2.0, 0.5, 3.0];
        let y = vec![-1.0, 0.0, 2.0];
        let b: Vec<f64> = y
            .iter()
            .flat_map(|yk| x.iter().map(move |xj| xj * yk))
            .collect();
        let surf = UniformCubicSurface::new(4, 3, b).unwrap();
        let (cx, cy) = (
            UniformCubicCurve::new(x).unwrap(),
            UniformCubicCurve::new(y).unwrap(),
        );
        for (s, t) in [(0.0, 0.0), (1.3, 0.7), (3.0, 2.0), (2.5, 1.99)] {
            assert!((surf.eval(s, t) - cx.eval(s) * cy.eval(t)).abs() < 1e-12);
            let (ds, dt) = surf.gradient(s, t);
            assert!((ds - cx.derivative(s) * cy.eval(t)).abs() < 1e-12);
            assert!((dt - cx.eval(s) * cy.derivative(t)).abs() < 1e-12);
        }
    }

    #[test]
    fn rejects_bad_shapes() {
        assert!(UniformCubicSurface::new(1, 3, vec![0.0; 3]).is_none());
        assert!(UniformCubicSurface::new(2, 2, vec![0.0; 3]).is_none());
    }
}
