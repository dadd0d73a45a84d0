//! The guard's decision on fitted surrogates of small scenes: freshness by
//! arrival and pipeline delay, stamp skew, motion allowance, unobserved space,
//! several views, and the wire message.

use super::*;
use crate::guard::{Envelope, GuardConfig, Shape, WorldShape};
use crate::message::GuardVerdict;
use crate::surrogate::{fit_surrogate, FitOptions, Sides};
use glam::DVec3;
use rand::{Rng, SeedableRng};

const MS: u64 = 1_000_000;
const S: u64 = 1_000_000_000;
/// The guard's wall clock in these tests; surrogates are stamped with it.
const WALL: u64 = 1_700_000_000 * S;

/// A floor `[-1, 1]^2` at z = 0 and a wall `x in [0, 0.05]`, `z in [0, 1]`.
fn floor_and_wall() -> Vec<[f32; 3]> {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
    let mut points: Vec<[f32; 3]> = (0..6000)
        .map(|_| {
            [
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                0.0,
            ]
        })
        .collect();
    points.extend((0..6000).map(|_| {
        [
            rng.random_range(0.0..0.05),
            rng.random_range(-1.0..1.0),
            rng.random_range(0.0..1.0),
        ]
    }));
    points
}

fn view(points: &[[f32; 3]], direction: [f64; 3], pipeline_ns: u64) -> SurrogateInput {
    view_on_grid(points, direction, 16, pipeline_ns)
}

fn view_on_grid(
    points: &[[f32; 3]],
    direction: [f64; 3],
    grid: usize,
    pipeline_ns: u64,
) -> SurrogateInput {
    let options = FitOptions {
        cols: grid,
        rows: grid,
        direction,
        sides: Sides::Sandwich,
        ..FitOptions::default()
    };
    let surrogate = fit_surrogate(points, &options).unwrap();
    SurrogateInput {
        envelope: Envelope::new(&surrogate).unwrap(),
        stamp_ns: WALL,
        sequence: 1,
        pipeline_ns,
    }
}

const TOP: [f64; 3] = [0.0, 0.0, -1.0];
const SIDE: [f64; 3] = [0.0, -1.0, 0.0];

fn config() -> GuardConfig {
    GuardConfig {
        stop_distance: 0.05,
        max_report: 0.2,
        refine_depth: 3,
        max_obstacle_speed: 0.0,
    }
}

fn guard_with(views: &[&str], policy: GuardPolicy, config: GuardConfig) -> CollisionGuard {
    let names = views.iter().map(|v| v.to_string()).collect();
    CollisionGuard::new(names, vec!["base".into(), "tool".into()], policy, config).unwrap()
}

fn guard(views: &[&str], policy: GuardPolicy) -> CollisionGuard {
    guard_with(views, policy, config())
}

fn sphere(link: usize, at: [f64; 3], radius: f64) -> WorldShape {
    WorldShape {
        link,
        shape: Shape::sphere(DVec3::from_array(at), radius),
    }
}

/// A tool sphere 0.6 m above the floor, away from the wall: clear from the top.
fn above_floor() -> Vec<WorldShape> {
    vec![sphere(1, [-0.5, 0.0, 0.6], 0.05)]
}

/// A tool sphere beside the wall, halfway up: inside the top view's sandwich
/// (which spans floor to wall top there), 0.13 m from everything in truth.
fn beside_wall() -> Vec<WorldShape> {
    vec![sphere(1, [0.2, 0.0, 0.5], 0.02)]
}

#[test]
fn no_surrogate_then_clear_then_stale_by_arrival_and_pipeline_delay() {
    let points = floor_and_wall();
    let mut g = guard(&["top"], GuardPolicy::default());
    let d = g.decide(&above_floor(), 0).unwrap();
    assert_eq!(d.verdict, GuardVerdict::NoSurrogate);
    assert!(d.reason.contains("top"), "{}", d.reason);
    // Arrives at 10 s on the guard's clock, 100 ms after the sensor's data
    // reached shroud.
    g.accept(0, view(&points, TOP, 100 * MS), 10 * S, WALL)
        .unwrap();
    let d = g.decide(&above_floor(), 10 * S + 900 * MS).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Clear, "{}", d.reason);
    assert_eq!(d.views, 1);
    assert_eq!(d.oldest.unwrap().age_ns, S);
    let d = g.decide(&above_floor(), 10 * S + 900 * MS + 1).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Stale);
    assert!(d.report.is_none());
    // Stale on arrival when the pipeline alone took longer than the limit.
    g.accept(0, view(&points, TOP, 2 * S), 20 * S, WALL)
        .unwrap();
    assert_eq!(
        g.decide(&above_floor(), 20 * S).unwrap().verdict,
        GuardVerdict::Stale
    );
}

#[test]
fn device_stamps_do_not_decide_freshness_and_skewed_ones_are_refused() {
    let points = floor_and_wall();
    let mut g = guard(&["top"], GuardPolicy::default());
    // A stamp an hour off, either way, is refused.
    for skew in [3600 * S as i64, -(3600 * S as i64)] {
        let mut input = view(&points, TOP, 0);
        input.stamp_ns = (WALL as i64 + skew) as u64;
        let refused = g.accept(0, input, 0, WALL).unwrap_err();
        assert!(matches!(refused, SurrogateRejected::ClockSkew(_)));
        assert_eq!(refused.counter(), "clock_skew");
        assert!(refused.to_string().contains("3600.000 s"), "{refused}");
    }
    assert_eq!(
        g.decide(&above_floor(), 0).unwrap().verdict,
        GuardVerdict::NoSurrogate
    );
    // Within the skew: fresh by arrival, whatever the stamp says.
    let mut input = view(&points, TOP, 0);
    input.stamp_ns = WALL - 4 * S;
    g.accept(0, input, 0, WALL).unwrap();
    assert_eq!(
        g.decide(&above_floor(), 0).unwrap().verdict,
        GuardVerdict::Clear
    );
    // A skewed newcomer empties the view: its timing cannot be trusted.
    let mut late = view(&points, TOP, 0);
    late.stamp_ns = WALL + 3600 * S;
    assert!(g.accept(0, late, 500 * MS, WALL).is_err());
    assert_eq!(
        g.decide(&above_floor(), 500 * MS).unwrap().verdict,
        GuardVerdict::NoSurrogate
    );
    // So does one that could not be decoded.
    g.accept(0, view(&points, TOP, 0), 0, WALL).unwrap();
    g.invalidate(0);
    assert_eq!(
        g.decide(&above_floor(), 0).unwrap().verdict,
        GuardVerdict::NoSurrogate
    );
    // The check can be switched off (replays of old logs).
    let mut off = guard(
        &["top"],
        GuardPolicy {
            max_skew_ns: u64::MAX,
            ..GuardPolicy::default()
        },
    );
    let mut old = view(&points, TOP, 0);
    old.stamp_ns = 1;
    off.accept(0, old, 0, WALL).unwrap();
}

#[test]
fn the_motion_allowance_shrinks_clearances_by_speed_times_age() {
    let points = floor_and_wall();
    let input = view(&points, TOP, 0);
    let still = guard(&["top"], GuardPolicy::default());
    let fast = GuardConfig {
        max_obstacle_speed: 0.5,
        ..config()
    };
    let moving = guard_with(&["top"], GuardPolicy::default(), fast);
    let shapes = vec![sphere(1, [-0.5, 0.0, 0.2], 0.05)];
    let mut clearances = vec![];
    for mut g in [still, moving] {
        g.accept(0, input.clone(), 0, WALL).unwrap();
        let d = g.decide(&shapes, 200 * MS).unwrap();
        clearances.push(d.report.unwrap().min_clearance);
        // Older: the allowance grows until the shape must stop.
        let late = g.decide(&shapes, 900 * MS).unwrap();
        if g.config().max_obstacle_speed > 0.0 {
            assert_eq!(late.verdict, GuardVerdict::Stop, "{}", late.reason);
        }
    }
    // 0.5 m/s for 0.2 s: 0.1 m less, floored at 0.
    let expected = (clearances[0] - 0.1).max(0.0);
    assert!((clearances[1] - expected).abs() < 1e-12, "{clearances:?}");
}

#[test]
fn unobserved_space_stops_by_policy_and_is_always_flagged() {
    let points = floor_and_wall();
    // Far outside the floor's domain, high up: nothing seen there.
    let outside = vec![sphere(1, [3.0, 0.0, 0.6], 0.05)];
    for (policy, verdict) in [
        (UnobservedPolicy::Stop, GuardVerdict::Unobserved),
        (UnobservedPolicy::Ignore, GuardVerdict::Clear),
    ] {
        let mut g = guard(
            &["top"],
            GuardPolicy {
                unobserved: policy,
                ..GuardPolicy::default()
            },
        );
        g.accept(0, view(&points, TOP, 0), 0, WALL).unwrap();
        let d = g.decide(&outside, 0).unwrap();
        assert_eq!(d.verdict, verdict, "{}", d.reason);
        let msg = g.message(&d, "arm", (5, 6), 7);
        assert!(msg.unobserved);
        assert!(!msg.links[0].unobserved && msg.links[1].unobserved);
        assert_eq!((msg.joints_stamp_ns, msg.joints_sequence), (5, 6));
        assert_eq!(msg.stop, verdict != GuardVerdict::Clear);
        if verdict == GuardVerdict::Unobserved {
            assert!(msg.reason.contains("tool"), "{}", msg.reason);
        }
    }
}

#[test]
fn a_second_view_clears_what_the_top_view_cannot() {
    let points = floor_and_wall();
    // A coarse top view: the wall's cell reaches past the sphere.
    let (top, side) = (
        view_on_grid(&points, TOP, 8, 0),
        view_on_grid(&points, SIDE, 32, 0),
    );
    let mut one = guard(&["top"], GuardPolicy::default());
    one.accept(0, top.clone(), 0, WALL).unwrap();
    let alone = one.decide(&beside_wall(), 0).unwrap();
    assert_eq!(
        alone.verdict,
        GuardVerdict::Stop,
        "the top view alone is loose"
    );
    let mut two = guard(&["top", "side"], GuardPolicy::default());
    two.accept(0, top, 0, WALL).unwrap();
    two.accept(1, side.clone(), 0, WALL).unwrap();
    let both = two.decide(&beside_wall(), 0).unwrap();
    assert_eq!(both.verdict, GuardVerdict::Clear, "{}", both.reason);
    assert_eq!(both.views, 2);
    // Truth: the sphere is 0.13 m from the wall; the bound is below it.
    assert!(both.report.unwrap().min_clearance <= 0.13);
    // A view that has gone stale no longer helps.
    let mut aged = guard(&["top", "side"], GuardPolicy::default());
    aged.accept(0, view_on_grid(&points, TOP, 8, 0), 5 * S, WALL)
        .unwrap();
    aged.accept(1, side, 0, WALL).unwrap();
    let d = aged.decide(&beside_wall(), 5 * S).unwrap();
    assert_eq!((d.verdict, d.views), (GuardVerdict::Stop, 1));
}

#[test]
fn max_report_leaves_room_for_the_motion_allowance() {
    let fast = GuardConfig {
        max_obstacle_speed: 1.0,
        ..config()
    };
    let policy = GuardPolicy {
        unobserved: UnobservedPolicy::Ignore,
        ..GuardPolicy::default()
    };
    let g = guard_with(&["top"], policy, fast);
    // 0.05 m stop distance plus 1 m/s for the 1 s maximum age.
    assert!((g.config().max_report - 1.05).abs() < 1e-12);
    // Far from everything, an old surrogate still clears (with the cap at
    // 0.2 m, 0.6 s at 1 m/s would leave nothing).
    let mut g = g;
    g.accept(0, view(&floor_and_wall(), TOP, 0), 0, WALL)
        .unwrap();
    let shapes = vec![sphere(1, [-0.5, 0.0, 1.8], 0.05)];
    let d = g.decide(&shapes, 600 * MS).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Clear, "{}", d.reason);
    assert!(d.report.unwrap().min_clearance > config().stop_distance);
}

#[test]
fn refused_joint_states_stop_with_their_reason() {
    let g = guard(&["top"], GuardPolicy::default());
    let d = Decision::refused("joint names differ");
    let msg = g.message(&d, "arm", (0, 0), 1);
    assert!(msg.stop && msg.verdict == GuardVerdict::Stop);
    assert_eq!(msg.reason, "joint names differ");
    assert_eq!(msg.min_clearance, 0.0);
}

#[test]
fn bad_settings_are_refused() {
    let policy = GuardPolicy::default();
    let new = |views: Vec<&str>, policy| {
        CollisionGuard::new(
            views.into_iter().map(String::from).collect(),
            vec![],
            policy,
            config(),
        )
    };
    assert!(new(vec![], policy).is_err());
    assert!(new(vec!["a", "a"], policy).is_err());
    assert!(new(
        vec!["a"],
        GuardPolicy {
            max_age_ns: 0,
            ..policy
        }
    )
    .is_err());
    let mut g = new(vec!["a"], policy).unwrap();
    let input = view(&floor_and_wall(), TOP, 0);
    assert_eq!(
        g.accept(3, input, 0, WALL),
        Err(SurrogateRejected::UnknownView(3))
    );
}
