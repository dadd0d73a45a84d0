//! A uniform cubic spline curve (function) of one variable.

use super::basis::{basis_derivative_weights, basis_weights, knot_interval};
use serde::{Deserialize, Serialize};

/// `f(s) = sum_i b_i N_i(s)` on `[0, n-1]` with `b_{-1} = b_0`, `b_n = b_{n-1}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UniformCubicCurve {
    pub coefficients: Vec<f64>,
}

impl UniformCubicCurve {
    /// A curve needs at least two coefficients (one knot interval).
    pub fn new(coefficients: Vec<f64>) -> Option<Self> {
        (coefficients.len() >= 2).then_some(Self { coefficients })
    }

    pub fn len(&self) -> usize {
        self.coefficients.len()
    }

    pub fn is_empty(&self) -> bool {
        self.coefficients.is_empty()
    }

    /// Coefficient `b_i` for `i` in `-1 ..= n` (the repeated ends included).
    #[inline]
    pub fn coefficient(&self, i: isize) -> f64 {
        let n = self.coefficients.len() as isize;
        self.coefficients[i.clamp(0, n - 1) as usize]
    }

    pub fn eval(&self, s: f64) -> f64 {
        self.eval_with(s, basis_weights)
    }

    pub fn derivative(&self, s: f64) -> f64 {
        self.eval_with(s, basis_derivative_weights)
    }

    fn eval_with(&self, s: f64, weights: fn(f64) -> [f64; 4]) -> f64 {
        let (h, u) = knot_interval(s, self.len());
        let w = weights(u);
        (0..4)
            .map(|k| w[k] * self.coefficient(h as isize + k as isize - 1))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_linear_functions_inside_and_is_flat_at_ends() {
        // The end conditions make the spline's slope vanish at 0 and n-1 only for
        // symmetric data; constants are reproduced everywhere.
        let c = UniformCubicCurve::new(vec![2.5; 6]).unwrap();
        for i in 0..=10 {
            assert!((c.eval(i as f64 * 0.5) - 2.5).abs() < 1e-14);
            assert!(c.derivative(i as f64 * 0.5).abs() < 1e-14);
        }
        let lin = UniformCubicCurve::new((0..8).map(|i| i as f64).collect()).unwrap();
        // Away from the ends a uniform cubic spline reproduces linear data.
        assert!((lin.eval(3.3) - 3.3).abs() < 1e-12);
        assert!((lin.derivative(3.3) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_single_coefficient() {
        assert!(UniformCubicCurve::new(vec![1.0]).is_none());
    }
}
