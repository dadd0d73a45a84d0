//! A primal-dual interior-point method (Mehrotra predictor-corrector) for the
//! spline LP `min c.x  s.t.  A x >= h,  floors <= x <= ceiling`.
//!
//! Each iteration solves the normal equations `(A^T D A + D_b) dx = r` once for
//! the predictor and once for the corrector with the same factor. `A^T D A` is
//! assembled cell by cell (all rows of a cell share their 16 unknowns) and is
//! banded in the unknowns' order, so a banded Cholesky factorisation does it.

mod normal_equations;
mod state;
#[cfg(test)]
mod tests;

use super::error::LpError;
use super::lp::SplineLp;
use state::State;

/// Stopping rule and budget.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IpmSettings {
    /// Complementarity gap `s.y` to stop at, relative to the volume between the
    /// surface and the lowest constraint, `c.x - (sum c) min h`. Both are
    /// unchanged when every height moves by a constant (the basis sums to one),
    /// so the rule does not depend on where the frame's origin is.
    pub gap: f64,
    /// Relative primal and dual infeasibility to stop at.
    pub feasibility: f64,
    pub max_iterations: usize,
}

impl Default for IpmSettings {
    fn default() -> Self {
        Self {
            gap: 1e-9,
            feasibility: 1e-9,
            max_iterations: 60,
        }
    }
}

/// The solution in the LP's unknowns.
#[derive(Debug, Clone, PartialEq)]
pub struct IpmSolution {
    pub x: Vec<f64>,
    /// Dual values of the constraint rows, then of the floors, then of the ceilings.
    pub y: Vec<f64>,
    pub objective: f64,
    pub iterations: usize,
    /// The uniform lift applied at the end so that every row holds exactly (the
    /// unknowns are also raised to their floors first).
    pub lift: f64,
}

/// Largest factorisation accepted, in multiply-adds (`n bw^2 / 2`): about a
/// second per iteration on one core. A 100 x 100 grid needs ~5e8; beyond the
/// limit the caller falls back to coordinate descent.
const MAX_FACTOR_FLOPS: f64 = 2e9;

/// Solves `lp` from `start` (the values of its unknowns, as from
/// [`SplineLp::gather`]; feasibility is not required). The rows are the
/// constraints, then one identity row per unknown for its floor and one negated
/// identity row for the ceiling; slacks `s = A x - h` and duals `y` live on all
/// of them.
pub fn solve(lp: &SplineLp, start: &[f64], settings: &IpmSettings) -> Result<IpmSolution, LpError> {
    let (unknowns, bandwidth) = (lp.unknowns(), lp.bandwidth);
    let flops = unknowns as f64 * (bandwidth as f64 + 1.0).powi(2) / 2.0;
    if flops > MAX_FACTOR_FLOPS {
        return Err(LpError::TooLarge {
            unknowns,
            bandwidth,
            flops,
        });
    }
    if start.len() != unknowns {
        return Err(LpError::StartLength {
            expected: unknowns,
            got: start.len(),
        });
    }
    let mut state = State::new(lp, start)?;
    let mut best = Best {
        merit: f64::INFINITY,
        x: Vec::new(),
        y: Vec::new(),
        at: 0,
    };
    let mut iterations = 0;
    loop {
        let report = state.residuals();
        let merit = report.merit(settings);
        if merit <= 1.0 {
            return Ok(state.finish(iterations));
        }
        best.offer(merit, &state, iterations);
        // Near the optimum the normal equations become so ill-conditioned that the
        // residuals can stall above the tolerance (and then grow again) while the
        // complementarity gap has long converged.
        let stalled = report.gap <= settings.gap && iterations >= best.at + STALL_ITERATIONS;
        if iterations == settings.max_iterations || stalled {
            if best.merit > ACCEPTABLE_MERIT {
                return Err(LpError::NoConvergence {
                    iterations,
                    gap: report.gap,
                    infeasibility: report.primal.max(report.dual),
                });
            }
            (state.x, state.y) = (best.x, best.y);
            return Ok(state.finish(iterations));
        }
        state.step()?;
        iterations += 1;
    }
}

/// The iterate closest to the stopping rule so far.
struct Best {
    merit: f64,
    x: Vec<f64>,
    y: Vec<f64>,
    at: usize,
}

impl Best {
    fn offer(&mut self, merit: f64, state: &State, iteration: usize) {
        if merit < self.merit {
            *self = Best {
                merit,
                x: state.x.clone(),
                y: state.y.clone(),
                at: iteration,
            };
        }
    }
}

/// Iterations without a better iterate, once the gap has closed, after which the
/// method stops.
const STALL_ITERATIONS: usize = 6;
/// A stalled run still returns its best iterate if that meets the tolerances to
/// within this factor (the final lift makes it feasible in any case).
const ACCEPTABLE_MERIT: f64 = 1e3;
