//! The guard's decision on fitted surrogates of small scenes: freshness by
//! arrival and pipeline delay, stamp skew, motion allowance, unobserved space,
//! several views, and the wire message.

use super::*;
use crate::{Envelope, GuardConfig, Shape, WorldShape};
use glam::DVec3;
use rand::{Rng, SeedableRng};
use shroud_msg::GuardVerdict;
use shroud_surrogate::{fit_surrogate, FitOptions, Sides};

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
    input_of(&surrogate, pipeline_ns)
}

fn input_of(surrogate: &shroud_surrogate::Surrogate, pipeline_ns: u64) -> SurrogateInput {
    SurrogateInput {
        envelope: Envelope::new(surrogate).unwrap(),
        stamp_ns: WALL,
        sequence: 1,
        pipeline_ns,
        published_ns: WALL,
        position_error: 0.0,
    }
}

const TOP: [f64; 3] = [0.0, 0.0, -1.0];
/// Looking at the wall's face: every column of this view holds wall points.
const SIDE: [f64; 3] = [-1.0, 0.0, 0.0];
/// Along the wall: the columns between the floor and the wall's top hold no
/// point, so this view saw nothing there.
const ALONG: [f64; 3] = [0.0, -1.0, 0.0];
/// The clock offset every transit is counted with by default.
const OFFSET: u64 = shroud_msg::DEFAULT_MAX_CLOCK_OFFSET_NS;

fn config() -> GuardConfig {
    GuardConfig {
        stop_distance: 0.05,
        max_report: 0.2,
        refine_depth: 3,
        max_obstacle_speed: 0.0,
        horizon: 0.0,
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
    // Its transit counts as the clock offset bound (published and received
    // at the same wall time).
    let d = g
        .decide(&above_floor(), 10 * S + 900 * MS - OFFSET)
        .unwrap();
    assert_eq!(d.verdict, GuardVerdict::Clear, "{}", d.reason);
    assert_eq!(d.views, 1);
    assert_eq!(d.oldest.unwrap().age_ns, S);
    let d = g
        .decide(&above_floor(), 10 * S + 900 * MS - OFFSET + 1)
        .unwrap();
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
    // 0.5 m/s for 0.2 s and the transit's offset bound, floored at 0.
    let expected = (clearances[0] - 0.5 * (0.2 + OFFSET as f64 * 1e-9)).max(0.0);
    assert!((clearances[1] - expected).abs() < 1e-12, "{clearances:?}");
}

/// Case 4 of issue 23: the arm may move on a clear until its deadline, so an
/// obstacle's motion until then counts, and so does the sensor's own error.
#[test]
fn the_allowance_runs_until_the_horizon_and_counts_the_position_error() {
    let points = floor_and_wall();
    let shapes = vec![sphere(1, [-0.5, 0.0, 0.2], 0.05)];
    let clearance = |speed: f64, horizon: f64, error: f64| {
        let cfg = GuardConfig {
            max_obstacle_speed: speed,
            horizon,
            ..config()
        };
        let mut g = guard_with(&["top"], GuardPolicy::default(), cfg);
        let mut input = view(&points, TOP, 0);
        input.position_error = error;
        g.accept(0, input, 0, WALL).unwrap();
        let d = g.decide(&shapes, 100 * MS).unwrap();
        (d.verdict, d.report.unwrap().min_clearance)
    };
    let (_, still) = clearance(0.0, 0.0, 0.0);
    assert!(still > 0.1, "{still}");
    let age = 0.1 + OFFSET as f64 * 1e-9;
    let (_, moving) = clearance(0.2, 0.06, 0.0);
    assert!((moving - (still - 0.2 * (age + 0.06))).abs() < 1e-12);
    let (_, misplaced) = clearance(0.0, 0.0, 0.03);
    assert!((misplaced - (still - 0.03)).abs() < 1e-12);
    // Far from everything, a view with a position error looks that much
    // further, so its bound stays at `max_report` instead of stopping the
    // arm in empty space (0.2 - 0.16 would be below the stop distance).
    let far = vec![sphere(1, [-0.5, 0.0, 1.6], 0.05)];
    for error in [0.0, 0.16] {
        let mut g = guard(&["top"], GuardPolicy::default());
        let mut input = view(&points, TOP, 0);
        input.position_error = error;
        g.accept(0, input, 0, WALL).unwrap();
        let d = g.decide(&far, 0).unwrap();
        assert_eq!(d.verdict, GuardVerdict::Clear, "{error}: {}", d.reason);
        let bound = d.report.unwrap().min_clearance;
        assert!(
            (bound - config().max_report).abs() < 1e-12,
            "{error}: {bound}"
        );
    }
    // The demo's numbers: 1.3 m/s over a 60 ms deadline is 7.8 cm, more than
    // the 5 cm stop distance: a shape 10 cm clear at the decision stops.
    let (verdict, _) = clearance(1.3, 0.06, 0.0);
    assert_eq!(verdict, GuardVerdict::Stop);
    // A position error that is not a distance empties the view.
    let mut g = guard(&["top"], GuardPolicy::default());
    for bad in [f64::NAN, -0.01, f64::INFINITY] {
        let mut input = view(&points, TOP, 0);
        input.position_error = bad;
        let refused = g.accept(0, input, 0, WALL).unwrap_err();
        assert_eq!(refused.counter(), "bad_position_error");
    }
}

/// Case 3 of issue 23: what held the surrogate up before the guard's callback
/// ran (the network, a stalled link, a guard frozen or starved) counts.
#[test]
fn time_in_transit_and_before_the_callback_counts_toward_the_age() {
    let points = floor_and_wall();
    let mut g = guard(&["top"], GuardPolicy::default());
    // Published 2 s before the guard's callback saw it (a guard stopped with
    // SIGSTOP, say): stale at once, however recently it "arrived".
    let mut input = view(&points, TOP, 0);
    input.published_ns = WALL - 2 * S;
    g.accept(0, input, 10 * S, WALL).unwrap();
    let d = g.decide(&above_floor(), 10 * S).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Stale, "{}", d.reason);
    assert_eq!(d.oldest.unwrap().age_ns, 2 * S + OFFSET);
    // 300 ms in transit plus 200 ms since: 0.5 s old.
    let mut input = view(&points, TOP, 0);
    input.published_ns = WALL - 300 * MS;
    g.accept(0, input, 10 * S, WALL).unwrap();
    let d = g.decide(&above_floor(), 10 * S + 200 * MS).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Clear, "{}", d.reason);
    assert_eq!(d.oldest.unwrap().age_ns, 500 * MS + OFFSET);
    // Published in the guard's future by more than the clock offset bound:
    // the clocks disagree beyond what was configured; the view is emptied.
    let mut ahead = view(&points, TOP, 0);
    ahead.published_ns = WALL + 2 * OFFSET;
    let refused = g.accept(0, ahead, 10 * S, WALL).unwrap_err();
    assert_eq!(refused.counter(), "clock_offset");
    assert!(refused.to_string().contains("future"), "{refused}");
    assert_eq!(
        g.decide(&above_floor(), 10 * S).unwrap().verdict,
        GuardVerdict::NoSurrogate
    );
    // Within the bound it is taken, its transit counted as the bound.
    let mut close = view(&points, TOP, 0);
    close.published_ns = WALL + OFFSET / 2;
    g.accept(0, close, 10 * S, WALL).unwrap();
    let d = g.decide(&above_floor(), 10 * S).unwrap();
    assert_eq!(d.oldest.unwrap().age_ns, OFFSET);
}

/// Case 1 of issue 23, as filed: an obstacle appears from above in the top
/// view's newer cloud; the side view, from the older cloud, ends below it.
#[test]
fn views_of_different_clouds_never_clear_what_one_of_them_saw() {
    let older = floor_and_wall();
    let mut newer = older.clone();
    newer.extend((0..5).map(|k| [0.5, 0.0, 1.32 + 0.01 * k as f32]));
    let link = vec![sphere(1, [0.5, 0.0, 1.25], 0.05)];
    for speed in [0.0, 0.2] {
        let cfg = GuardConfig {
            max_obstacle_speed: speed,
            ..config()
        };
        let mut g = guard_with(&["top", "side"], GuardPolicy::default(), cfg);
        g.accept(0, view(&newer, TOP, 0), 300 * MS, WALL).unwrap();
        g.accept(1, view(&older, ALONG, 0), 0, WALL).unwrap();
        let d = g.decide(&link, 300 * MS).unwrap();
        assert_eq!(d.verdict, GuardVerdict::Stop, "{speed} m/s: {}", d.reason);
        assert_eq!(d.views, 2);
    }
}

/// Case 2 of issue 23, as filed: a floor seen only where x + y < 0; the rest
/// of the domain holds trimmed triangles, which are not free space.
#[test]
fn space_no_point_covers_inside_the_domain_is_unobserved() {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(9);
    let mut points: Vec<[f32; 3]> = Vec::new();
    while points.len() < 6000 {
        let (x, y): (f32, f32) = (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
        if x + y < 0.0 {
            points.push([x, y, 0.0]);
        }
    }
    // The domain is the points' bounding box, [-1, 1]^2: stretch it there.
    points.extend([[1.0, -1.0, 0.0], [-1.0, 1.0, 0.0]]);
    let link = vec![sphere(1, [0.6, 0.6, 0.1], 0.05)];
    for sides in [Sides::Sandwich, Sides::Upper] {
        let options = FitOptions {
            cols: 16,
            rows: 16,
            direction: TOP,
            sides,
            ..FitOptions::default()
        };
        let surrogate = fit_surrogate(&points, &options).unwrap();
        let mut g = guard(&["top"], GuardPolicy::default());
        g.accept(0, input_of(&surrogate, 0), 0, WALL).unwrap();
        let d = g.decide(&link, 0).unwrap();
        assert_eq!(
            d.verdict,
            GuardVerdict::Unobserved,
            "{sides:?}: {}",
            d.reason
        );
        // Where the floor was seen, the same sphere is clear.
        let seen = vec![sphere(1, [-0.6, -0.6, 0.3], 0.05)];
        let d = g.decide(&seen, 0).unwrap();
        assert_eq!(d.verdict, GuardVerdict::Clear, "{sides:?}: {}", d.reason);
    }
}

/// The floor is seen whole, but the sensor's cone from 1.5 m above its
/// centre does not reach the corner at the height of the arm: with the field
/// of view stated, a sphere there is unobserved, one on the axis is clear,
/// and without it both are clear (the view's column vouches for the corner).
#[test]
fn space_outside_a_stated_field_of_view_is_unobserved() {
    use shroud_msg::{Aperture, FieldOfView};
    let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
    // Dense enough that no triangle of the 16x16 grid is empty.
    let floor: Vec<[f32; 3]> = (0..20000)
        .map(|_| {
            [
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                0.0,
            ]
        })
        .collect();
    // 45 degrees: the floor's corners are 1.41 m off the axis at 1.5 m down,
    // inside; at z = 1.0 (0.5 m down) the cone's radius is 0.5 m.
    let fov = FieldOfView {
        apex: [0.0, 0.0, 1.5],
        axis: [0.0, 0.0, -1.0],
        aperture: Aperture::Cone {
            half_angle: std::f64::consts::FRAC_PI_4,
        },
        max_range: 5.0,
    };
    let corner = vec![sphere(1, [-0.8, -0.8, 1.0], 0.05)];
    let axis = vec![sphere(1, [0.0, 0.0, 0.6], 0.05)];
    let plain = view(&floor, TOP, 0);
    let mut stated = plain.clone();
    stated.envelope = stated.envelope.with_field_of_view(Some(fov)).unwrap();
    let mut g = guard(&["top"], GuardPolicy::default());
    g.accept(0, stated, 0, WALL).unwrap();
    let d = g.decide(&corner, 0).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Unobserved, "{}", d.reason);
    let d = g.decide(&axis, 0).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Clear, "{}", d.reason);
    // Near the cone, the bound is the distance to it less the radius: at
    // 0.5 m down and 0.3 m off the axis, (0.5 - 0.3) sin(45 deg) away.
    let near = vec![sphere(1, [0.3, 0.0, 1.0], 0.05)];
    let d = g.decide(&near, 0).unwrap();
    let expected = 0.2 * std::f64::consts::FRAC_1_SQRT_2 - 0.05;
    let bound = d.report.unwrap().min_clearance;
    assert!((bound - expected).abs() < 1e-9, "{bound} vs {expected}");
    let mut g = guard(&["top"], GuardPolicy::default());
    g.accept(0, plain, 0, WALL).unwrap();
    assert_eq!(g.decide(&corner, 0).unwrap().verdict, GuardVerdict::Clear);
    assert_eq!(g.decide(&axis, 0).unwrap().verdict, GuardVerdict::Clear);
    // A field of view that is not convex is refused by name.
    let bad = FieldOfView {
        aperture: Aperture::Cone { half_angle: 2.0 },
        ..fov
    };
    let e = view(&floor, TOP, 0)
        .envelope
        .with_field_of_view(Some(bad))
        .unwrap_err();
    assert!(e.to_string().contains("half angle"), "{e}");
}

/// A black ball of radius 6 cm at (0.4, 0, 0.5) under a sensor 1.5 m above
/// the floor's centre: its rays return nothing, but the floor seen around it
/// keeps every triangle of an 8 x 8 grid, so without the empty rays stated
/// a sphere 2 cm above the ball is `clear`. With them (`cloud::dark_cones` over the sensor's ray
/// grid, as a driver states them), it is `unobserved`; a sphere away from
/// the ball's cone stays clear.
#[test]
fn rays_without_return_are_unobserved_space() {
    use shroud_geometry::cloud::{dark_cones, EmptyRays};
    let apex = DVec3::new(0.0, 0.0, 1.5);
    let (ball, radius) = (DVec3::new(0.4, 0.0, 0.5), 0.06);
    // A 201 x 201 pinhole grid over [-0.8, 0.8]^2 of the image plane at unit
    // distance below the apex: the floor is hit at 1.5 times that.
    let (n, step) = (201usize, 0.008);
    let direction = |k: usize| {
        let (i, j) = ((k % n) as f64 - 100.0, (k / n) as f64 - 100.0);
        DVec3::new(i * step, j * step, -1.0).normalize()
    };
    let mut floor = Vec::new();
    let mut empty = vec![false; n * n];
    for (k, slot) in empty.iter_mut().enumerate() {
        let d = direction(k);
        // Ray against the ball: the nearest approach of the line to its centre.
        let along = (ball - apex).dot(d);
        if ((ball - apex) - d * along).length() <= radius {
            *slot = true;
            continue;
        }
        let p = apex + d * (1.5 / -d.z);
        floor.push([p.x as f32, p.y as f32, 0.0]);
    }
    let rays = EmptyRays {
        rows: n,
        columns: n,
        empty: &empty,
    };
    let spread = step * std::f64::consts::SQRT_2;
    let no_return = dark_cones(apex.to_array(), &rays, direction, spread)
        .unwrap()
        .expect("the ball's rays are kept");
    let touching = vec![sphere(1, [0.4, 0.0, 0.63], 0.05)];
    let away = vec![sphere(1, [-0.5, 0.3, 0.6], 0.05)];
    let plain = view_on_grid(&floor, TOP, 8, 0);
    let mut g = guard(&["top"], GuardPolicy::default());
    g.accept(0, plain.clone(), 0, WALL).unwrap();
    let d = g.decide(&touching, 0).unwrap();
    assert_eq!(
        d.verdict,
        GuardVerdict::Clear,
        "the hole the test is about: {}",
        d.reason
    );
    let mut stated = plain;
    stated.envelope = stated.envelope.with_no_return(Some(&no_return)).unwrap();
    let mut g = guard(&["top"], GuardPolicy::default());
    g.accept(0, stated, 0, WALL).unwrap();
    let d = g.decide(&touching, 0).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Unobserved, "{}", d.reason);
    let d = g.decide(&away, 0).unwrap();
    assert_eq!(d.verdict, GuardVerdict::Clear, "{}", d.reason);
    // A cone that is not one is refused by name.
    let mut bad = no_return.clone();
    bad.cones[0].half_angle = f64::NAN;
    let e = view(&floor, TOP, 0)
        .envelope
        .with_no_return(Some(&bad))
        .unwrap_err();
    assert!(e.to_string().contains("no_return"), "{e}");
}

#[test]
fn unobserved_space_stops_by_policy_and_is_always_flagged() {
    // (Under `ignore`, views combine as if their clouds had seen everything.)
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
    // A coarse top view: the wall's cell reaches past the sphere. The side
    // view's grid is coarse enough that each of its triangles holds wall
    // points (an empty one is space it did not see).
    let (top, side) = (
        view_on_grid(&points, TOP, 8, 0),
        view_on_grid(&points, SIDE, 8, 0),
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
    // 0.05 m stop distance plus 1 m/s for the 1 s maximum age (and no horizon).
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

/// A guard over the top view of the floor and wall whose "tool" link (a
/// sphere 0.5 m out on a revolute joint) is speed-monitored: 1 rad/s at
/// most, braking at 10 rad/s², 50 ms reaction, 0.1 s horizon.
fn monitored_guard() -> CollisionGuard {
    use crate::{
        ArmModel, ArmMotion, Joint, JointKind, JointMotion, Link, SpeedMonitor, StoppingModel,
    };
    let arm = ArmModel::new(
        "arm",
        glam::DAffine3::IDENTITY,
        vec![
            Link {
                name: "base".into(),
                shapes: vec![],
            },
            Link {
                name: "tool".into(),
                shapes: vec![Shape::sphere(DVec3::new(0.5, 0.0, 0.0), 0.05)],
            },
        ],
        vec![Joint::new(
            "turn",
            JointKind::Revolute,
            [0.0, 0.0, 1.0],
            [0.0; 3],
            [0.0; 3],
            None,
        )
        .unwrap()],
    )
    .unwrap();
    let motion = ArmMotion {
        reaction_time: 0.05,
        position_uncertainty: 0.0,
        scale_rise_per_second: 1.0,
        joints: vec![JointMotion {
            max_velocity: 1.0,
            stopping: StoppingModel::Deceleration(10.0),
        }],
    };
    let config = GuardConfig {
        horizon: 0.1,
        ..config()
    };
    let mut g = guard_with(&["top"], GuardPolicy::default(), config)
        .with_speed_monitor(SpeedMonitor::new(&arm, motion).unwrap());
    g.accept(0, view(&floor_and_wall(), TOP, 0), 0, WALL)
        .unwrap();
    g
}

#[test]
fn the_speed_scale_follows_the_separation_and_rises_slowly() {
    let mut g = monitored_guard();
    let at = |h: f64| vec![sphere(1, [-0.5, 0.0, h], 0.05)];
    let still = JointMotionSample::default();
    // Just started, the guard takes full speed as in force (an earlier
    // guard may have allowed it): far away, that still allows full speed.
    let first = g.decide_moving(&at(0.6), still, 0).unwrap();
    assert_eq!(
        (first.verdict, first.speed.scale),
        (GuardVerdict::Clear, 1.0)
    );
    // From rest (once that full speed is out of the window, 0.355 s) with
    // 0.1 m of clearance: 0.55 (0.1 s + s² / 20) <= 0.1 - 0.05 gives s ~ 0.7.
    let near = g.decide_moving(&at(0.15), still, 400 * MS).unwrap();
    assert_eq!(near.verdict, GuardVerdict::Clear, "{}", near.reason);
    assert!(
        near.speed.scale > 0.5 && near.speed.scale < 0.75,
        "{:?}",
        near.speed
    );
    assert_eq!(near.speed.limiting_link, Some(1));
    // Nearer, while the arm may still run at that scale: it cannot stop in
    // time, so the guard stops it and says which link and why.
    let close = g.decide_moving(&at(0.105), still, 410 * MS).unwrap();
    assert_eq!(
        (close.verdict, close.speed.scale),
        (GuardVerdict::Stop, 0.0)
    );
    assert!(close.reason.contains("link tool"), "{}", close.reason);
    // Far: the scale rises by at most 1 per second, then reaches full speed
    // (the view reports up to what scale 1 needs).
    let away = g.decide_moving(&at(0.6), still, 510 * MS).unwrap();
    assert_eq!(away.verdict, GuardVerdict::Clear, "{}", away.reason);
    assert!((away.speed.scale - 0.1).abs() < 1e-9, "{:?}", away.speed);
    g.accept(0, view(&floor_and_wall(), TOP, 0), 2 * S, WALL)
        .unwrap();
    let far = g.decide_moving(&at(0.6), still, 2 * S).unwrap();
    assert_eq!((far.verdict, far.speed.scale), (GuardVerdict::Clear, 1.0));
    assert!(far.speed.limiting_link.is_none());
    // Right after full speed, the same near pose no longer allows moving:
    // the arm may still be at full speed.
    let rushed = g.decide_moving(&at(0.15), still, 2 * S + 10 * MS).unwrap();
    assert_eq!(rushed.verdict, GuardVerdict::Stop, "{}", rushed.reason);
    // A joint measured over its limit is not obeying: stop.
    let fast = [1.2];
    let sample = JointMotionSample {
        velocities: Some(&fast),
        age_ns: 0,
    };
    let over = g.decide_moving(&at(0.6), sample, 2 * S + 20 * MS).unwrap();
    assert_eq!(over.verdict, GuardVerdict::Stop);
    assert!(over.reason.contains("joint turn"), "{}", over.reason);
}
