//! The interior-point method against clarabel, on fitted, degenerate, random and
//! oversized LPs.

use super::state::base_volume;
use super::*;
use crate::tight::fixture::Fixture;
use crate::tight::lp_reference::solve_with_clarabel;
use crate::{Candidate, TrimMask};
use shroud_geometry::spline::UniformCubicSurface;

fn assert_matches_clarabel(lp: &SplineLp, start: &[f64]) {
    let ipm = solve(lp, start, &IpmSettings::default()).unwrap();
    let reference = lp.objective(&solve_with_clarabel(lp).unwrap());
    let relative = (ipm.objective - reference).abs() / reference.abs().max(1e-300);
    assert!(
        relative < 1e-6,
        "ipm {} vs clarabel {reference} ({} iterations)",
        ipm.objective,
        ipm.iterations
    );
    assert!(lp.max_violation(&ipm.x) <= 0.0);
}

#[test]
fn matches_clarabel_on_a_fitted_candidate_lp() {
    for fixture in [
        Fixture::spheres(20_000, 12, 0.3),
        Fixture::terrain(20_000, 10),
    ] {
        let surface = &fixture.plain.upper.as_ref().unwrap().surface;
        let lp = SplineLp::new(surface, &fixture.plain.trim, &fixture.candidates()).unwrap();
        assert_matches_clarabel(&lp, &lp.gather(&surface.coefficients));
    }
}

#[test]
fn solves_flat_degenerate_data() {
    // Every candidate at one height, on every quarter knot line: the optimum is
    // the flat surface, with every row at a knot crossing active at once and the
    // rest active or nearly so.
    let (cols, rows) = (5, 5);
    let candidates: Vec<Candidate> = (0..17 * 17)
        .map(|i| Candidate {
            s: (i % 17) as f64 * 0.25,
            t: (i / 17) as f64 * 0.25,
            height: 1.0,
        })
        .collect();
    let surface = UniformCubicSurface::constant(cols, rows, 2.0).unwrap();
    let lp = SplineLp::new(&surface, &TrimMask::full(cols - 1, rows - 1), &candidates).unwrap();
    let solution = solve(
        &lp,
        &lp.gather(&surface.coefficients),
        &IpmSettings::default(),
    )
    .unwrap();
    assert!(
        (solution.objective - 16.0).abs() < 1e-8,
        "{}",
        solution.objective
    );
    assert_matches_clarabel(&lp, &lp.gather(&surface.coefficients));
}

#[test]
fn refuses_a_band_too_large_to_factor() {
    // One candidate per cell of a 150 x 150 grid: 22500 unknowns, half-bandwidth
    // 453, about 2.3e9 multiply-adds per factorisation.
    let (cols, rows) = (150, 150);
    let candidates: Vec<Candidate> = (0..(cols - 1) * (rows - 1))
        .map(|i| Candidate {
            s: (i % (cols - 1)) as f64 + 0.5,
            t: (i / (cols - 1)) as f64 + 0.5,
            height: 1.0,
        })
        .collect();
    let surface = UniformCubicSurface::constant(cols, rows, 2.0).unwrap();
    let lp = SplineLp::new(&surface, &TrimMask::full(cols - 1, rows - 1), &candidates).unwrap();
    let error = solve(
        &lp,
        &lp.gather(&surface.coefficients),
        &IpmSettings::default(),
    )
    .unwrap_err();
    assert!(matches!(error, LpError::TooLarge { .. }), "{error}");
}

#[test]
fn matches_clarabel_from_an_infeasible_start_on_a_wide_grid() {
    // cols > rows exercises the column-major band order; the zero start is
    // below every candidate.
    let (cols, rows) = (11, 5);
    let candidates: Vec<Candidate> = (0..900)
        .map(|i| {
            let (s, t) = (
                (i * 37 % 997) as f64 * 0.01,
                (i * 53 % 401) as f64 * 0.00997,
            );
            Candidate {
                s,
                t,
                height: (s * 1.3).sin() + (t * 2.1).cos() * 0.5 + ((i * 7) % 5) as f64 * 0.05,
            }
        })
        .collect();
    let surface = UniformCubicSurface::constant(cols, rows, 0.0).unwrap();
    let lp = SplineLp::new(&surface, &TrimMask::full(cols - 1, rows - 1), &candidates).unwrap();
    assert!(lp.bandwidth <= 3 * rows + 3);
    assert_matches_clarabel(&lp, &lp.gather(&surface.coefficients));
}

/// A random LP in the shape the fitter produces, but with sparse, clustered and
/// offset data: few candidates per cell, trims from the candidates themselves,
/// heights far from the origin, starts far from feasible.
fn random_lp(seed: u64) -> (SplineLp, Vec<f64>) {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let (cols, rows) = (rng.random_range(2..14), rng.random_range(2..14));
    let (scale, offset) = (
        [1e-3, 1.0, 1e3][rng.random_range(0..3)],
        [0.0, 100.0, -1e4][rng.random_range(0..3)],
    );
    let quantise = rng.random_bool(0.3);
    let mut trim = TrimMask::empty(cols - 1, rows - 1);
    let candidates: Vec<Candidate> = (0..rng.random_range(1..300))
        .map(|_| {
            let mut s = rng.random_range(0.0..(cols - 1) as f64);
            let mut t = rng.random_range(0.0..(rows - 1) as f64);
            if quantise {
                (s, t) = ((s * 4.0).round() / 4.0, (t * 4.0).round() / 4.0);
            }
            trim.mark(s, t);
            let step = if rng.random_bool(0.1) { 2.0 } else { 0.0 };
            Candidate {
                s,
                t,
                height: offset + scale * ((s * 0.7).sin() + (t * 1.3).cos() + step),
            }
        })
        .collect();
    let start = offset + scale * rng.random_range(-5.0..5.0);
    let surface = UniformCubicSurface::constant(cols, rows, start).unwrap();
    let lp = SplineLp::new(&surface, &trim, &candidates).unwrap();
    let x = lp.gather(&surface.coefficients);
    (lp, x)
}

#[test]
fn is_feasible_and_no_worse_than_clarabel_on_random_sparse_lps() {
    // One-sided: on nearly unbounded instances clarabel stops short of the
    // optimum (its solution is then the worse one, sometimes infeasible).
    for seed in 0..80 {
        let (lp, start) = random_lp(seed);
        let ipm = solve(&lp, &start, &IpmSettings::default()).unwrap();
        assert!(
            lp.max_violation(&ipm.x) <= 0.0,
            "seed {seed}: a row is violated"
        );
        assert!(
            ipm.x.iter().zip(&lp.floors).all(|(x, f)| x >= f),
            "seed {seed}: below a floor"
        );
        let reference = lp.objective(&solve_with_clarabel(&lp).unwrap());
        let volume = (reference - base_volume(&lp))
            .abs()
            .max(1e-9 * reference.abs());
        assert!(
            ipm.objective <= reference + 1e-6 * volume,
            "seed {seed}: ipm {} vs clarabel {reference}",
            ipm.objective
        );
    }
}
