//! Section 4: the broken-line surrogate, Heuristic(σ, b).
//!
//! Given uniform data `c_i` at the Greville abscissae `i`, find coefficients `b`
//! whose Lemma 4.1 breakpoints equal the data, `ℓ = (I + diag(σ) D / 6) b = c`
//! (eq. 4), alternating between solving for `b` and resetting the signs
//! `σ_i = [Δ_i b < 0]` until they agree. Free breakpoints (no data) get the row
//! `Δ_i b / 6 = 0` instead (Figure 4).

use super::error::FitError;
use super::lower_bound::broken_line_lower_bound;
use shroud_geometry::math::BandedMatrix;
use shroud_geometry::spline::{second_difference, UniformCubicCurve};

/// Sign iterations allowed before the fallback shift (the paper never saw more
/// than three).
pub const MAX_SIGN_ITERATIONS: usize = 12;

/// Result of a Section 4 fit.
#[derive(Debug, Clone, PartialEq)]
pub struct BrokenLineFit {
    pub curve: UniformCubicCurve,
    /// Banded solves (the paper's "iterations").
    pub solves: usize,
    /// Final `σ_i`: true where `Δ_i b < 0`.
    pub signs: Vec<bool>,
    /// Uniform lift applied because the signs did not settle (0 when they did).
    pub fallback_lift: f64,
}

/// Heuristic(σ, b): a spline whose Lemma 4.1 broken line lies on or above `values`
/// at every non-free breakpoint, hence above their piecewise-linear interpolant.
/// `warm_signs` replaces the paper's initialisation `σ = sgn(ℓ)` (warm start).
pub fn fit_broken_line_above(
    values: &[f64],
    free: &[bool],
    warm_signs: Option<&[bool]>,
) -> Result<BrokenLineFit, FitError> {
    let n = values.len();
    if n < 2 {
        return Err(FitError::CurveTooShort(n));
    }
    if let Some(index) = values.iter().position(|v| !v.is_finite()) {
        return Err(FitError::NonFiniteSample { index });
    }
    if free.iter().all(|&f| f) {
        return Err(FitError::NoSamples);
    }
    let mut signs: Vec<bool> = match warm_signs {
        Some(s) if s.len() == n => s.to_vec(),
        _ => (0..n).map(|i| second_difference(values, i) < 0.0).collect(),
    };
    let mut matrix = BandedMatrix::<1, 1>::zeros(n);
    let mut b = vec![0.0; n];
    let mut solves = 0;
    let mut settled = false;
    while solves < MAX_SIGN_ITERATIONS {
        solve_rows(&mut matrix, values, free, &signs, &mut b)?;
        solves += 1;
        let mut changed = false;
        for (i, s) in signs.iter_mut().enumerate() {
            let now = second_difference(&b, i) < 0.0;
            changed |= now != *s;
            *s = now;
        }
        if !changed {
            settled = true;
            break;
        }
    }
    let fallback_lift = lift_to_cover(&mut b, values, free);
    debug_assert!(settled || solves == MAX_SIGN_ITERATIONS);
    Ok(BrokenLineFit {
        curve: UniformCubicCurve { coefficients: b },
        solves,
        signs,
        fallback_lift,
    })
}

fn solve_rows(
    matrix: &mut BandedMatrix<1, 1>,
    values: &[f64],
    free: &[bool],
    signs: &[bool],
    b: &mut [f64],
) -> Result<(), FitError> {
    let n = values.len();
    matrix.clear();
    for i in 0..n {
        let (prev, next) = (i.saturating_sub(1), (i + 1).min(n - 1));
        // Row i: free => Δ_i b / 6 = 0; data => b_i + σ_i Δ_i b / 6 = c_i.
        let weight = if free[i] || signs[i] { 1.0 / 6.0 } else { 0.0 };
        if !free[i] {
            matrix.add(i, i, 1.0);
        }
        if weight != 0.0 {
            matrix.add(i, prev, weight);
            matrix.add(i, i, -2.0 * weight);
            matrix.add(i, next, weight);
        }
        b[i] = if free[i] { 0.0 } else { values[i] };
    }
    matrix.solve_in_place(b).map_err(|_| FitError::NoSamples)
}

/// If the signs never settled, some breakpoint may sit below its datum; a uniform
/// lift (which leaves every `Δ_i b` unchanged) restores `ℓ >= c`. Returns the lift.
fn lift_to_cover(b: &mut [f64], values: &[f64], free: &[bool]) -> f64 {
    let ell = broken_line_lower_bound(b);
    let deficit = (0..b.len())
        .filter(|&i| !free[i])
        .map(|i| values[i] - ell[i])
        .fold(0.0f64, f64::max);
    if deficit > 0.0 {
        let lift = deficit * (1.0 + 1e-12) + f64::MIN_POSITIVE;
        b.iter_mut().for_each(|x| *x += lift);
        lift
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn covers(fit: &BrokenLineFit, values: &[f64], free: &[bool]) -> bool {
        let ell = broken_line_lower_bound(&fit.curve.coefficients);
        let n = values.len();
        // Spline above the data's broken line, sampled densely.
        (0..n).all(|i| free[i] || ell[i] >= values[i] - 1e-9)
            && (0..=(n - 1) * 20).all(|k| {
                let s = k as f64 / 20.0;
                let h = (s.floor() as usize).min(n - 2);
                let u = s - h as f64;
                free[h]
                    || free[h + 1]
                    || fit.curve.eval(s) >= (1.0 - u) * values[h] + u * values[h + 1] - 1e-9
            })
    }

    #[test]
    fn covers_random_broken_lines_in_few_iterations() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let mut histogram = [0usize; MAX_SIGN_ITERATIONS + 1];
        for _ in 0..500 {
            let n = rng.random_range(2..40);
            let values: Vec<f64> = (0..n).map(|_| rng.random_range(-3.0..3.0)).collect();
            let free = vec![false; n];
            let fit = fit_broken_line_above(&values, &free, None).unwrap();
            assert!(covers(&fit, &values, &free));
            histogram[fit.solves] += 1;
        }
        // The paper: "a single large spike at 2 with negligible counts at 1 and 3".
        let at_most_three: usize = histogram[..=3].iter().sum();
        assert!(at_most_three >= 450, "{histogram:?}");
    }

    #[test]
    fn free_breakpoints_get_zero_second_difference() {
        let values = [0.0, 1.0, 0.0, 0.0, 2.0, 0.5];
        let free = [false, false, true, true, false, false];
        let fit = fit_broken_line_above(&values, &free, None).unwrap();
        for i in [2, 3] {
            assert!(second_difference(&fit.curve.coefficients, i).abs() < 1e-9);
        }
        assert!(covers(&fit, &values, &free));
    }

    #[test]
    fn warm_signs_reduce_solves() {
        let values: Vec<f64> = (0..30).map(|i| ((i as f64) * 0.7).sin() * 3.0).collect();
        let free = vec![false; 30];
        let cold = fit_broken_line_above(&values, &free, None).unwrap();
        let warm = fit_broken_line_above(&values, &free, Some(&cold.signs)).unwrap();
        assert_eq!(warm.solves, 1);
        assert_eq!(warm.curve, cold.curve);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(fit_broken_line_above(&[1.0], &[false], None).is_err());
        assert!(fit_broken_line_above(&[1.0, f64::NAN], &[false, false], None).is_err());
        assert!(fit_broken_line_above(&[1.0, 2.0], &[true, true], None).is_err());
    }
}
