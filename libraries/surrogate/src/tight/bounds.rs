//! The bounds that make the spline LP well posed where data is sparse: one
//! safety floor under every coefficient, far below the data, and a ceiling over
//! all of them. Both are part of the LP's definition, shared by the fit and the
//! reference; derived from the same constraint set (the fitter's candidates),
//! they are the same numbers in both.

use crate::{Candidate, TrimMask};

/// How far below the lowest constraint the safety floor lies, in height ranges
/// of the constraints.
pub const SAFETY_DEPTH: f64 = 10.0;

/// Lower bound of every coefficient: [`SAFETY_DEPTH`] height ranges below the
/// lowest constraint. The LP needs one: where a kept triangle holds few points,
/// a spline can vanish at those points and have any negative integral, so the
/// unbounded optimum would plunge between them. A floor at the data
/// ([`floors_of`], the LP's floor until issue 27) bound along every silhouette
/// and left 3 to 27 % of the optimum's excess volume unclaimed on the
/// simulator scenes. This one binds only where the optimum dives between sparse
/// points (a few dozen of the 400 coefficients of a 20 x 20 grid on the
/// spheres, none on the terrain seen from above), and there it is where the dive
/// stops, at the same depth for the fit and the reference. The price: between
/// its candidates the fit's optimum may dip under points that are not
/// candidates, and certification's local raise pays that back (see
/// `docs/benchmarks.md`, the tightness table). `-inf` without constraints.
pub fn safety_floor(constraints: &[Candidate]) -> f64 {
    let (lo, hi) = height_range(constraints);
    if !lo.is_finite() {
        return f64::NEG_INFINITY;
    }
    lo - SAFETY_DEPTH * range_of(lo, hi)
}

/// The data floor of each coefficient: the lowest constraint height in the kept
/// cells it acts on (`+inf` for a coefficient without any). No longer a bound of
/// the LP (see [`safety_floor`]), but the floor of the default lowering pass
/// (`crate::tighten` keeps it alongside its constraint columns) and the level
/// the excess measure gives empty pieces (see [`super::excess`]).
pub fn floors_of(
    cols: usize,
    rows: usize,
    grouped: &[(usize, usize, Vec<Candidate>)],
    trim: &TrimMask,
) -> Vec<f64> {
    let mut lowest = vec![f64::INFINITY; (cols - 1) * (rows - 1)];
    for (h, g, list) in grouped.iter().filter(|(h, g, _)| trim.cell_kept(*h, *g)) {
        let cell = &mut lowest[g * (cols - 1) + h];
        *cell = list.iter().fold(*cell, |m, c| m.min(c.height));
    }
    crate::tighten::floors_of_cells(cols, rows, &lowest)
}

/// Upper bound of every coefficient: the highest constraint plus the height range
/// of the constraints. It never binds where data is dense (an optimal surface does
/// not overshoot its data by a whole range), but without it a coefficient whose
/// support barely touches the kept region (tiny objective weight) can be sent
/// arbitrarily high to let its neighbours drop, which leaves the LP nearly
/// unbounded and badly conditioned.
pub fn ceiling_of(constraints: &[Candidate]) -> f64 {
    let (lo, hi) = height_range(constraints);
    if !hi.is_finite() {
        return f64::INFINITY;
    }
    hi + range_of(lo, hi)
}

/// Lowest and highest constraint height (`+inf, -inf` without constraints).
fn height_range(constraints: &[Candidate]) -> (f64, f64) {
    constraints
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| {
            (a.min(c.height), b.max(c.height))
        })
}

/// The height range, at least a sliver of the heights' magnitude (flat data).
fn range_of(lo: f64, hi: f64) -> f64 {
    (hi - lo).max(1e-3 * (1.0 + hi.abs().max(lo.abs())))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(height: f64) -> Candidate {
        Candidate {
            s: 0.5,
            t: 0.5,
            height,
        }
    }

    #[test]
    fn the_floor_lies_far_below_and_the_ceiling_above_the_data() {
        let data = [at(-2.0), at(3.0), at(1.0)];
        assert_eq!(safety_floor(&data), -2.0 - SAFETY_DEPTH * 5.0);
        assert_eq!(ceiling_of(&data), 8.0);
        // Flat data still gets room on both sides.
        let flat = [at(4.0), at(4.0)];
        assert!(safety_floor(&flat) < 4.0 && ceiling_of(&flat) > 4.0);
        assert_eq!(safety_floor(&[]), f64::NEG_INFINITY);
        assert_eq!(ceiling_of(&[]), f64::INFINITY);
    }
}
