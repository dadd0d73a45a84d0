//! The optimal safe surface in the spline space (the `--tight` mode) and the
//! tightness measure the modes are compared by.
//!
//! The optimum is a linear program: minimise `∫_kept f` subject to `f` lying on
//! the safe side of every constraint point ([`lp`], [`objective`]). The fit solves
//! it over the candidates with a banded primal-dual interior-point method
//! ([`ipm`]); [`lp_reference`] solves it over every point with clarabel and
//! cutting planes; [`excess`] measures how far a surface stands off the data.

pub mod banded_cholesky;
mod cloud_side;
mod error;
pub mod excess;
#[cfg(test)]
mod fixture;
pub mod ipm;
pub mod lp;
pub mod lp_reference;
pub mod objective;
pub mod quadrature;

pub use cloud_side::CloudSide;
pub use error::LpError;
pub use excess::{excess_volume, Envelope, DEFAULT_RASTER};
pub use ipm::{IpmSettings, IpmSolution};
pub use lp::SplineLp;
pub use lp_reference::{optimal_surface, ReferenceOptimum};
pub use objective::objective_weights;

use crate::spline::UniformCubicSurface;
use crate::surrogate::{lower_onto_candidates, Candidate, TrimMask};

/// Sweeps of the coordinate-descent fallback when the LP cannot be solved.
const FALLBACK_SWEEPS: usize = 50;

/// Stopping rule of the fit. A gap of `1e-4` of the volume above the lowest
/// candidate is a few thousandths of a percent of the optimum's excess volume on
/// the benchmark scenes, and stopping there saves a quarter of the iterations;
/// the final lift covers the remaining infeasibility (`1e-5` of the heights).
const FIT_SETTINGS: IpmSettings = IpmSettings {
    gap: 1e-4,
    feasibility: 1e-5,
    max_iterations: 60,
};

/// Moves `surface` (upper sense) to the optimum of the candidate LP and returns
/// the number of coefficients that changed. Should the interior-point method fail
/// (it has not been seen to), the coordinate-descent pass runs instead, so the
/// result is never worse than the default mode's.
pub fn lower_to_optimum(
    surface: &mut UniformCubicSurface,
    candidates: &[Candidate],
    trim: &TrimMask,
    sub: usize,
) -> u64 {
    match optimum_of_candidates(surface, candidates, trim) {
        Ok(coefficients) => {
            let moved = coefficients
                .iter()
                .zip(&surface.coefficients)
                .filter(|(a, b)| a != b)
                .count();
            surface.coefficients = coefficients;
            moved as u64
        }
        Err(_) => lower_onto_candidates(surface, candidates, trim, sub, FALLBACK_SWEEPS),
    }
}

/// The coefficients of the candidate-LP optimum, warm-started from `surface`.
pub fn optimum_of_candidates(
    surface: &UniformCubicSurface,
    candidates: &[Candidate],
    trim: &TrimMask,
) -> Result<Vec<f64>, LpError> {
    let lp = SplineLp::new(surface, trim, candidates)?;
    let solution = ipm::solve(&lp, &lp.gather(&surface.coefficients), &FIT_SETTINGS)?;
    let mut coefficients = surface.coefficients.clone();
    lp.scatter(&solution.x, &mut coefficients);
    Ok(coefficients)
}

#[cfg(test)]
mod tests {
    use super::fixture::Fixture;
    use super::*;

    #[test]
    fn the_optimum_holds_every_candidate_and_lowers_the_integral() {
        for fixture in [
            Fixture::spheres(20_000, 12, 0.0),
            Fixture::terrain(20_000, 12),
        ] {
            let candidates = fixture.candidates();
            let trim = &fixture.plain.trim;
            let mut surface = fixture.plain.upper.as_ref().unwrap().surface.clone();
            let before = objective_weights(surface.cols, surface.rows, trim);
            let integral = |s: &UniformCubicSurface| {
                s.coefficients
                    .iter()
                    .zip(&before)
                    .map(|(a, b)| a * b)
                    .sum::<f64>()
            };
            let heuristic = integral(&surface);
            let moved =
                lower_to_optimum(&mut surface, &candidates, trim, fixture.options.sub_cells);
            assert!(moved > 0);
            for c in &candidates {
                assert!(
                    surface.eval(c.s, c.t) - c.height >= -1e-9,
                    "candidate above the optimum"
                );
            }
            assert!(integral(&surface) < heuristic);
        }
    }
}
