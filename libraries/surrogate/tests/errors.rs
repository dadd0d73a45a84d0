//! Bad input gives the `FitError` that names the problem, and never a panic.

mod common;

use common::brute_force::assert_certified;
use common::config::config;
use proptest::prelude::*;
use shroud_geometry::math::FrameError;
use shroud_geometry::CloudError;
use shroud_surrogate::{fit_surrogate, FitError, FitOptions, Surrogate, SurrogateFitter, MAX_GRID};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// A small valid cloud: a wavy 10 x 10 patch.
fn patch() -> Vec<[f32; 3]> {
    (0..100)
        .map(|i| {
            [
                (i % 10) as f32 * 0.1,
                (i / 10) as f32 * 0.1,
                ((i % 7) as f32 * 0.9).sin(),
            ]
        })
        .collect()
}

/// Fits along the default direction (-z) on a 6 x 5 grid.
fn fit(points: &[[f32; 3]]) -> Result<Surrogate, FitError> {
    fit_along(points, FitOptions::default().direction)
}

fn fit_along(points: &[[f32; 3]], direction: [f64; 3]) -> Result<Surrogate, FitError> {
    let options = FitOptions {
        cols: 6,
        rows: 5,
        direction,
        ..FitOptions::default()
    };
    fit_surrogate(points, &options)
}

fn assert_degenerate(result: Result<Surrogate, FitError>, what: &str) {
    match result {
        Err(e @ (FitError::Degenerate { .. } | FitError::Collinear { .. })) => {
            assert!(e.to_string().contains("degenerate"), "{what}: message {e}")
        }
        Err(e) => panic!("{what}: expected a degenerate-cloud error, got {e}"),
        Ok(s) => panic!(
            "{what}: expected a degenerate-cloud error, got a surrogate over {:?}",
            s.domain
        ),
    }
}

#[test]
fn an_empty_cloud_is_rejected() {
    let err = fit(&[]).unwrap_err();
    assert_eq!(err, FitError::Cloud(CloudError::Empty));
    assert!(err.to_string().contains("empty"), "{err}");
}

#[test]
fn a_non_finite_coordinate_is_reported_with_its_index() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        for axis in 0..3 {
            for index in [0, 41, 99] {
                let mut points = patch();
                points[index][axis] = bad;
                let err = fit(&points).unwrap_err();
                assert!(
                    matches!(err, FitError::Cloud(CloudError::NonFinite { index: i, .. }) if i == index),
                    "{bad} in axis {axis} at {index}: {err:?}"
                );
                assert!(
                    err.to_string().contains(&format!("point {index} ")),
                    "message names the index: {err}"
                );
            }
        }
    }
}

/// The first bad point is named even when the cloud is split into parallel chunks
/// and a later chunk also holds one.
#[test]
fn the_first_non_finite_point_is_named_across_parallel_chunks() {
    let mut points: Vec<[f32; 3]> = (0..100_000)
        .map(|i| [(i % 300) as f32, (i / 300) as f32, ((i % 11) as f32).cos()])
        .collect();
    points[70_000][1] = f32::NAN;
    points[40_000][2] = f32::INFINITY;
    points[99_999][0] = f32::NAN;
    let err = fit(&points).unwrap_err();
    assert!(
        matches!(
            err,
            FitError::Cloud(CloudError::NonFinite { index: 40_000, .. })
        ),
        "{err:?}"
    );
}

#[test]
fn identical_points_are_degenerate() {
    assert_degenerate(fit(&[[1.5, -2.0, 3.0]; 50]), "50 copies of one point");
    assert_degenerate(fit(&[[0.0; 3]]), "a single point");
}

#[test]
fn collinear_points_along_a_frame_axis_are_degenerate() {
    // Seen along -z the frame axes are -y and x: this line spans only one of them.
    let line: Vec<[f32; 3]> = (0..40)
        .map(|i| [i as f32 * 0.25, 3.0, (i as f32).sin()])
        .collect();
    assert_degenerate(fit(&line), "a line along x seen along -z");
}

/// The error promises "all points identical or collinear"; a line skew to the
/// frame axes has a 2D bounding box but still no 2D footprint.
#[test]
fn collinear_points_along_a_skew_line_are_degenerate() {
    let line: Vec<[f32; 3]> = (0..40)
        .map(|i| [i as f32 * 0.25, i as f32 * 0.25, (i as f32).sin()])
        .collect();
    assert_degenerate(fit(&line), "the line x = y seen along -z");
}

#[test]
fn points_on_a_line_along_the_direction_are_degenerate() {
    let column: Vec<[f32; 3]> = (0..30).map(|i| [2.0, -1.0, i as f32 * 0.5]).collect();
    assert_degenerate(fit(&column), "a vertical column seen along -z");
    let column: Vec<[f32; 3]> = (0..30).map(|i| [i as f32 * 0.5, 7.0, 1.0]).collect();
    assert_degenerate(
        fit_along(&column, [1.0, 0.0, 0.0]),
        "a line along x seen along +x",
    );
}

/// Multiples of `(1, 2, 3)` are exact in f32, so this cloud projects to a single
/// point along `(1, 2, 3)`; only f64 rounding of the frame separates them.
#[test]
fn points_on_a_skew_line_through_the_origin_along_the_direction_are_degenerate() {
    let line: Vec<[f32; 3]> = (-5..=5)
        .map(|k| [k as f32, 2.0 * k as f32, 3.0 * k as f32])
        .collect();
    assert_degenerate(
        fit_along(&line, [1.0, 2.0, 3.0]),
        "multiples of (1, 2, 3) seen along (1, 2, 3)",
    );
}

#[test]
fn zero_and_non_finite_directions_are_rejected() {
    for d in [
        [0.0; 3],
        [f64::NAN, 0.0, -1.0],
        [0.0, f64::INFINITY, 0.0],
        [f64::NEG_INFINITY; 3],
    ] {
        let options = FitOptions {
            direction: d,
            ..FitOptions::default()
        };
        let err = SurrogateFitter::new(options.clone()).unwrap_err();
        assert!(
            matches!(err, FitError::Direction(FrameError::BadDirection(..))),
            "{d:?}: {err:?}"
        );
        assert!(err.to_string().contains("direction"), "{err}");
        // NaN != NaN, so the two errors are compared by their messages.
        assert_eq!(
            fit_surrogate(&patch(), &options).unwrap_err().to_string(),
            err.to_string()
        );
    }
}

/// The options say the direction "need not be unit length": a finite, non-zero
/// direction whose squared length overflows or underflows is still a direction.
#[test]
fn finite_non_zero_directions_of_any_magnitude_are_accepted() {
    let points = patch();
    let mut refused = Vec::new();
    for d in [
        [0.0, 0.0, -1e-200],
        [1e300, 1e300, -1e300],
        [0.0, -1e200, -1e200],
    ] {
        let options = FitOptions {
            cols: 6,
            rows: 5,
            direction: d,
            ..FitOptions::default()
        };
        match fit_surrogate(&points, &options) {
            Ok(s) => assert_certified(&points, &s, options.sides),
            Err(e) => refused.push(format!("{d:?}: {e:?}")),
        }
    }
    assert!(refused.is_empty(), "refused: {refused:#?}");
}

#[test]
fn grids_below_two_by_two_are_rejected() {
    for (cols, rows) in [(1, 5), (5, 1), (0, 0), (0, 7), (1, 1)] {
        let options = FitOptions {
            cols,
            rows,
            ..FitOptions::default()
        };
        let err = SurrogateFitter::new(options.clone()).unwrap_err();
        assert_eq!(err, FitError::GridTooSmall { cols, rows });
        assert!(
            err.to_string().contains(&format!("{cols} x {rows}")),
            "{err}"
        );
        assert_eq!(fit_surrogate(&patch(), &options).unwrap_err(), err);
    }
}

#[test]
fn grids_above_the_maximum_are_rejected_without_allocating() {
    for (cols, rows) in [
        (MAX_GRID + 1, 2),
        (2, MAX_GRID + 1),
        (usize::MAX, usize::MAX),
        (MAX_GRID + 1, 1),
    ] {
        let options = FitOptions {
            cols,
            rows,
            ..FitOptions::default()
        };
        let err = SurrogateFitter::new(options.clone()).unwrap_err();
        if cols >= 2 && rows >= 2 {
            assert_eq!(
                err,
                FitError::GridTooLarge {
                    cols,
                    rows,
                    max: MAX_GRID
                }
            );
            assert!(err.to_string().contains("too large"), "{err}");
        } else {
            assert!(
                matches!(
                    err,
                    FitError::GridTooSmall { .. } | FitError::GridTooLarge { .. }
                ),
                "{err:?}"
            );
        }
        assert_eq!(fit_surrogate(&patch(), &options).unwrap_err(), err);
    }
    let largest = FitOptions {
        cols: MAX_GRID,
        rows: 2,
        ..FitOptions::default()
    };
    assert!(SurrogateFitter::new(largest).is_ok());
}

/// `sub_cells` comes from the user like the grid: an absurd value must give an
/// error or a certified surrogate, not an arithmetic-overflow panic (it once
/// overflowed `cells * sub * sub` in the binning).
#[test]
fn an_absurd_sub_cell_count_does_not_panic() {
    let points = patch();
    let options = FitOptions {
        cols: 4,
        rows: 4,
        sub_cells: usize::MAX,
        ..FitOptions::default()
    };
    let outcome = catch_unwind(AssertUnwindSafe(|| fit_surrogate(&points, &options)));
    match outcome {
        Ok(Ok(s)) => assert_certified(&points, &s, options.sides),
        Ok(Err(e)) => assert!(!e.to_string().is_empty()),
        Err(_) => panic!("fit_surrogate panicked on sub_cells = usize::MAX"),
    }
}

fn odd_coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -10.0f32..10.0,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(0.0f32),
        1 => Just(f32::MAX),
        1 => Just(f32::MIN_POSITIVE),
    ]
}

fn odd_direction() -> impl Strategy<Value = [f64; 3]> {
    let component =
        prop_oneof![4 => -1.0f64..1.0, 1 => Just(0.0), 1 => Just(f64::NAN), 1 => Just(1e-320)];
    [component.clone(), component.clone(), component]
}

proptest! {
    #![proptest_config(config(1000))]

    /// Garbage in any field gives an error or a certified surrogate; never a panic.
    #[test]
    fn garbage_never_panics(
        points in prop::collection::vec([odd_coordinate(), odd_coordinate(), odd_coordinate()], 0..40),
        cols in 0..8usize,
        rows in 0..8usize,
        direction in odd_direction(),
        sub_cells in 0..6usize,
        max_solves in 0..4usize,
        sweeps in 0..3usize,
    ) {
        let options = FitOptions { cols, rows, direction, sub_cells, max_solves, sweeps, ..FitOptions::default() };
        let outcome = catch_unwind(AssertUnwindSafe(|| fit_surrogate(&points, &options)));
        match outcome {
            Ok(Ok(s)) => assert_certified(&points, &s, options.sides),
            Ok(Err(e)) => prop_assert!(!e.to_string().is_empty()),
            Err(_) => prop_assert!(false, "panicked on {:?} with {:?}", points, options),
        }
    }
}
