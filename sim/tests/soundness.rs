//! The guard's promise, checked by brute force: random scenes of moving
//! solids, scanned by random sensors, fitted and judged by shroud's real
//! fitter and guard, every verdict compared with exact geometry
//! (`shroud_sim::soundness`; the full run is `shroud-bench guard-soundness`).
//!
//! - Within the guard's documented assumptions (sensors that see every
//!   column over their footprint, i.e. parallel rays, and no black solids) a
//!   `clear` must never be optimistic, and the run must not be trivially
//!   safe: clear verdicts and stops, near and far.
//! - Perspective sensors whose clouds state their field of view, without
//!   black solids: no optimistic `clear` either. Without the stated field of
//!   view the field-of-view edge class appears: what the statement fixes.
//! - In the realistic scenes (black solids too), clouds that also list their
//!   rays without a return: no optimistic `clear`. Without that list, black
//!   solids are missed, and nothing else (the control).
//! - The negative control: a guard that ignores unseen space is caught.

use shroud_guard::UnobservedPolicy;
use shroud_sim::soundness::{minimise, run, FindingClass, SoundnessParams, SoundnessReport};

/// Scenes per run (a few seconds each in the test profile).
const CASES: u64 = 150;
const SEED: u64 = 23;

/// Scenes the guard's assumptions cover.
fn assumed() -> SoundnessParams {
    SoundnessParams {
        parallel_rays: true,
        black_share: 0.0,
        ..SoundnessParams::default()
    }
}

/// Runs `params` and asserts no optimistic verdict, no contact, and both
/// clear and stop verdicts (not trivially safe).
fn assert_never_optimistic(params: &SoundnessParams) {
    let report = run(params, CASES, SEED).expect("the run runs");
    eprintln!(
        "verdicts {:?}, conservativeness {:?}",
        report.verdicts,
        report.conservativeness()
    );
    assert_eq!(report.contacts, 0, "{}", findings(&report));
    assert_eq!(report.optimistic, 0, "{}", findings(&report));
    assert!(report.verdicts.clear > 0 && report.verdicts.stop > 0);
}

fn findings(report: &SoundnessReport) -> String {
    let list: Vec<String> = report.findings.iter().map(|f| f.to_string()).collect();
    format!("{:?}\n{}", report.classes, list.join("\n"))
}

#[test]
fn no_clear_verdict_is_optimistic_within_the_assumptions() {
    let params = assumed();
    let report = run(&params, CASES, SEED).expect("the run runs");
    eprintln!(
        "{:#?}",
        SoundnessReport {
            findings: Vec::new(),
            ..report.clone()
        }
    );
    assert_eq!(report.scenes, CASES);
    assert_eq!(
        report.verdicts.total(),
        CASES * params.verdicts_per_case as u64
    );
    assert_eq!(report.contacts, 0, "{}", findings(&report));
    assert_eq!(report.optimistic, 0, "{}", findings(&report));
    // Not trivially safe: the guard said clear and stop, and cleared poses
    // close to the stop distance.
    let v = &report.verdicts;
    assert!(v.clear * 5 >= v.total(), "{v:?}");
    assert!(v.stop * 5 >= v.total(), "{v:?}");
    assert!(report.views > CASES, "most scenes have several views");
    assert!(
        report.closest_clear < 2.5 * params.stop_distance,
        "{}",
        report.closest_clear
    );
    assert!(
        report.eligible * 10 >= v.total(),
        "{} eligible",
        report.eligible
    );
    // The target for stops in space the sensors proved free is a third;
    // with the sensors the views assume the guard meets it (about 28 % here,
    // 28.6 % over 10^4 scenes in docs/guard-soundness.md).
    let share = report.conservativeness().expect("some poses are eligible");
    assert!(share <= 1.0 / 3.0, "conservativeness {share}");
}

#[test]
fn perspective_sensors_stating_their_field_of_view_are_never_optimistic() {
    let params = SoundnessParams {
        black_share: 0.0,
        ..SoundnessParams::default()
    };
    assert_never_optimistic(&params);
    // The control: the same scenes with clouds that do not state it.
    let unstated = SoundnessParams {
        state_field_of_view: false,
        ..params
    };
    let report = run(&unstated, CASES, SEED).expect("the run runs");
    let edge = report.classes[FindingClass::FieldOfView as usize];
    assert!(
        edge > 0,
        "no field-of-view edge finding without the statement"
    );
}

/// The realistic scenes: perspective sensors whose clouds state their field
/// of view and their rays without a return, black solids among the rest.
#[test]
fn realistic_scenes_are_never_optimistic() {
    let params = SoundnessParams::default();
    assert_never_optimistic(&params);
}

/// Sectors (the default: 4 x 4 per view) clear poses in space the sensors
/// proved free that the whole views alone stop, on the same eligible poses
/// (29.2 % against 40.3 % over 10^4 scenes in docs/guard-soundness.md).
#[test]
fn sectors_stop_fewer_poses_in_seen_space_than_whole_views() {
    let with = run(&SoundnessParams::default(), CASES, SEED).expect("the run runs");
    let whole = SoundnessParams {
        sectors: 0,
        ..SoundnessParams::default()
    };
    let without = run(&whole, CASES, SEED).expect("the run runs");
    eprintln!(
        "stopped {} of {} with sectors, {} of {} without",
        with.eligible_stopped, with.eligible, without.eligible_stopped, without.eligible
    );
    assert_eq!(
        with.eligible, without.eligible,
        "the same poses are eligible"
    );
    assert!(with.eligible * 10 >= CASES, "{} eligible", with.eligible);
    assert!(with.eligible_stopped < without.eligible_stopped);
    assert_eq!(with.optimistic, 0, "{}", findings(&with));
    let share = with.conservativeness().expect("some poses are eligible");
    assert!(share <= 1.0 / 3.0, "conservativeness {share}");
}

/// The control: clouds that do not list their empty rays let black solids
/// through, and nothing else: every finding is a black solid inside a kept
/// triangle, and the first one replays and minimises.
#[test]
fn without_empty_rays_stated_only_black_solids_are_missed() {
    let params = SoundnessParams {
        state_no_return: false,
        black_share: 0.5,
        ..SoundnessParams::default()
    };
    let report = run(&params, CASES, SEED).expect("the run runs");
    eprintln!(
        "classes {:?}, optimistic {}",
        report.classes, report.optimistic
    );
    assert_eq!(report.classes.iter().sum::<u64>(), report.optimistic);
    assert!(
        report.classes[FindingClass::BlackSolid as usize] > 0,
        "no black-solid finding without the statement"
    );
    for class in [
        FindingClass::FieldOfView,
        FindingClass::Timing,
        FindingClass::Sampling,
        FindingClass::Other,
    ] {
        assert_eq!(
            report.classes[class as usize],
            0,
            "{class:?}: {}",
            findings(&report)
        );
    }
    let finding = report.findings.first().expect("a kept finding");
    let scene = minimise(&params, finding)
        .expect("replays")
        .expect("still optimistic");
    assert!(!scene.solids.is_empty() || finding.solid.is_none());
    assert!(!scene.sensors.is_empty());
}

/// With unseen space ignored, a view vouches for what its sensor never saw,
/// and the harness must catch it even where the assumptions hold.
#[test]
fn ignoring_unseen_space_is_caught() {
    let params = SoundnessParams {
        unobserved: UnobservedPolicy::Ignore,
        sectors: 0,
        ..assumed()
    };
    let report = run(&params, CASES, SEED).expect("the run runs");
    eprintln!(
        "classes {:?}, optimistic {}",
        report.classes, report.optimistic
    );
    assert!(report.optimistic > 0, "the harness missed a lying guard");
    assert!(!report.findings.is_empty());
}

#[test]
fn bad_parameters_are_errors() {
    for params in [
        SoundnessParams {
            stop_distance: -1.0,
            ..SoundnessParams::default()
        },
        SoundnessParams {
            horizon: f64::NAN,
            ..SoundnessParams::default()
        },
        SoundnessParams {
            sectors: 9,
            ..SoundnessParams::default()
        },
        SoundnessParams {
            sector_reach: 0.5,
            ..SoundnessParams::default()
        },
        SoundnessParams {
            unobserved: UnobservedPolicy::Ignore,
            ..SoundnessParams::default()
        },
        SoundnessParams {
            timings_per_pose: 0,
            ..SoundnessParams::default()
        },
        SoundnessParams {
            black_share: 2.0,
            ..SoundnessParams::default()
        },
    ] {
        assert!(run(&params, 1, 0).is_err(), "{params:?}");
    }
}
