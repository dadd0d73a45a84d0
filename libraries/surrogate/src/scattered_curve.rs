//! Section 5: the scattered-data curve surrogate, Heuristic(σ, b, λ).
//!
//! One sample per Greville abscissa `j` is selected (`λ_j`, initially the highest
//! sample with `round(s) = j`) and the Lemma 5.1 bound is made to interpolate the
//! selection, `C_λ M b = Λ` (eq. 7); signs are iterated as in Section 4, then the
//! worst sample above the bound replaces the selection of its abscissa, until no
//! sample is above. Abscissae with no sample are free (`Δ_j b = 0`).

use super::error::FitError;
use super::lower_bound::{negative_differences, scattered_lower_bound};
use super::upper_hull::upper_hull_into;
use shroud_geometry::math::BandedMatrix;
use shroud_geometry::spline::{knot_interval, second_difference, UniformCubicCurve};

/// Selection state carried from one frame to the next (warm start).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CurveWarmStart {
    /// The previous frame's coefficients.
    pub coefficients: Vec<f64>,
    /// Parameter of the selected sample per Greville abscissa (`None`: free).
    pub selected: Vec<Option<f64>>,
    /// `σ_j` of the converged fit.
    pub signs: Vec<bool>,
}

/// Result of a Section 5 fit.
#[derive(Debug, Clone, PartialEq)]
pub struct ScatteredCurveFit {
    pub curve: UniformCubicCurve,
    /// Banded solves ("LDL decompositions" of Figure 9).
    pub solves: usize,
    /// Selection replacements (step 5 of the heuristic).
    pub reselections: usize,
    /// Intervals that needed the monotone local raise after the iteration cap.
    pub raised_intervals: usize,
    pub warm: CurveWarmStart,
}

/// Iteration budget of the heuristic; past it the local raise finishes the job.
pub const DEFAULT_MAX_SOLVES: usize = 64;
const MAX_SIGN_ROUNDS: usize = 8;
/// Relative margin (in units of `|y|`) of the final cover, a few dozen ulps.
const ROUNDING_MARGIN: f64 = 32.0 * f64::EPSILON;

/// Fits a curve with `n` coefficients whose Lemma 5.1 bound lies on or above every
/// sample `(s, y)`, `s` in `[0, n-1]`. Exact: reduces each knot interval to its
/// upper hull first (see `lower_bound` for why that suffices).
pub fn fit_curve_above(samples: &[(f64, f64)], n: usize) -> Result<ScatteredCurveFit, FitError> {
    check_samples(samples, n)?;
    let mut sorted = samples.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let candidates = hull_per_interval(&sorted, n);
    fit_sorted_candidates_above(&candidates, n, None, DEFAULT_MAX_SOLVES)
}

pub(crate) fn check_samples(samples: &[(f64, f64)], n: usize) -> Result<(), FitError> {
    if n < 2 {
        return Err(FitError::CurveTooShort(n));
    }
    if samples.is_empty() {
        return Err(FitError::NoSamples);
    }
    match samples
        .iter()
        .position(|(s, y)| !s.is_finite() || !y.is_finite())
    {
        Some(index) => Err(FitError::NonFiniteSample { index }),
        None => Ok(()),
    }
}

/// Upper-hull vertices of each knot interval of samples sorted by `s`.
pub fn hull_per_interval(sorted: &[(f64, f64)], n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut hull = Vec::new();
    let mut start = 0;
    while start < sorted.len() {
        let h = knot_interval(sorted[start].0, n).0;
        let end = start + sorted[start..].partition_point(|p| knot_interval(p.0, n).0 == h);
        upper_hull_into(&sorted[start..end], &mut hull);
        out.extend_from_slice(&hull);
        start = end;
    }
    out
}

/// Heuristic(σ, b, λ) on candidates sorted by `s` (every sample that must end up
/// below the bound). `warm` seeds signs and selection from the previous frame.
pub fn fit_sorted_candidates_above(
    samples: &[(f64, f64)],
    n: usize,
    warm: Option<&CurveWarmStart>,
    max_solves: usize,
) -> Result<ScatteredCurveFit, FitError> {
    check_samples(samples, n)?;
    let ranges = greville_ranges(samples, n);
    let mut selection = initial_selection(samples, &ranges, warm);
    let mut signs = match warm {
        Some(w) if w.signs.len() == n => w.signs.clone(),
        _ => vec![true; n],
    };
    let scale = samples.iter().fold(1.0f64, |m, p| m.max(p.1.abs()));
    let tolerance = 1e-12 * scale;
    let mut matrix = BandedMatrix::<2, 2>::zeros(n);
    let mut b = vec![0.0; n];
    let (mut solves, mut reselections) = (0, 0);
    'outer: while solves < max_solves.max(1) {
        for _ in 0..MAX_SIGN_ROUNDS {
            if solve_selection(&mut matrix, samples, &selection, &signs, &mut b).is_err() {
                b = vec![scale_max(samples); n];
                solves += 1;
                break 'outer;
            }
            solves += 1;
            if !update_signs(&b, &mut signs) {
                break;
            }
        }
        let Some((worst, excess)) = worst_violation(samples, &b) else {
            break;
        };
        if excess <= tolerance {
            break;
        }
        let j = greville_of(samples[worst].0, n);
        if selection[j] == Some(worst) {
            break;
        }
        selection[j] = Some(worst);
        reselections += 1;
    }
    let raised_intervals = raise_to_cover(&mut b, samples);
    let warm = CurveWarmStart {
        coefficients: b.clone(),
        selected: selection.iter().map(|s| s.map(|i| samples[i].0)).collect(),
        signs,
    };
    Ok(ScatteredCurveFit {
        curve: UniformCubicCurve { coefficients: b },
        solves,
        reselections,
        raised_intervals,
        warm,
    })
}

fn scale_max(samples: &[(f64, f64)]) -> f64 {
    samples.iter().fold(f64::NEG_INFINITY, |m, p| m.max(p.1))
}

#[inline]
fn greville_of(s: f64, n: usize) -> usize {
    ((s + 0.5).max(0.0) as usize).min(n - 1)
}

/// `ranges[j]..ranges[j+1]` are the samples with `round(s) = j`.
fn greville_ranges(samples: &[(f64, f64)], n: usize) -> Vec<usize> {
    (0..=n)
        .map(|j| samples.partition_point(|p| greville_of(p.0, n) < j))
        .collect()
}

fn initial_selection(
    samples: &[(f64, f64)],
    ranges: &[usize],
    warm: Option<&CurveWarmStart>,
) -> Vec<Option<usize>> {
    let n = ranges.len() - 1;
    // Warm: per abscissa, the candidate furthest above (or least below) the previous
    // frame's bound, i.e. the one most likely to bind now. Cold (step 1): the highest.
    let previous = warm.filter(|w| w.coefficients.len() == n).map(|w| {
        let neg = negative_differences(&w.coefficients);
        (w.coefficients.as_slice(), neg)
    });
    let score = |i: usize| match &previous {
        Some((b, neg)) => samples[i].1 - scattered_lower_bound(b, neg, samples[i].0),
        None => samples[i].1,
    };
    (0..n)
        .map(|j| (ranges[j]..ranges[j + 1]).max_by(|&a, &c| score(a).total_cmp(&score(c))))
        .collect()
}

fn solve_selection(
    matrix: &mut BandedMatrix<2, 2>,
    samples: &[(f64, f64)],
    selection: &[Option<usize>],
    signs: &[bool],
    b: &mut [f64],
) -> Result<(), shroud_geometry::math::BandedSolveError> {
    let n = b.len();
    matrix.clear();
    for (j, sel) in selection.iter().enumerate() {
        match sel {
            Some(i) => {
                let (s, y) = samples[*i];
                let (h, u) = knot_interval(s, n);
                let w = 1.0 - u;
                matrix.add(j, h, w);
                matrix.add(j, h + 1, u);
                if signs[h] {
                    add_difference_row(matrix, j, h, w * w * w / 6.0);
                }
                if signs[h + 1] {
                    add_difference_row(matrix, j, h + 1, u * u * u / 6.0);
                }
                b[j] = y;
            }
            None => {
                add_difference_row(matrix, j, j, 1.0 / 6.0);
                b[j] = 0.0;
            }
        }
    }
    matrix.solve_in_place(b)
}

/// Adds `weight * (row i of D)` to matrix row `row`.
#[inline]
fn add_difference_row(matrix: &mut BandedMatrix<2, 2>, row: usize, i: usize, weight: f64) {
    let n = matrix.n();
    matrix.add(row, i.saturating_sub(1), weight);
    matrix.add(row, i, -2.0 * weight);
    matrix.add(row, (i + 1).min(n - 1), weight);
}

/// Step 4: resets `σ_j = [Δ_j b < 0]`; true when any sign changed.
fn update_signs(b: &[f64], signs: &mut [bool]) -> bool {
    let mut changed = false;
    for (j, s) in signs.iter_mut().enumerate() {
        let now = second_difference(b, j) < 0.0;
        changed |= now != *s;
        *s = now;
    }
    changed
}

/// Step 5: the sample furthest above the Lemma 5.1 bound, with its excess.
fn worst_violation(samples: &[(f64, f64)], b: &[f64]) -> Option<(usize, f64)> {
    let neg = negative_differences(b);
    samples
        .iter()
        .enumerate()
        .map(|(i, &(s, y))| (i, y - scattered_lower_bound(b, &neg, s)))
        .max_by(|a, c| a.1.total_cmp(&c.1))
}

/// Raises `b_{h-1..h+2}` by the worst excess of each knot interval `h`, in order;
/// returns how many intervals needed more than a rounding-sized raise.
/// Such a raise lifts the Lemma 5.1 bound by exactly that amount on interval `h`
/// (`Δ_h`, `Δ_{h+1}` are unchanged) and never lowers it elsewhere (a neighbouring
/// interval loses at most `v/6` through its `Δ` term but gains at least `v` through
/// its linear part, or `u v - u³v/6 >= 0` one interval further out).
fn raise_to_cover(b: &mut [f64], samples: &[(f64, f64)]) -> usize {
    let n = b.len();
    let mut neg = negative_differences(b);
    let mut raised = 0;
    let mut start = 0;
    while start < samples.len() {
        let h = knot_interval(samples[start].0, n).0;
        let end = start + samples[start..].partition_point(|p| knot_interval(p.0, n).0 == h);
        // A few ulps of margin so that evaluating the spline in f64 (a different
        // operation order than the bound) still lands on the safe side.
        let excess = samples[start..end]
            .iter()
            .map(|&(s, y)| {
                y + ROUNDING_MARGIN * (1.0 + y.abs()) - scattered_lower_bound(b, &neg, s)
            })
            .fold(0.0f64, f64::max);
        if excess > 0.0 {
            for x in &mut b[h.saturating_sub(1)..=(h + 2).min(n - 1)] {
                *x += excess;
            }
            neg = negative_differences(b);
            raised += usize::from(excess > 1e-9);
        }
        start = end;
    }
    raised
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn all_below(fit: &ScatteredCurveFit, samples: &[(f64, f64)]) -> bool {
        samples.iter().all(|&(s, y)| fit.curve.eval(s) >= y)
    }

    fn random_cloud(rng: &mut rand_pcg::Pcg64, n: usize, count: usize) -> Vec<(f64, f64)> {
        let kind = rng.random_range(0..3);
        (0..count)
            .map(|_| {
                let s = rng.random_range(0.0..=(n - 1) as f64);
                let y = match kind {
                    0 => rng.random_range(-1.0..1.0),
                    1 => (s * 1.3).sin() * 2.0 - rng.random_range(0.0..0.5),
                    _ => {
                        (if s > (n as f64) / 2.0 { 3.0 } else { 0.0 }) - rng.random_range(0.0..0.2)
                    }
                };
                (s, y)
            })
            .collect()
    }

    #[test]
    fn safe_on_random_clouds_against_brute_force() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let mut histogram = vec![0usize; DEFAULT_MAX_SOLVES + 1];
        for _ in 0..300 {
            let n = rng.random_range(2..30);
            let count = rng.random_range(1..500);
            let samples = random_cloud(&mut rng, n, count);
            let fit = fit_curve_above(&samples, n).unwrap();
            if !all_below(&fit, &samples) {
                let worst = samples
                    .iter()
                    .map(|&(s, y)| (s, y, fit.curve.eval(s) - y))
                    .min_by(|a, b| a.2.total_cmp(&b.2));
                panic!("n {n} count {count} worst {worst:?} fit {fit:?}");
            }
            histogram[fit.solves.min(DEFAULT_MAX_SOLVES)] += 1;
        }
        // Figure 9 (right): "in almost all cases less or equal to 10".
        let small: usize = histogram[..=20].iter().sum();
        assert!(small >= 270, "{histogram:?}");
    }

    #[test]
    fn tight_on_points_lying_on_a_spline() {
        // Samples taken from a spline with all Δ < 0 (concave) are interpolated.
        let b: Vec<f64> = (0..8).map(|i| -((i as f64) - 3.5).powi(2)).collect();
        let curve = UniformCubicCurve::new(b).unwrap();
        let samples: Vec<(f64, f64)> = (0..=70)
            .map(|i| {
                let s = i as f64 * 0.1;
                (s, curve.eval(s))
            })
            .collect();
        let fit = fit_curve_above(&samples, 8).unwrap();
        // Lemma 5.1 drops positive second differences, so the bound is loose where
        // the end conditions make the first difference positive; measure inside.
        let gap = samples
            .iter()
            .filter(|p| (2.0..=5.0).contains(&p.0))
            .map(|&(s, y)| fit.curve.eval(s) - y)
            .fold(0.0f64, f64::max);
        assert!(all_below(&fit, &samples));
        assert!(gap < 0.05, "gap {gap}");
    }

    #[test]
    fn free_abscissae_and_single_sample() {
        let fit = fit_curve_above(&[(2.2, 1.0)], 6).unwrap();
        assert!(fit.curve.eval(2.2) >= 1.0);
        assert_eq!(fit.warm.selected.iter().filter(|s| s.is_some()).count(), 1);
    }

    #[test]
    fn warm_start_needs_fewer_solves_on_a_moving_cloud() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let frame = |shift: f64, rng: &mut rand_pcg::Pcg64| -> Vec<(f64, f64)> {
            (0..2000)
                .map(|_| {
                    let s = rng.random_range(0.0..19.0);
                    (
                        s,
                        (s * 0.5 + shift).sin() * 3.0 - rng.random_range(0.0..0.3),
                    )
                })
                .collect()
        };
        let (mut cold_total, mut warm_total) = (0, 0);
        let mut warm: Option<CurveWarmStart> = None;
        for k in 0..20 {
            let mut samples = frame(k as f64 * 0.02, &mut rng);
            samples.sort_by(|a, b| a.0.total_cmp(&b.0));
            let cand = hull_per_interval(&samples, 20);
            let cold = fit_sorted_candidates_above(&cand, 20, None, DEFAULT_MAX_SOLVES).unwrap();
            let hot =
                fit_sorted_candidates_above(&cand, 20, warm.as_ref(), DEFAULT_MAX_SOLVES).unwrap();
            assert!(all_below(&hot, &samples) && all_below(&cold, &samples));
            cold_total += cold.solves;
            warm_total += hot.solves;
            warm = Some(hot.warm);
        }
        assert!(
            warm_total < cold_total,
            "warm {warm_total} cold {cold_total}"
        );
    }

    #[test]
    fn rejects_bad_samples() {
        assert!(fit_curve_above(&[], 5).is_err());
        assert!(fit_curve_above(&[(1.0, f64::NAN)], 5).is_err());
        assert!(fit_curve_above(&[(1.0, 1.0)], 1).is_err());
    }
}
