//! The bounds that make the spline LP well posed where data is sparse: a floor
//! under each coefficient and a ceiling over all of them. Neither binds where
//! data is dense; both are part of the LP's definition, shared by the fit, the
//! reference and the excess measure.

use super::cells::cell_slots;
use crate::{Candidate, TrimMask};

/// Lower bound of each coefficient: the lowest constraint height in the kept
/// cells it acts on. The LP needs one: where a kept triangle holds few points, a
/// spline can vanish at those points and have any negative integral, so the
/// unbounded optimum would plunge between them. This floor keeps the control net
/// above the lowest data it acts on, and with it (convex hull property) the
/// surface above the lowest data within three cells; where data is dense it does
/// not bind. Coefficients without constraints get `+inf` (they are never unknowns).
pub fn floors_of(
    cols: usize,
    rows: usize,
    grouped: &[(usize, usize, Vec<Candidate>)],
    trim: &TrimMask,
) -> Vec<f64> {
    let mut floors = vec![f64::INFINITY; cols * rows];
    for (h, g, list) in grouped.iter().filter(|(h, g, _)| trim.cell_kept(*h, *g)) {
        let lowest = list.iter().fold(f64::INFINITY, |m, c| m.min(c.height));
        for i in cell_slots(*h, *g, cols, rows) {
            floors[i] = floors[i].min(lowest);
        }
    }
    floors
}

/// Upper bound of every coefficient: the highest constraint plus the height range
/// of the constraints. It never binds where data is dense (an optimal surface does
/// not overshoot its data by a whole range), but without it a coefficient whose
/// support barely touches the kept region (tiny objective weight) can be sent
/// arbitrarily high to let its neighbours drop, which leaves the LP nearly
/// unbounded and badly conditioned.
pub fn ceiling_of(constraints: &[Candidate]) -> f64 {
    let (lo, hi) = constraints
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| {
            (a.min(c.height), b.max(c.height))
        });
    if !hi.is_finite() {
        return f64::INFINITY;
    }
    hi + (hi - lo).max(1e-3 * (1.0 + hi.abs().max(lo.abs())))
}
