//! Evaluating the RBF at many points at once, as the zero-set sampler asks for
//! it: exactly, centre by centre ([`ExactField`]), or split into a near sum and
//! an interpolated far field ([`super::SplitField`]).

use super::eval::Rbf;
use glam::DVec3;
use rayon::prelude::*;

/// A scalar field evaluated in batches. Evaluators may keep state between
/// batches (a cache), hence `&mut self`.
pub trait BatchField {
    /// `s` at every point.
    fn values(&mut self, points: &[DVec3]) -> Vec<f64>;
    /// `s` and its gradient (world units) at every point.
    fn value_gradients(&mut self, points: &[DVec3]) -> Vec<(f64, DVec3)>;
}

/// The RBF summed over every centre at every point, in parallel.
#[derive(Debug, Clone, Copy)]
pub struct ExactField<'a>(pub &'a Rbf);

impl BatchField for ExactField<'_> {
    fn values(&mut self, points: &[DVec3]) -> Vec<f64> {
        self.0.values(points)
    }

    fn value_gradients(&mut self, points: &[DVec3]) -> Vec<(f64, DVec3)> {
        points
            .par_iter()
            .with_min_len(32)
            .map(|&p| self.0.value_gradient(p))
            .collect()
    }
}
