//! Why an optimal safe surface could not be computed.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum LpError {
    #[error("constraint {index} has a non-finite parameter or height ({s}, {t}, {height})")]
    NonFiniteConstraint {
        index: usize,
        s: f64,
        t: f64,
        height: f64,
    },
    #[error("the surface is {cols} x {rows} control points but the trim mask has {cells_s} x {cells_t} cells")]
    TrimMismatch {
        cols: usize,
        rows: usize,
        cells_s: usize,
        cells_t: usize,
    },
    #[error("the normal equations lost definiteness at unknown {0} (the LP is degenerate beyond repair)")]
    NotPositiveDefinite(usize),
    #[error("the starting point has {got} values but the LP has {expected} unknowns")]
    StartLength { expected: usize, got: usize },
    #[error(
        "the LP has {unknowns} unknowns with half-bandwidth {bandwidth}: too large for the banded \
         interior-point method (about {flops:e} multiply-adds per factorisation)"
    )]
    TooLarge {
        unknowns: usize,
        bandwidth: usize,
        flops: f64,
    },
    #[error("the interior-point method did not converge in {iterations} iterations (gap {gap:e}, infeasibility {infeasibility:e})")]
    NoConvergence {
        iterations: usize,
        gap: f64,
        infeasibility: f64,
    },
    #[error("the reference LP solver failed: {0}")]
    Reference(String),
    #[error("cutting planes did not reach a feasible optimum in {0} rounds")]
    CuttingPlanes(usize),
}
