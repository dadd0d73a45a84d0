//! `Tightness::Optimal`: the fitter's surface moved to the optimum of the LP over
//! its candidates, solved by the interior-point method from the heuristic surface.

use super::ipm::{self, IpmSettings};
use super::lp::SplineLp;
use super::LpError;
use crate::{lower_onto_candidates, Candidate, TrimMask};
use shroud_geometry::spline::UniformCubicSurface;

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
/// (the grid is too large for it, or it stalls on a degenerate LP), the
/// coordinate-descent pass runs instead: the mode degrades to the default's
/// lowering rather than failing the fit.
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
    use super::super::fixture::Fixture;
    use super::super::objective_weights;
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
