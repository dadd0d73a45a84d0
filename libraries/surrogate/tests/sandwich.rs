//! Sandwich surrogates never cross inside the kept region: sampled densely over
//! every kept triangle `upper - lower >= 0` (up to evaluation rounding), and on
//! every kept cell the 16 coefficient differences are non-negative, which makes
//! the difference non-negative there by the convex hull property (Section 6).

mod common;

use common::brute_force::assert_certified;
use common::clouds::{cloud, CloudKind};
use common::config::config;
use common::directions::{direction, DirectionKind};
use proptest::prelude::*;
use proptest::sample::select;
use shroud_geometry::spline::UniformCubicSurface;
use shroud_surrogate::trim::{BOTTOM, LEFT, RIGHT, TOP};
use shroud_surrogate::{fit_surrogate, FitError, FitOptions, Sides, Surrogate, Tightness};

/// Samples per triangle edge: `(K + 1)(K + 2) / 2` barycentric points each.
const K: usize = 10;
/// Evaluation rounding allowed, relative to the largest coefficient.
const ROUNDING: f64 = 1e-12;

/// The corners of each triangle of the unit cell, the centre last.
fn triangle(bit: u8) -> [(f64, f64); 3] {
    let c = (0.5, 0.5);
    match bit {
        BOTTOM => [(0.0, 0.0), (1.0, 0.0), c],
        RIGHT => [(1.0, 0.0), (1.0, 1.0), c],
        TOP => [(1.0, 1.0), (0.0, 1.0), c],
        _ => [(0.0, 1.0), (0.0, 0.0), c],
    }
}

/// Barycentric grid points of a triangle, corners and edges included.
fn samples(corners: [(f64, f64); 3]) -> impl Iterator<Item = (f64, f64)> {
    (0..=K).flat_map(move |i| {
        (0..=K - i).map(move |j| {
            let (a, b) = (i as f64 / K as f64, j as f64 / K as f64);
            let c = 1.0 - a - b;
            (
                a * corners[0].0 + b * corners[1].0 + c * corners[2].0,
                a * corners[0].1 + b * corners[1].1 + c * corners[2].1,
            )
        })
    })
}

fn largest_coefficient(a: &UniformCubicSurface, b: &UniformCubicSurface) -> f64 {
    a.coefficients
        .iter()
        .chain(&b.coefficients)
        .fold(1.0f64, |m, c| m.max(c.abs()))
}

/// Panics where the two surfaces of a sandwich cross inside the kept region.
fn assert_never_cross(surrogate: &Surrogate) {
    let (Some(up), Some(low)) = (&surrogate.upper, &surrogate.lower) else {
        panic!("a sandwich needs both surfaces")
    };
    let (up, low) = (&up.surface, &low.surface);
    let tolerance = ROUNDING * largest_coefficient(up, low);
    let trim = &surrogate.trim;
    for g in 0..trim.cells_t {
        for h in 0..trim.cells_s {
            if !trim.cell_kept(h, g) {
                continue;
            }
            let (cu, cl) = (up.cell_coefficients(h, g), low.cell_coefficients(h, g));
            for (r, (ru, rl)) in cu.iter().zip(&cl).enumerate() {
                for (q, (a, b)) in ru.iter().zip(rl).enumerate() {
                    assert!(
                        a - b >= 0.0,
                        "cell ({h}, {g}) coefficient [{r}][{q}]: upper {a} < lower {b}"
                    );
                }
            }
            for bit in [BOTTOM, RIGHT, TOP, LEFT]
                .into_iter()
                .filter(|&b| trim.cell_bits(h, g) & b != 0)
            {
                for (u, v) in samples(triangle(bit)) {
                    let (s, t) = (h as f64 + u, g as f64 + v);
                    let gap = up.eval(s, t) - low.eval(s, t);
                    assert!(
                        gap >= -tolerance,
                        "surfaces cross at ({s}, {t}) in triangle {bit} of ({h}, {g}): {gap}"
                    );
                }
            }
        }
    }
}

fn sandwich_options() -> impl Strategy<Value = FitOptions> {
    (
        2..=30usize,
        2..=20usize,
        any::<bool>(),
        any::<bool>(),
        select(vec![
            Tightness::Plain,
            Tightness::Lowered,
            Tightness::Optimal,
        ]),
        1..=4usize,
    )
        .prop_map(
            |(cols, rows, symmetrize, trim, tightness, sub_cells)| FitOptions {
                cols,
                rows,
                sides: Sides::Sandwich,
                symmetrize,
                trim,
                tightness,
                sub_cells,
                ..FitOptions::default()
            },
        )
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn sandwich_surfaces_never_cross_in_the_kept_region(
        kind in select(CloudKind::ALL.to_vec()),
        count in 3..=1000usize,
        seed in any::<u64>(),
        random_direction in any::<bool>(),
        options in sandwich_options(),
    ) {
        let cloud = cloud(kind, count, seed);
        let kind = if random_direction { DirectionKind::Random } else { DirectionKind::Axis };
        let options = FitOptions { direction: direction(kind, cloud.normal, seed), ..options };
        match fit_surrogate(&cloud.points, &options) {
            Ok(surrogate) => {
                assert_certified(&cloud.points, &surrogate, Sides::Sandwich);
                assert_never_cross(&surrogate);
            }
            Err(FitError::Degenerate { .. } | FitError::Collinear { .. }) => {}
            Err(e) => prop_assert!(false, "unexpected error {}", e),
        }
    }
}

/// A perfectly flat cloud: both surfaces are pushed onto the same plane, where the
/// tightened upper surface dips below the tightened lower one unless un-crossed.
#[test]
fn a_flat_cloud_gives_touching_but_uncrossed_surfaces() {
    let points: Vec<[f32; 3]> = (0..2000)
        .map(|i| [(i % 50) as f32 * 0.02, (i / 50) as f32 * 0.025, 0.5])
        .collect();
    for tightness in [Tightness::Plain, Tightness::Lowered, Tightness::Optimal] {
        let options = FitOptions {
            cols: 12,
            rows: 9,
            sides: Sides::Sandwich,
            tightness,
            ..FitOptions::default()
        };
        let surrogate = fit_surrogate(&points, &options).expect("a flat patch fits");
        assert_certified(&points, &surrogate, Sides::Sandwich);
        assert_never_cross(&surrogate);
    }
}

/// The paper's scene (Figure 12 shows such two-sided cross sections).
#[test]
fn moving_spheres_sandwich_never_crosses() {
    let scene = shroud_sim::MovingSpheres {
        points: 20_000,
        ..Default::default()
    };
    for time in [0.0, 1.7, 4.1] {
        let points = scene.generate(time).expect("valid scene");
        for symmetrize in [false, true] {
            let options = FitOptions {
                sides: Sides::Sandwich,
                symmetrize,
                ..FitOptions::default()
            };
            let surrogate = fit_surrogate(&points, &options).expect("spheres fit");
            assert_certified(&points, &surrogate, Sides::Sandwich);
            assert_never_cross(&surrogate);
        }
    }
}
