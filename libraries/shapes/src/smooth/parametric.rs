//! Parametric fits in R^3 with parameter correction (paper 004, Section 6.2):
//! fit the three coordinates over the domain, move every sample's parameters
//! to its foot point on the fitted surface, and fit again; each round lowers
//! the distances that the least squares measure only along the old
//! parameters.

use super::bernstein::bernstein5_jet;
use super::error::SmoothError;
use super::fit::{FitErrors, SmoothFitter, SmoothSurface};
use super::foot_point::{foot_point, PatchAdjacency, PatchSurface};
use super::sample::Sample;
use crate::mesh::PATCH_COEFFICIENTS;
use glam::DVec3;
use rayon::prelude::*;

/// Gauss-Newton steps per foot point and correction round.
const FOOT_POINT_STEPS: usize = 8;

/// A parametric fit and how it improved.
#[derive(Debug, Clone)]
pub struct ParametricFit {
    pub surface: SmoothSurface,
    /// The samples' parameters after the last correction.
    pub samples: Vec<Sample>,
    /// Errors (28) after the first fit and after each correction round, each
    /// measured at the parameters that round fitted with.
    pub rounds: Vec<FitErrors>,
    /// The points' distances to the final surface itself, at their foot
    /// points (never above the last round's errors).
    pub distances: FitErrors,
}

impl PatchSurface for SmoothSurface {
    /// The first three components (missing ones zero). The hot loop of
    /// parameter correction: contracted along u first, then v.
    fn jet(&self, face: usize, u: f64, v: f64) -> [DVec3; 3] {
        let (bu, du) = bernstein5_jet(u);
        let (bv, dv) = bernstein5_jet(v);
        let dim = self.dim;
        let patch =
            &self.coefficients[face * PATCH_COEFFICIENTS * dim..][..PATCH_COEFFICIENTS * dim];
        let mut out = [DVec3::ZERO; 3];
        for j in 0..6 {
            let (mut value, mut along) = (DVec3::ZERO, DVec3::ZERO);
            for i in 0..6 {
                let c = coefficient(patch, (6 * j + i) * dim, dim);
                value += bu[i] * c;
                along += du[i] * c;
            }
            out[0] += bv[j] * value;
            out[1] += bv[j] * along;
            out[2] += dv[j] * value;
        }
        out
    }
}

/// The first three values of the coefficient at `at`.
fn coefficient(patch: &[f64], at: usize, dim: usize) -> DVec3 {
    match dim {
        3.. => DVec3::new(patch[at], patch[at + 1], patch[at + 2]),
        2 => DVec3::new(patch[at], patch[at + 1], 0.0),
        _ => DVec3::new(patch[at], 0.0, 0.0),
    }
}

/// Moves each sample to the foot point of its point (`points[3 n..3 n + 3]`)
/// on `surface`, across patch borders; returns how many moved.
pub fn correct_parameters(
    surface: &SmoothSurface,
    adjacency: &PatchAdjacency,
    samples: &mut [Sample],
    points: &[f64],
) -> usize {
    samples
        .par_iter_mut()
        .zip(points.par_chunks_exact(3))
        .map(|(sample, p)| {
            let p = DVec3::new(p[0], p[1], p[2]);
            let (moved, _) = foot_point(surface, adjacency, *sample, p, FOOT_POINT_STEPS);
            let changed = moved != *sample;
            *sample = moved;
            usize::from(changed)
        })
        .sum()
}

impl SmoothFitter {
    /// Fits `points` (x, y, z per sample) over the domain at `samples`, then
    /// `corrections` rounds of parameter correction and refitting.
    pub fn fit_parametric(
        &self,
        samples: &[Sample],
        points: &[f64],
        lambda: f64,
        corrections: usize,
    ) -> Result<ParametricFit, SmoothError> {
        let mut samples = samples.to_vec();
        let mut surface = self.fit(&samples, points, 3, lambda)?;
        let mut rounds = vec![surface.errors(&samples, points)];
        for _ in 0..corrections {
            correct_parameters(&surface, self.adjacency(), &mut samples, points);
            surface = self.fit(&samples, points, 3, lambda)?;
            rounds.push(surface.errors(&samples, points));
        }
        let mut feet = samples.clone();
        correct_parameters(&surface, self.adjacency(), &mut feet, points);
        let distances = surface.errors(&feet, points);
        Ok(ParametricFit {
            surface,
            samples,
            rounds,
            distances,
        })
    }

    /// As [`Self::fit_parametric`], with the samples first moved to their foot
    /// points on `previous`, a fit of an earlier cloud of the same object over
    /// this domain: a live stream's warm start, closer than the domain mesh's
    /// stand-in surface, so fewer rounds reach the same error. A `previous`
    /// of another space is ignored.
    pub fn fit_parametric_warm(
        &self,
        previous: &SmoothSurface,
        samples: &[Sample],
        points: &[f64],
        lambda: f64,
        corrections: usize,
    ) -> Result<ParametricFit, SmoothError> {
        let same_space = previous.dim == 3
            && previous.faces() == self.domain.mesh.face_count()
            && previous.weights.len() == 3 * self.basis.len();
        if !same_space || points.len() != 3 * samples.len() {
            return self.fit_parametric(samples, points, lambda, corrections);
        }
        let mut warm = samples.to_vec();
        correct_parameters(previous, self.adjacency(), &mut warm, points);
        self.fit_parametric(&warm, points, lambda, corrections)
    }
}
