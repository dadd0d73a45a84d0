//! Envelope and clearance on hand-made surrogates: exact answers on flat
//! sandwiches, one-sided surrogates, trimmed cells, refinement, tilted frames,
//! and conservativeness against dense samples of the occupied region.

use super::*;
use glam::DVec3;
use rand::{Rng, SeedableRng};
use shroud_geometry::math::Frame;
use shroud_geometry::spline::UniformCubicSurface;
use shroud_surrogate::trim::{BOTTOM, LEFT};
use shroud_surrogate::{Certificate, Domain, FitStats, SafeSurface, Side, Surrogate, TrimMask};

fn rng(seed: u64) -> rand_pcg::Pcg64 {
    rand_pcg::Pcg64::seed_from_u64(seed)
}

fn safe(side: Side, cols: usize, rows: usize, c: Vec<f64>, frame: &Frame) -> SafeSurface {
    SafeSurface {
        side,
        surface: UniformCubicSurface::new(cols, rows, c).unwrap(),
        certificate: Certificate {
            side,
            direction: frame.direction.to_array(),
            points_checked: 0,
            violations: 0,
            min_gap: 0.0,
            max_gap: 0.0,
            mean_gap: 0.0,
            corrected_points: 0,
        },
    }
}

/// A surrogate over `[0, cols-1] x [0, rows-1]` (unit steps, so frame `(u, v)`
/// equals the parameters), looking along `direction`.
pub(crate) fn surrogate(
    direction: [f64; 3],
    cols: usize,
    rows: usize,
    trim: TrimMask,
    upper: Option<Vec<f64>>,
    lower: Option<Vec<f64>>,
) -> Surrogate {
    let frame = Frame::from_direction(DVec3::from_array(direction)).unwrap();
    Surrogate {
        frame,
        domain: Domain {
            u_min: 0.0,
            v_min: 0.0,
            u_step: 1.0,
            v_step: 1.0,
            cols,
            rows,
        },
        trim,
        upper: upper.map(|c| safe(Side::Upper, cols, rows, c, &frame)),
        lower: lower.map(|c| safe(Side::Lower, cols, rows, c, &frame)),
        stats: FitStats::default(),
    }
}

const DOWN: [f64; 3] = [0.0, 0.0, -1.0];

/// World point of frame coordinates `(u, v, h)` of the frame looking down
/// (`u = -y`, `v = x`, `h = z`).
fn uvh(u: f64, v: f64, h: f64) -> DVec3 {
    Frame::from_direction(DVec3::from_array(DOWN))
        .unwrap()
        .to_world(DVec3::new(u, v, h))
}

fn flat_sandwich(trim: TrimMask) -> Surrogate {
    surrogate(DOWN, 5, 5, trim, Some(vec![1.0; 25]), Some(vec![0.0; 25]))
}

fn config(stop: f64, max_report: f64, depth: u32) -> GuardConfig {
    GuardConfig {
        stop_distance: stop,
        max_report,
        refine_depth: depth,
        max_obstacle_speed: 0.0,
        horizon: 0.0,
    }
}

/// Equal up to the padding (the domain slack is 1e-9 parameter units).
fn near(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-8
}

#[test]
fn flat_sandwich_distances_are_exact() {
    let env = Envelope::new(&flat_sandwich(TrimMask::full(4, 4))).unwrap();
    assert_eq!((env.cells(), env.kept_cells()), ((4, 4), 16));
    let cfg = config(0.1, 2.0, 3);
    let c = |x: f64, y: f64, z: f64, r: f64| env.sphere_clearance(uvh(x, y, z), r, &cfg).unwrap();
    assert!(near(c(2.0, 2.0, 3.0, 0.5), 1.5));
    assert!(near(c(2.0, 2.0, -1.0, 0.25), 0.75));
    assert_eq!(c(2.0, 2.0, 0.5, 0.01), 0.0, "inside the slab");
    assert_eq!(c(2.0, 2.0, 1.2, 0.25), 0.0, "overlapping the top");
    // Beside the domain: horizontal distance to its edge.
    assert!(near(c(-1.0, 2.0, 0.5, 0.5), 0.5));
    assert!(near(c(5.0, 5.0, 0.5, 0.1), 2f64.sqrt() - 0.1));
    // Capped far away, also when the footprint misses the domain entirely.
    assert_eq!(c(2.0, 2.0, 30.0, 0.5), 2.0);
    assert_eq!(c(100.0, 2.0, 0.5, 0.5), 2.0);
    // A capsule lying flat above the slab, and one crossing it.
    let cap = |a: [f64; 3], b: [f64; 3], r: f64| {
        env.capsule_clearance(uvh(a[0], a[1], a[2]), uvh(b[0], b[1], b[2]), r, &cfg)
            .unwrap()
    };
    assert!(near(cap([0.5, 0.5, 1.7], [3.5, 3.0, 1.7], 0.2), 0.5));
    assert_eq!(cap([2.0, 2.0, 3.0], [2.0, 2.0, -3.0], 0.01), 0.0);
    assert!(near(cap([-2.0, 2.0, 0.5], [-1.0, 2.0, 0.8], 0.5), 0.5));
    // Rising beside the slab: (u, h) = (-2 + x, 0.5 + 2.5 x), closest at x = 6.5 / 14.5.
    let x: f64 = 6.5 / 14.5;
    let exact = ((2.0 - x) * (2.0 - x) + (2.5 * x - 0.5) * (2.5 * x - 0.5)).sqrt() - 0.5;
    assert!(near(cap([-2.0, 2.0, 0.5], [-1.0, 2.0, 3.0], 0.5), exact));
}

#[test]
fn one_sided_surrogates_occupy_a_half_space_over_the_domain() {
    let up = surrogate(DOWN, 5, 5, TrimMask::full(4, 4), Some(vec![1.0; 25]), None);
    let low = surrogate(DOWN, 5, 5, TrimMask::full(4, 4), None, Some(vec![0.0; 25]));
    let (up, low) = (Envelope::new(&up).unwrap(), Envelope::new(&low).unwrap());
    assert!(up.has_upper() && !up.has_lower() && low.has_lower() && !low.has_upper());
    let cfg = GuardConfig::default();
    let deep = uvh(2.0, 2.0, -1e6);
    let high = uvh(2.0, 2.0, 1e6);
    assert_eq!(up.sphere_clearance(deep, 0.1, &cfg).unwrap(), 0.0);
    assert_eq!(
        up.sphere_clearance(high, 0.1, &cfg).unwrap(),
        cfg.max_report
    );
    assert!(near(
        up.sphere_clearance(uvh(2.0, 2.0, 1.3), 0.1, &cfg).unwrap(),
        0.2
    ));
    assert_eq!(low.sphere_clearance(high, 0.1, &cfg).unwrap(), 0.0);
    assert!(near(
        low.sphere_clearance(uvh(2.0, 2.0, -0.3), 0.1, &cfg)
            .unwrap(),
        0.2
    ));
    // Outside the domain nothing is represented.
    let beside = uvh(-3.0, 2.0, -1e6);
    assert_eq!(
        up.sphere_clearance(beside, 0.1, &cfg).unwrap(),
        cfg.max_report
    );
}

#[test]
fn trimmed_cells_and_triangles_hold_nothing() {
    let mut trim = TrimMask::full(4, 4);
    trim.bits[4 + 1] = 0; // cell (1, 1) empty
    let env = Envelope::new(&flat_sandwich(trim)).unwrap();
    let cfg = config(0.05, 2.0, 4);
    // In the middle of the empty cell, inside the slab's height: 0.5 to its walls.
    let hole = env.sphere_clearance(uvh(1.5, 1.5, 0.5), 0.1, &cfg).unwrap();
    assert!(near(hole, 0.4), "{hole}");

    // Only cell (2, 1) is kept, and of it only the bottom and left triangles
    // (below the anti-diagonal): its bounding rectangle is the whole cell, so
    // the coarse bound is 0, but the sphere sits over the trimmed part.
    let mut trim = TrimMask::empty(4, 4);
    trim.bits[4 + 2] = BOTTOM | LEFT;
    let env = Envelope::new(&flat_sandwich(trim)).unwrap();
    let centre = uvh(2.8, 1.75, 0.5);
    let exact = (0.8 + 0.75 - 1.0) / 2f64.sqrt() - 0.05;
    let coarse = env
        .sphere_clearance(centre, 0.05, &config(0.05, 2.0, 0))
        .unwrap();
    let fine = env.sphere_clearance(centre, 0.05, &cfg).unwrap();
    assert_eq!(coarse, 0.0);
    assert!(
        fine > 0.0 && fine <= exact + 1e-12,
        "{fine} vs exact {exact}"
    );
    // Refined until it is decided: clear of a stop distance just below the truth.
    let finer = env
        .sphere_clearance(centre, 0.05, &config(0.3, 2.0, 6))
        .unwrap();
    assert!(
        finer > fine && finer <= exact + 1e-12 && finer >= 0.3,
        "{finer}"
    );
}

/// Samples of the occupied region: parameters in kept closed triangles, heights
/// between the surfaces (or up to `depth` beyond a lone surface).
fn occupied_samples(sur: &Surrogate, n: usize, seed: u64) -> Vec<DVec3> {
    let mut r = rng(seed);
    let (cs, ct) = (sur.trim.cells_s as f64, sur.trim.cells_t as f64);
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let (s, t): (f64, f64) = (r.random_range(0.0..=cs), r.random_range(0.0..=ct));
        if !shroud_surrogate::query::kept_closed(&sur.trim, s, t) {
            continue;
        }
        let up = sur.upper.as_ref().map(|x| x.surface.eval(s, t));
        let low = sur.lower.as_ref().map(|x| x.surface.eval(s, t));
        let (lo, hi) = match (low, up) {
            (Some(l), Some(u)) => (l, u),
            (Some(l), None) => (l, l + 3.0),
            (None, Some(u)) => (u - 3.0, u),
            (None, None) => unreachable!(),
        };
        if hi < lo {
            continue;
        }
        let w = lo + (hi - lo) * r.random_range(0.0..=1.0);
        let (u, v) = sur.domain.frame_uv(s, t);
        out.push(sur.frame.to_world(DVec3::new(u, v, w)));
    }
    out
}

/// A random grid of 3 to 7 control points a side and a viewing direction
/// that looks down more than sideways.
fn random_grid(r: &mut rand_pcg::Pcg64) -> (usize, usize, [f64; 3]) {
    let (cols, rows) = (r.random_range(3..8), r.random_range(3..8));
    let direction = [
        r.random_range(-1.0..1.0),
        r.random_range(-1.0..1.0),
        r.random_range(-1.0..-0.2),
    ];
    (cols, rows, direction)
}

/// Random bumpy surfaces in tilted frames: every reported clearance is at most
/// the distance to every sampled occupied point, and refinement only raises it.
#[test]
fn clearances_never_exceed_sampled_distances() {
    let mut r = rng(21);
    for case in 0..12 {
        let (cols, rows, direction) = random_grid(&mut r);
        let n = cols * rows;
        let low: Vec<f64> = (0..n).map(|_| r.random_range(-1.0..0.0)).collect();
        let up: Vec<f64> = low.iter().map(|l| l + r.random_range(0.0..1.0)).collect();
        let mut trim = TrimMask::full(cols - 1, rows - 1);
        trim.bits
            .iter_mut()
            .for_each(|b| *b = r.random_range(0..16));
        let sides = match case % 3 {
            0 => (Some(up), Some(low)),
            1 => (Some(up), None),
            _ => (None, Some(low)),
        };
        if trim.kept_triangles() == 0 {
            continue;
        }
        let sur = surrogate(direction, cols, rows, trim, sides.0, sides.1);
        let env = Envelope::new(&sur).unwrap();
        let samples = occupied_samples(&sur, 4000, case);
        for _ in 0..60 {
            let centre = sur.frame.to_world(DVec3::new(
                r.random_range(-1.0..cols as f64),
                r.random_range(-1.0..rows as f64),
                r.random_range(-2.5..2.5),
            ));
            let radius = r.random_range(0.01..0.6);
            let shape = if r.random_bool(0.3) {
                let d = DVec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                );
                Shape::capsule(centre, centre + d, radius)
            } else {
                Shape::sphere(centre, radius)
            };
            let truth = samples
                .iter()
                .map(|p| shape.distance_to(*p).max(0.0))
                .fold(f64::INFINITY, f64::min);
            let mut last = 0.0;
            for depth in 0..=4 {
                let cfg = config(0.3, 1.0, depth);
                let c = env.shape_clearance(&shape, &cfg).unwrap();
                assert!(
                    c <= truth + 1e-12,
                    "case {case} depth {depth}: {c} > sampled {truth}"
                );
                assert!(
                    c >= last - 1e-12,
                    "refinement lowered the bound: {c} < {last}"
                );
                last = c;
            }
        }
    }
}

/// Counting unseen space first (the guard's `UnobservedPolicy::Stop`) and
/// searching occupied space only up to it never raises a clearance, and
/// where the clearance reaches the stop distance it and its cause are the
/// same as with the full search.
#[test]
fn searching_occupied_space_up_to_the_unseen_bound_keeps_every_clear_answer() {
    let mut r = rng(33);
    let (mut compared, mut far) = (0, 0);
    for case in 0..40 {
        let (cols, rows, direction) = random_grid(&mut r);
        let n = cols * rows;
        let up: Vec<f64> = (0..n).map(|_| r.random_range(-1.0..0.0)).collect();
        let mut trim = TrimMask::full(cols - 1, rows - 1);
        trim.bits.iter_mut().for_each(|b| {
            *b = if r.random_bool(0.8) {
                15
            } else {
                r.random_range(0..16)
            }
        });
        if trim.kept_triangles() == 0 {
            continue;
        }
        let sur = surrogate(direction, cols, rows, trim, Some(up), None);
        let env = Envelope::new(&sur).unwrap();
        let shapes: Vec<WorldShape> = (0..50)
            .map(|_| {
                let centre = sur.frame.to_world(DVec3::new(
                    r.random_range(-2.0..cols as f64 + 1.0),
                    r.random_range(-2.0..rows as f64 + 1.0),
                    r.random_range(-1.5..1.5),
                ));
                WorldShape {
                    link: 0,
                    shape: Shape::sphere(centre, r.random_range(0.01..0.3)),
                }
            })
            .collect();
        let cfg = config(0.2, 1.0, 3);
        let full = check_shapes(&env, &shapes, 1, &cfg).unwrap();
        let counted = crate::report::check_shapes_counting(&env, &shapes, 1, &cfg, true).unwrap();
        for (a, b) in full.shapes.iter().zip(&counted.shapes) {
            assert!(
                b.clearance <= a.clearance + 1e-12,
                "case {case}: {b:?} > {a:?}"
            );
            assert_eq!(a.unseen, b.unseen);
            if a.clearance >= cfg.stop_distance {
                assert_eq!((a.clearance, a.unobserved), (b.clearance, b.unobserved));
                far += 1;
            }
            compared += 1;
        }
    }
    assert!(far > 100 && far < compared, "{far} of {compared}");
}

#[test]
fn refinement_tightens_a_bumpy_cell() {
    // One tall coefficient in the middle: the cell boxes around it are tall,
    // the surface itself falls off quickly.
    let mut up = vec![0.0; 36];
    up[2 * 6 + 2] = 6.0;
    let sur = surrogate(DOWN, 6, 6, TrimMask::full(5, 5), Some(up), None);
    let env = Envelope::new(&sur).unwrap();
    let centre = uvh(0.2, 0.2, 1.0);
    let coarse = env
        .sphere_clearance(centre, 0.1, &config(2.0, 2.0, 0))
        .unwrap();
    let fine = env
        .sphere_clearance(centre, 0.1, &config(2.0, 2.0, 4))
        .unwrap();
    assert!(coarse < fine, "coarse {coarse} fine {fine}");
}

#[test]
fn bad_inputs_are_refused() {
    let env = Envelope::new(&flat_sandwich(TrimMask::full(4, 4))).unwrap();
    let cfg = GuardConfig::default();
    assert!(env.sphere_clearance(DVec3::NAN, 0.1, &cfg).is_err());
    assert!(env.sphere_clearance(DVec3::ZERO, 0.0, &cfg).is_err());
    assert!(env
        .sphere_clearance(DVec3::ZERO, 0.1, &config(1.0, 0.5, 1))
        .is_err());
    let mut broken = flat_sandwich(TrimMask::full(4, 4));
    broken.trim = TrimMask::full(3, 4);
    assert!(matches!(
        Envelope::new(&broken),
        Err(GuardError::Surrogate(_))
    ));
    let mut skewed = flat_sandwich(TrimMask::full(4, 4));
    skewed.frame.u *= 1.001;
    assert!(matches!(
        Envelope::new(&skewed),
        Err(GuardError::Surrogate(_))
    ));
    let mut nan = flat_sandwich(TrimMask::full(4, 4));
    if let Some(u) = nan.upper.as_mut() {
        u.surface.coefficients[3] = f64::NAN;
    }
    assert!(Envelope::new(&nan).is_err());
    let shapes = [WorldShape {
        link: 2,
        shape: Shape::sphere(DVec3::ZERO, 0.1),
    }];
    assert!(matches!(
        check_shapes(&env, &shapes, 2, &cfg),
        Err(GuardError::ShapeLink { .. })
    ));
}

#[test]
fn report_summarises_links_and_stop() {
    let env = Envelope::new(&flat_sandwich(TrimMask::full(4, 4))).unwrap();
    let cfg = config(0.1, 1.0, 2);
    let at = |link, z: f64| WorldShape {
        link,
        shape: Shape::sphere(uvh(2.0, 2.0, z), 0.1),
    };
    let shapes = [at(0, 2.0), at(2, 1.4), at(2, 1.15)];
    let report = check_shapes(&env, &shapes, 3, &cfg).unwrap();
    assert_eq!(report.links.len(), 3);
    assert!(near(report.links[0], 0.9));
    assert_eq!(
        report.links[1], 1.0,
        "a link without shapes reports max_report"
    );
    assert!(near(report.links[2], 0.05));
    assert_eq!(
        (report.closest_link, report.closest_shape),
        (Some(2), Some(2))
    );
    assert!(report.stop && !report.unobserved);
    let clear = check_shapes(&env, &shapes[..2], 3, &cfg).unwrap();
    assert!(!clear.stop);
    let merged = clear
        .merged(&check_shapes(&env, &shapes[..2], 3, &cfg).unwrap(), &cfg)
        .unwrap();
    assert_eq!(merged, clear);
    // Contact stops even with a zero stop distance.
    let touching = check_shapes(&env, &[at(0, 1.05)], 1, &config(0.0, 1.0, 2)).unwrap();
    assert!(touching.stop && touching.min_clearance == 0.0);
    let empty = check_shapes(&env, &[], 1, &cfg).unwrap();
    assert_eq!(
        (empty.min_clearance, empty.closest_link, empty.stop),
        (1.0, None, false)
    );
    // High above the middle: nearer the domain's border (2 m away) than the
    // surface, so the bound is set by the space the view did not see.
    let edge = check_shapes(&env, &[at(0, 5.0)], 1, &config(0.1, 3.0, 1)).unwrap();
    let shape = edge.shapes[0];
    assert!(
        shape.unobserved && shape.unseen < shape.occupied,
        "{shape:?}"
    );
    assert!(near(edge.min_clearance, shape.unseen) && !edge.stop);
}
