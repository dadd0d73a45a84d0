//! Warm start across the frames of a moving cloud: one `SurrogateFitter` carried
//! through 20 frames of `shroud_sim::MovingSpheres` against a fresh fitter per
//! frame. Both must be certified every frame; the warm one must not need more
//! Heuristic(σ, b, λ) solves, and must say it was warm-started.

mod common;

use common::brute_force::assert_certified;
use shroud_surrogate::{fit_surrogate, FitOptions, Histogram, Sides, SurrogateFitter, Tightness};

const FRAMES: usize = 20;
/// Seconds between frames: a 30 Hz sensor.
const FRAME_TIME: f64 = 1.0 / 30.0;

/// Solve totals of the warm and the cold runs, and their merged histograms.
struct Run {
    warm_total: u64,
    cold_total: u64,
    warm: Histogram,
    cold: Histogram,
}

/// Sum of the recorded values (the histogram index is the solve count).
fn total_solves(h: &Histogram) -> u64 {
    h.counts
        .iter()
        .enumerate()
        .map(|(solves, lines)| solves as u64 * lines)
        .sum()
}

/// Fits every frame warm and cold, checking each surrogate by brute force.
fn run(options: &FitOptions, points: usize) -> Run {
    let scene = shroud_sim::MovingSpheres {
        points,
        seed: 3,
        ..Default::default()
    };
    let mut fitter = SurrogateFitter::new(options.clone()).expect("valid options");
    let mut run = Run {
        warm_total: 0,
        cold_total: 0,
        warm: Histogram::default(),
        cold: Histogram::default(),
    };
    for frame in 0..FRAMES {
        let cloud = scene
            .generate(frame as f64 * FRAME_TIME)
            .expect("valid scene");
        let warm = fitter.fit(&cloud).expect("warm fit");
        let cold = fit_surrogate(&cloud, options).expect("cold fit");
        assert_certified(&cloud, &warm, options.sides);
        assert_certified(&cloud, &cold, options.sides);
        assert_eq!(
            warm.stats.warm_started,
            frame > 0,
            "frame {frame}: warm_started of the carried fitter"
        );
        assert!(
            !cold.stats.warm_started,
            "frame {frame}: a fresh fitter is never warm"
        );
        run.warm_total += total_solves(&warm.stats.curve_solves);
        run.cold_total += total_solves(&cold.stats.curve_solves);
        run.warm.merge(&warm.stats.curve_solves);
        run.cold.merge(&cold.stats.curve_solves);
    }
    run
}

fn assert_warm_is_cheaper(options: FitOptions, points: usize) {
    let run = run(&options, points);
    eprintln!(
        "{:?} {:?}: warm {} solves (mean {:.2}, max {}), cold {} solves (mean {:.2}, max {})",
        options.sides,
        options.tightness,
        run.warm_total,
        run.warm.mean(),
        run.warm.max(),
        run.cold_total,
        run.cold.mean(),
        run.cold.max()
    );
    assert_eq!(
        run.warm.total(),
        run.cold.total(),
        "the same lines are fitted"
    );
    assert!(
        run.warm_total <= run.cold_total,
        "warm {} > cold {}",
        run.warm_total,
        run.cold_total
    );
    assert!(run.warm.mean() <= run.cold.mean());
}

#[test]
fn warm_start_is_certified_and_needs_no_more_solves_than_cold() {
    assert_warm_is_cheaper(FitOptions::default(), 5_000);
}

#[test]
fn warm_start_of_a_symmetrized_sandwich_is_certified_and_no_dearer() {
    let options = FitOptions {
        cols: 17,
        rows: 23,
        sides: Sides::Sandwich,
        symmetrize: true,
        tightness: Tightness::Plain,
        ..FitOptions::default()
    };
    assert_warm_is_cheaper(options, 4_000);
}

#[test]
fn reset_forgets_the_previous_frame() {
    let cloud = shroud_sim::MovingSpheres {
        points: 2_000,
        ..Default::default()
    }
    .generate(0.5)
    .expect("scene");
    let options = FitOptions {
        cols: 10,
        rows: 10,
        ..FitOptions::default()
    };
    let mut fitter = SurrogateFitter::new(options.clone()).expect("valid options");
    let cold = fitter.fit(&cloud).expect("fit");
    assert!(fitter.fit(&cloud).expect("fit").stats.warm_started);
    fitter.reset_warm_start();
    let again = fitter.fit(&cloud).expect("fit");
    assert!(!again.stats.warm_started);
    assert_eq!(
        again, cold,
        "a reset fitter reproduces the cold fit exactly"
    );
}
