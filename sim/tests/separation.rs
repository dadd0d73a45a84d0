//! The guard's speed and separation monitoring, checked by brute force in
//! closed loop (`shroud_sim::soundness::separation`; the full run is
//! `shroud-bench guard-separation`, its table in docs/guard-separation.md):
//!
//! - an arm that keeps its contract never comes nearer to anything than the
//!   stop distance less the sampling margin while it moves, under the
//!   scaled guard and the binary one, and the run is not trivially safe:
//!   full-speed, scaled and stop verdicts all occur, obstacles do reach the
//!   arm (while it stands), and the scaling moves the arm further than the
//!   binary stop;
//! - the negative controls fail: an arm that obeys later than its declared
//!   reaction time, and a guard told that obstacles stand still, are caught,
//!   and the first failure replays alone from its seed.

use shroud_sim::soundness::separation::{
    run, run_trajectory, ArmBehaviour, SeparationArms, SeparationParams, SeparationReport,
};

const SEED: u64 = 23;

fn summary(report: &SeparationReport, params: &SeparationParams) -> String {
    report.table(params, &[])
}

#[test]
fn an_arm_keeping_its_contract_keeps_its_separation() {
    let params = SeparationParams::default();
    let trajectories = 120;
    let report = run(&params, trajectories, SEED).expect("the run runs");
    let table = summary(&report, &params);
    eprintln!("{table}");
    assert_eq!(report.trajectories, trajectories);
    assert_eq!(report.failures, 0, "{table}");
    assert_eq!(report.binary_failures, 0, "{table}");
    assert!(report.first_failure.is_none(), "{table}");
    // Every joint state answered, by both guards (but those whose decision
    // would fall after the end).
    let states = trajectories * (params.duration * params.joint_rate) as u64;
    assert!(report.verdicts.total() * 100 >= states * 99, "{table}");
    assert_eq!(
        report.binary_clear + report.binary_stop,
        report.verdicts.total()
    );
    // Not trivially safe: scales strictly between 0 and 1, full speed and
    // stops all occur; obstacles reach the arm's shapes (while it stands).
    assert!(report.scaled > 0, "{table}");
    assert!(report.smallest_scale > 0.0 && report.smallest_scale < 1.0);
    assert!(report.full_speed > 0, "{table}");
    assert!(report.verdicts.stop > 0, "{table}");
    assert!(report.min_separation < 0.0, "{table}");
    assert!(report.min_separation_moving.is_finite(), "{table}");
    assert!(report.crossings > 0 && report.crossings < trajectories);
    // The threshold is a real one: the sampling margin leaves most of C.
    assert!(report.min_threshold > 0.3 * params.stop_distance, "{table}");
    // The scaling moves the arm further than a binary stop at the same
    // safety.
    let (scaled, binary) = (&report.scaled_mode.all, &report.binary_mode.all);
    assert!(scaled.progress > binary.progress, "{table}");
    assert!(scaled.mean_scale() > 0.0 && binary.mean_scale() > 0.0);
}

/// Runs a negative control on `trajectories` person-crossing scenes and
/// returns its report.
fn control(params: SeparationParams, trajectories: u64) -> SeparationReport {
    let params = SeparationParams {
        person_share: 1.0,
        compare_binary: false,
        ..params
    };
    let report = run(&params, trajectories, SEED).expect("the run runs");
    eprintln!("{}", summary(&report, &params));
    report
}

#[test]
fn an_arm_obeying_later_than_declared_is_caught_and_replays() {
    let params = SeparationParams {
        behaviour: ArmBehaviour::Late(0.5),
        person_share: 1.0,
        compare_binary: false,
        ..SeparationParams::default()
    };
    // About one trajectory in ten fails.
    let report = control(params, 50);
    assert!(report.failures > 0, "the harness missed a late arm");
    let first = report.first_failure.expect("a failure is kept");
    assert!(first.distance < first.threshold, "{first}");
    assert!(!first.link.is_empty() && first.time > 0.0);
    // The failure replays alone from its seed, at the same instant.
    let arms = SeparationArms::load(params.mount_lift).expect("the arms load");
    let alone = run_trajectory(&arms, &params, first.seed, first.index).expect("replays");
    let again = alone.first_failure.expect("it fails alone too");
    assert_eq!(again, first);
    // The same trajectory with an arm on time keeps its separation.
    let on_time = SeparationParams {
        behaviour: ArmBehaviour::Obeys,
        ..params
    };
    let kept = run_trajectory(&arms, &on_time, first.seed, first.index).expect("runs");
    assert_eq!(kept.failures, 0, "{}", summary(&kept, &on_time));
}

#[test]
fn a_guard_that_takes_obstacles_for_still_is_caught() {
    // About one trajectory in thirty fails: the guard's own stop distance
    // and the arm's stopping terms still cover most approaches.
    let report = control(
        SeparationParams {
            declared_obstacle_speed: Some(0.0),
            ..SeparationParams::default()
        },
        150,
    );
    let first = report.first_failure.as_ref();
    assert!(first.is_some_and(|f| f.obstacle.contains("person") || f.obstacle.contains("solid")));
    assert!(
        report.failures > 0,
        "the harness missed a guard blind to motion"
    );
}

#[test]
fn bad_parameters_are_errors() {
    for params in [
        SeparationParams {
            stop_distance: 0.0,
            ..SeparationParams::default()
        },
        SeparationParams {
            horizon: 2.0,
            ..SeparationParams::default()
        },
        SeparationParams {
            scan_rate_max: 5.0,
            ..SeparationParams::default()
        },
        SeparationParams {
            behaviour: ArmBehaviour::SoftBrakes(0.5),
            ..SeparationParams::default()
        },
        SeparationParams {
            declared_obstacle_speed: Some(f64::NAN),
            ..SeparationParams::default()
        },
    ] {
        assert!(run(&params, 1, 0).is_err(), "{params:?}");
    }
}
