//! Each curve heuristic and lower bound against brute force: Section 4
//! (`fit_broken_line_above`, Lemma 4.1), Section 5 (`fit_curve_above`, Lemma 5.1,
//! the per-interval upper hull), the Section 3 baseline, and the iteration counts
//! the paper reports (Section 4: "never more than three"; Figure 9: "almost all
//! cases less or equal to 10 ... occasionally up to 20").

mod common;

use common::config::config;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use shroud_geometry::spline::{knot_interval, UniformCubicCurve};
use shroud_surrogate::{
    broken_line_lower_bound, fit_broken_line_above, fit_curve_above, fit_curve_by_trial_and_error,
    fit_sorted_candidates_above, hull_per_interval, negative_differences, scattered_lower_bound,
    upper_hull, DEFAULT_MAX_SOLVES,
};

/// Dense samples per knot interval.
const DENSE: usize = 64;
/// f64 evaluation rounding allowed by the exact-in-real-arithmetic bounds,
/// relative to the largest magnitude involved.
const ROUNDING: f64 = 1e-12;

/// Parameters `0, 1/DENSE, ..., n-1`, knots included exactly.
fn dense(n: usize) -> impl Iterator<Item = f64> {
    (0..=(n - 1) * DENSE).map(|i| i as f64 / DENSE as f64)
}

fn magnitude(values: &[f64]) -> f64 {
    values.iter().fold(1.0f64, |m, v| m.max(v.abs()))
}

/// Shapes of data that stress the heuristics: noise, smooth waves, steps (Gibbs),
/// isolated spikes, and huge magnitudes.
fn shaped_value(shape: u8, x: f64, rng: &mut Pcg64) -> f64 {
    match shape % 5 {
        0 => rng.random_range(-3.0..3.0),
        1 => (x * 1.3).sin() * 2.0 - rng.random_range(0.0..0.5),
        2 => (if x > 7.3 { 4.0 } else { 0.0 }) - rng.random_range(0.0..0.1),
        3 => (if rng.random_bool(0.05) { 50.0 } else { 0.0 }) + rng.random_range(0.0..0.1),
        _ => 1e7 * (x * 0.4).cos() + rng.random_range(0.0..1e3),
    }
}

fn random_samples(rng: &mut Pcg64, n: usize, count: usize, shape: u8) -> Vec<(f64, f64)> {
    (0..count)
        .map(|_| {
            // A fifth of the samples sit exactly on knots or at the domain ends.
            let s = if rng.random_bool(0.2) {
                rng.random_range(0..n) as f64
            } else {
                rng.random_range(0.0..=(n - 1) as f64)
            };
            (s, shaped_value(shape, s, rng))
        })
        .collect()
}

fn random_coefficients(rng: &mut Pcg64, n: usize, shape: u8) -> Vec<f64> {
    (0..n).map(|i| shaped_value(shape, i as f64, rng)).collect()
}

/// Panics unless the curve lies above the piecewise-linear interpolant of the
/// non-free data, densely sampled, and on or above each non-free datum.
fn assert_above_broken_line(curve: &UniformCubicCurve, values: &[f64], free: &[bool]) {
    let n = values.len();
    let tolerance = ROUNDING * magnitude(&curve.coefficients).max(magnitude(values));
    for s in dense(n) {
        let (h, u) = knot_interval(s, n);
        if free[h] || free[h + 1] {
            continue;
        }
        let line = (1.0 - u) * values[h] + u * values[h + 1];
        assert!(
            curve.eval(s) >= line - tolerance,
            "below the broken line at s = {s}: {} < {line}",
            curve.eval(s)
        );
    }
}

proptest! {
    #![proptest_config(config(500))]

    /// Section 4: Heuristic(σ, b) lies above the broken line of its data.
    #[test]
    fn broken_line_fit_lies_above_its_data(
        n in 2..60usize,
        shape in 0..5u8,
        free_fraction in prop::sample::select(vec![0.0, 0.2, 0.6]),
        warm in any::<bool>(),
        seed in any::<u64>(),
    ) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let values = random_coefficients(&mut rng, n, shape);
        let mut free: Vec<bool> = (0..n).map(|_| rng.random_bool(free_fraction)).collect();
        free[rng.random_range(0..n)] = false;
        let warm_signs: Option<Vec<bool>> = warm.then(|| (0..n).map(|_| rng.random_bool(0.5)).collect());
        let fit = fit_broken_line_above(&values, &free, warm_signs.as_deref()).expect("valid data");
        assert_above_broken_line(&fit.curve, &values, &free);
    }

    /// Section 5: Heuristic(σ, b, λ) lies above every sample, exactly in f64.
    #[test]
    fn scattered_fit_lies_above_every_sample(
        n in 2..40usize,
        count in 1..400usize,
        shape in 0..5u8,
        seed in any::<u64>(),
    ) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let samples = random_samples(&mut rng, n, count, shape);
        let fit = fit_curve_above(&samples, n).expect("valid samples");
        for &(s, y) in &samples {
            prop_assert!(fit.curve.eval(s) >= y, "sample ({}, {}) above the curve ({})", s, y, fit.curve.eval(s));
        }
    }

    /// The claim behind the candidate reduction: a fit constrained only at the
    /// upper-hull vertices of each knot interval covers every sample.
    #[test]
    fn constraining_the_per_interval_upper_hull_covers_every_sample(
        n in 2..30usize,
        count in 1..400usize,
        shape in 0..5u8,
        seed in any::<u64>(),
    ) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let mut samples = random_samples(&mut rng, n, count, shape);
        samples.sort_by(|a, b| a.0.total_cmp(&b.0));
        let hull = hull_per_interval(&samples, n);
        prop_assert!(hull.len() <= samples.len());
        let fit = fit_sorted_candidates_above(&hull, n, None, DEFAULT_MAX_SOLVES).expect("valid hull");
        for &(s, y) in &samples {
            prop_assert!(fit.curve.eval(s) >= y, "sample ({}, {}) above the curve ({})", s, y, fit.curve.eval(s));
        }
    }

    /// Section 3 baseline: when it says it converged, no sample is above the curve
    /// (beyond its documented 1e-12 acceptance).
    #[test]
    fn trial_and_error_is_above_every_sample_when_it_converges(
        n in 2..30usize,
        count in 1..300usize,
        shape in 0..4u8,
        seed in any::<u64>(),
    ) {
        let mut rng = Pcg64::seed_from_u64(seed);
        let samples = random_samples(&mut rng, n, count, shape);
        let fit = fit_curve_by_trial_and_error(&samples, n, 200).expect("valid samples");
        prop_assert!(fit.solves >= 1);
        if fit.converged {
            for &(s, y) in &samples {
                prop_assert!(fit.curve.eval(s) >= y - 1e-12, "sample ({}, {}) above ({})", s, y, fit.curve.eval(s));
            }
        }
    }
}

/// Lemma 4.1: the broken line through `(i, ℓ_i)` is below the spline everywhere.
#[test]
fn lemma_4_1_bound_is_below_the_spline() {
    let mut rng = Pcg64::seed_from_u64(41);
    for trial in 0..500 {
        let n = rng.random_range(2..40);
        let b = random_coefficients(&mut rng, n, trial as u8);
        let ell = broken_line_lower_bound(&b);
        let curve = UniformCubicCurve::new(b.clone()).expect("n >= 2");
        let tolerance = ROUNDING * magnitude(&b);
        for s in dense(n) {
            let (h, u) = knot_interval(s, n);
            let line = (1.0 - u) * ell[h] + u * ell[h + 1];
            assert!(
                curve.eval(s) >= line - tolerance,
                "trial {trial}: s = {s}, f = {}, ℓ = {line}",
                curve.eval(s)
            );
        }
    }
}

/// Lemma 5.1 bound at `s` of coefficients `b`.
fn lemma_5_1(b: &[f64], s: f64) -> f64 {
    scattered_lower_bound(b, &negative_differences(b), s)
}

/// Lemma 5.1: the bound (5) is below the spline at every parameter, and it is
/// exact at the knots where the second difference is non-positive.
#[test]
fn lemma_5_1_bound_is_below_the_spline() {
    let mut rng = Pcg64::seed_from_u64(51);
    for trial in 0..500 {
        let n = rng.random_range(2..40);
        let b = random_coefficients(&mut rng, n, trial as u8);
        let curve = UniformCubicCurve::new(b.clone()).expect("n >= 2");
        let tolerance = ROUNDING * magnitude(&b);
        let random = (0..200)
            .map(|_| rng.random_range(0.0..=(n - 1) as f64))
            .collect::<Vec<_>>();
        for s in dense(n).chain(random) {
            let bound = lemma_5_1(&b, s);
            assert!(
                curve.eval(s) >= bound - tolerance,
                "trial {trial}: s = {s}, f = {}, L = {bound}",
                curve.eval(s)
            );
        }
        // At knot i, f = b_i + Δ_i b / 6: the bound is tight where Δ_i b <= 0.
        for (i, neg) in negative_differences(&b).iter().enumerate() {
            let s = i as f64;
            if *neg < 0.0 {
                let gap = curve.eval(s) - lemma_5_1(&b, s);
                assert!(
                    gap.abs() <= tolerance,
                    "trial {trial}: not tight at knot {i}: {gap}"
                );
            }
        }
    }
}

/// The Lemma 5.1 bound is concave on each knot interval (why only upper-hull
/// vertices can bind): every second difference of a fine sampling is <= 0.
#[test]
fn lemma_5_1_bound_is_concave_on_each_interval() {
    let mut rng = Pcg64::seed_from_u64(52);
    for trial in 0..500 {
        let n = rng.random_range(2..30);
        let b = random_coefficients(&mut rng, n, trial as u8);
        let tolerance = 4.0 * ROUNDING * magnitude(&b);
        for h in 0..n - 1 {
            let at =
                |i: usize| lemma_5_1(&b, (h as f64 + i as f64 / DENSE as f64).min((n - 1) as f64));
            for i in 1..DENSE {
                let second = at(i - 1) - 2.0 * at(i) + at(i + 1);
                assert!(
                    second <= tolerance,
                    "trial {trial}: interval {h}, step {i}: second difference {second}"
                );
            }
        }
    }
}

/// Directly: whatever the coefficients, if the bound is above every upper-hull
/// vertex of an interval's samples, it is above every sample of the interval.
#[test]
fn a_bound_above_the_hull_vertices_is_above_every_sample() {
    let mut rng = Pcg64::seed_from_u64(53);
    for trial in 0..500 {
        let n = rng.random_range(2..20);
        let b = random_coefficients(&mut rng, n, trial as u8);
        let h = rng.random_range(0..n - 1) as f64;
        let mut samples: Vec<(f64, f64)> = (0..rng.random_range(1..60))
            .map(|_| {
                let s = h + if rng.random_bool(0.1) {
                    0.0
                } else {
                    rng.random_range(0.0..1.0)
                };
                (s, rng.random_range(-10.0..10.0) * magnitude(&b))
            })
            .collect();
        samples.sort_by(|a, c| a.0.total_cmp(&c.0));
        let hull = upper_hull(&samples);
        // The smallest clearance over the vertices; every sample must have at least it.
        let clearance = hull
            .iter()
            .map(|&(s, y)| lemma_5_1(&b, s) - y)
            .fold(f64::INFINITY, f64::min);
        let tolerance = 1e-9 * magnitude(&b);
        for &(s, y) in &samples {
            let own = lemma_5_1(&b, s) - y;
            assert!(
                own >= clearance - tolerance,
                "trial {trial}: sample ({s}, {y}) clearance {own} < {clearance}"
            );
        }
    }
}

/// Section 4: "we have never observed more than three iterations".
#[test]
fn broken_line_fits_mostly_take_at_most_three_solves() {
    let mut rng = Pcg64::seed_from_u64(4);
    let mut histogram = vec![0usize; 16];
    for trial in 0..1000 {
        let n = rng.random_range(2..60);
        let values = random_coefficients(&mut rng, n, trial as u8);
        let fit = fit_broken_line_above(&values, &vec![false; n], None).expect("valid data");
        histogram[fit.solves.min(15)] += 1;
    }
    eprintln!("Section 4 solves histogram (index = solves): {histogram:?}");
    let at_most_three: usize = histogram[..=3].iter().sum();
    assert!(at_most_three >= 950, "{histogram:?}");
}

/// Solves-per-fit histogram of `fit_curve_above` over 1000 random curves whose
/// data shape is drawn from `shapes`.
fn scattered_histogram(seed: u64, shapes: &[u8]) -> Vec<usize> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut histogram = vec![0usize; DEFAULT_MAX_SOLVES + 1];
    for trial in 0..1000 {
        let n = rng.random_range(2..40);
        let count = rng.random_range(1..800);
        let samples = random_samples(&mut rng, n, count, shapes[trial % shapes.len()]);
        let fit = fit_curve_above(&samples, n).expect("valid samples");
        histogram[fit.solves.min(DEFAULT_MAX_SOLVES)] += 1;
    }
    histogram
}

/// Figure 9: Heuristic(σ, b, λ) takes at most 20 solves in almost all cases, on
/// noise, waves, steps and spikes.
#[test]
fn scattered_fits_mostly_take_at_most_twenty_solves() {
    let histogram = scattered_histogram(5, &[0, 1, 2, 3]);
    eprintln!("Section 5 solves histogram (index = solves): {histogram:?}");
    let at_most_twenty: usize = histogram[..=20].iter().sum();
    assert!(at_most_twenty >= 900, "{histogram:?}");
}

/// Data within 1e-4 (relative) of a smooth curve is the slow case: many samples
/// nearly bind, and each reselection fixes one. The solve budget may run out
/// (the local raise then finishes the fit safely) but only rarely.
#[test]
fn near_smooth_data_rarely_exhausts_the_solve_budget() {
    let histogram = scattered_histogram(6, &[4]);
    eprintln!("Section 5 solves histogram on near-smooth data: {histogram:?}");
    assert!(histogram[DEFAULT_MAX_SOLVES] <= 20, "{histogram:?}");
}

/// The same counts inside a surface fit of the paper's scene (Figure 9 is for
/// N = 30K, 20 x 20 control points).
#[test]
fn surface_fit_iteration_counts_match_figure_9() {
    use shroud_surrogate::{fit_surrogate, FitOptions};
    let points = shroud_sim::MovingSpheres {
        points: 30_000,
        ..Default::default()
    }
    .generate(0.3)
    .expect("scene");
    let surrogate = fit_surrogate(&points, &FitOptions::default()).expect("spheres fit");
    let (curves, columns) = (
        &surrogate.stats.curve_solves,
        &surrogate.stats.column_solves,
    );
    eprintln!(
        "curve solves {:?} mean {:.2}; column solves {:?} mean {:.2}",
        curves.counts,
        curves.mean(),
        columns.counts,
        columns.mean()
    );
    let fraction = |h: &shroud_surrogate::Histogram, limit: usize| {
        h.counts.iter().take(limit + 1).sum::<u64>() as f64 / h.total().max(1) as f64
    };
    assert!(curves.total() > 0 && columns.total() > 0);
    assert!(
        fraction(curves, 20) >= 0.9,
        "curve solves {:?}",
        curves.counts
    );
    assert!(
        fraction(columns, 3) >= 0.9,
        "column solves {:?}",
        columns.counts
    );
}
