//! The reduced constraint set of a surface fit: the extreme point of every
//! occupied sub-cell, with its exact parameters. Tightening and the optimal (LP)
//! mode constrain the surface at these points; certification then checks all.

use super::bins::SubCellMaxima;

/// A constraint `f(s, t) >= height` in the upper sense (a lower surface's
/// heights are negated).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate {
    pub s: f64,
    pub t: f64,
    pub height: f64,
}

/// One candidate per occupied sub-cell.
pub fn candidates_of(
    maxima: &SubCellMaxima,
    param_of: &dyn Fn(u32) -> (f64, f64),
) -> Vec<Candidate> {
    maxima
        .occupied()
        .map(|(_, height, idx)| {
            let (s, t) = param_of(idx);
            Candidate { s, t, height }
        })
        .collect()
}
