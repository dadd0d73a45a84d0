//! Ray casting against brute-force marching and hand-made edge cases: grazing
//! rays, rays from below, vertical rays, rays off the domain, trimmed parts.

use super::fixtures::{assemble, domain, fitted, random_coefficients, random_trim, rng, terrain};
use crate::query::{
    first_hit_any, kept_closed, HeightQuery, QueryError, Ray, RayCast, RayHit, SideView,
};
use crate::trim::ALL;
use crate::{Side, Sides, Surrogate, TrimMask};
use glam::DVec3;
use rand::Rng;

/// First sample distance after which `f - w` changes sign (or is zero) between
/// two consecutive samples on the kept surface (with the step between them kept
/// too, as far as three inner probes can tell).
fn march(view: &SideView, ray: &Ray, max: f64, steps: usize) -> Option<f64> {
    let d = ray.direction.normalize();
    let step = max / steps as f64;
    let gap_at = |lambda: f64| {
        let (s, t, w) = view.locate(ray.origin + d * lambda);
        view.height_at_param(s, t).map(|f| f - w)
    };
    let mut previous: Option<f64> = None;
    for i in 0..=steps {
        let lambda = step * i as f64;
        let gap = gap_at(lambda);
        if let (Some(a), Some(b)) = (previous, gap) {
            let inner_kept = [0.25, 0.5, 0.75]
                .iter()
                .all(|x| gap_at(lambda - step * x).is_some());
            if inner_kept && (b == 0.0 || (a > 0.0) != (b > 0.0)) {
                return Some(lambda);
            }
        }
        previous = gap;
    }
    None
}

/// A reported hit lies on the kept surface, at the ray's point.
fn check_hit_is_real(view: &SideView, ray: &Ray, hit: &RayHit) {
    let expected = ray.origin + ray.direction.normalize() * hit.distance;
    assert!((hit.point - expected).length() < 1e-12 * (1.0 + hit.distance));
    let (s, t, w) = view.locate(hit.point);
    assert!((s - hit.s).abs() < 1e-9 && (t - hit.t).abs() < 1e-9);
    let f = view.surface().eval(hit.s, hit.t);
    assert!((f - w).abs() < 1e-9, "residual {} at {hit:?}", f - w);
    let near_kept = [
        (0.0, 0.0),
        (1e-9, 0.0),
        (-1e-9, 0.0),
        (0.0, 1e-9),
        (0.0, -1e-9),
    ]
    .iter()
    .any(|(a, b)| kept_closed(view.trim(), hit.s + a, hit.t + b));
    assert!(near_kept, "hit on a trimmed part: {hit:?}");
    assert!((hit.normal.length() - 1.0).abs() < 1e-12 && hit.normal.dot(view.frame().w) > 0.0);
}

/// Random rays around the domain: never miss what marching finds, and every hit
/// is real. Returns (hits, misses).
fn random_rays_agree_with_marching(
    sur: &Surrogate,
    side: Side,
    seed: u64,
    rays: usize,
) -> (usize, usize) {
    let view = SideView::new(sur, side).unwrap();
    let d = &sur.domain;
    let (u1, v1) = d.frame_uv((d.cols - 1) as f64, (d.rows - 1) as f64);
    let (span_u, span_v) = (u1 - d.u_min, v1 - d.v_min);
    let coefficients = &view.surface().coefficients;
    let (lo, hi) = coefficients
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &c| {
            (a.min(c), b.max(c))
        });
    let mut r = rng(seed);
    let max = 2.0 * (span_u + span_v);
    let (mut hits, mut misses) = (0, 0);
    for _ in 0..rays {
        let local = DVec3::new(
            d.u_min + r.random_range(-0.2..1.2) * span_u,
            d.v_min + r.random_range(-0.2..1.2) * span_v,
            r.random_range(lo - 0.5..hi + 0.5),
        );
        let dir = DVec3::new(
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
            r.random_range(-1.0..1.0),
        );
        let ray = Ray {
            origin: sur.frame.to_world(local),
            direction: sur.frame.to_world(dir),
        };
        let hit = view.first_hit(&ray, max).unwrap();
        let marched = march(&view, &ray, max, 20_000);
        if let Some(m) = marched {
            let h = hit.unwrap_or_else(|| panic!("missed a crossing near {m}: {ray:?}"));
            assert!(
                h.distance <= m + 1e-9,
                "hit at {} after the marched crossing at {m}",
                h.distance
            );
        }
        match hit {
            Some(h) => {
                check_hit_is_real(&view, &ray, &h);
                // Random rays cross rather than touch: the sign changes at the hit.
                let dir = ray.direction.normalize();
                let gap = |l: f64| {
                    let (s, t, w) = view.locate(ray.origin + dir * l);
                    view.surface().eval(s, t) - w
                };
                let (before, after) = (gap(h.distance - 1e-7), gap(h.distance + 1e-7));
                assert!(
                    (before > 0.0) != (after > 0.0),
                    "no sign change at {h:?}: {before} {after}"
                );
                hits += 1;
            }
            None => misses += 1,
        }
    }
    (hits, misses)
}

#[test]
fn random_rays_on_random_trimmed_surfaces_match_marching() {
    for (seed, direction) in [
        (1, [0.0, 0.0, -1.0]),
        (2, [1.0, 2.0, -3.0]),
        (3, [-0.3, 0.9, 0.2]),
    ] {
        let (cols, rows) = (7, 6);
        let trim = if seed == 1 {
            TrimMask::full(cols - 1, rows - 1)
        } else {
            random_trim(cols - 1, rows - 1, seed)
        };
        let sur = assemble(
            direction,
            domain(cols, rows),
            trim,
            [Some(random_coefficients(cols * rows, seed)), None],
        );
        let (hits, misses) = random_rays_agree_with_marching(&sur, Side::Upper, seed + 10, 300);
        assert!(
            hits > 20 && misses > 20,
            "seed {seed}: {hits} hits, {misses} misses"
        );
    }
}

#[test]
fn random_rays_on_a_fitted_terrain_match_marching() {
    let sur = fitted(&terrain(20_000), Sides::Sandwich, [0.0, 0.0, -1.0], 20);
    for side in [Side::Upper, Side::Lower] {
        let (hits, misses) = random_rays_agree_with_marching(&sur, side, 5, 150);
        assert!(
            hits > 20 && misses > 5,
            "{side:?}: {hits} hits, {misses} misses"
        );
    }
}

/// 7 x 7 grid, one unit coefficient in the middle: a bump of height 4/9 at (3, 3).
fn bump() -> Surrogate {
    let mut c = vec![0.0; 49];
    c[3 * 7 + 3] = 1.0;
    assemble(
        [0.0, 0.0, -1.0],
        domain(7, 7),
        TrimMask::full(6, 6),
        [Some(c), None],
    )
}

fn world(sur: &Surrogate, s: f64, t: f64, w: f64) -> DVec3 {
    let (u, v) = sur.domain.frame_uv(s, t);
    sur.frame.to_world(DVec3::new(u, v, w))
}

#[test]
fn grazing_rays_touching_the_top_are_hits_and_near_misses_are_not() {
    let sur = bump();
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let top = view.surface().eval(3.0, 3.0);
    assert!((top - 4.0 / 9.0).abs() < 1e-15);
    let along_s = sur.frame.u;
    let start = |w: f64| Ray {
        origin: world(&sur, -1.0, 3.0, w),
        direction: along_s,
    };
    let to_top = 4.0 * sur.domain.u_step;
    let touch = view
        .first_hit(&start(top), 10.0)
        .unwrap()
        .expect("a tangential touch is a hit");
    assert!(
        (touch.distance - to_top).abs() < 1e-6,
        "touch at {}, top at {to_top}",
        touch.distance
    );
    assert!(
        touch.distance <= to_top + 1e-12,
        "never later than the true touch"
    );
    assert_eq!(view.first_hit(&start(top + 1e-6), 10.0).unwrap(), None);
    let cut = view.first_hit(&start(top - 1e-6), 10.0).unwrap().unwrap();
    assert!(cut.distance < to_top && to_top - cut.distance < 1e-2);
    check_hit_is_real(&view, &start(top - 1e-6), &cut);
}

#[test]
fn a_ray_lying_in_a_flat_surface_hits_where_it_enters() {
    let sur = assemble(
        [0.0, 0.0, -1.0],
        domain(5, 5),
        TrimMask::full(4, 4),
        [Some(vec![0.25; 25]), None],
    );
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let ray = Ray {
        origin: world(&sur, -2.0, 1.3, 0.25),
        direction: sur.frame.u,
    };
    let hit = view.first_hit(&ray, 10.0).unwrap().unwrap();
    assert!((hit.distance - 2.0 * sur.domain.u_step).abs() < 1e-9);
}

#[test]
fn rays_from_below_cross_upward_and_miss_downward() {
    let sur = bump();
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let origin = world(&sur, 3.0, 3.0, -1.0);
    let up = Ray {
        origin,
        direction: sur.frame.to_world(DVec3::new(0.2, 0.1, 1.0)),
    };
    let hit = view.first_hit(&up, 10.0).unwrap().unwrap();
    check_hit_is_real(&view, &up, &hit);
    assert_eq!(
        march(&view, &up, 10.0, 100_000).map(|m| (m - hit.distance).abs() < 1e-3),
        Some(true)
    );
    let down = Ray {
        origin,
        direction: sur.frame.to_world(DVec3::new(0.2, 0.1, -1.0)),
    };
    assert_eq!(view.first_hit(&down, 10.0).unwrap(), None);
}

#[test]
fn vertical_rays_are_height_tests() {
    for direction in [[0.0, 0.0, -1.0], [1.0, 2.0, -3.0]] {
        let sur = assemble(
            direction,
            domain(6, 6),
            random_trim(5, 5, 4),
            [Some(random_coefficients(36, 4)), None],
        );
        let view = SideView::new(&sur, Side::Upper).unwrap();
        let mut tested = 0;
        for (i, j) in (0..40).map(|k| (k % 8, k / 8)) {
            // Off the diagonals: there a nearly vertical ray may see one triangle only.
            let (s, t) = (0.33 + 0.6 * i as f64, 0.21 + 1.1 * j as f64);
            let down = Ray {
                origin: world(&sur, s, t, 5.0),
                direction: -sur.frame.w,
            };
            let up = Ray {
                origin: world(&sur, s, t, -5.0),
                direction: sur.frame.w,
            };
            match view.height_at_param(s, t) {
                Some(f) => {
                    let hit = view.first_hit(&down, 20.0).unwrap().unwrap();
                    assert!((hit.distance - (5.0 - f)).abs() < 1e-9);
                    let hit = view.first_hit(&up, 20.0).unwrap().unwrap();
                    assert!((hit.distance - (5.0 + f)).abs() < 1e-9);
                    assert_eq!(
                        view.first_hit(&down, 5.0 - f - 1e-6).unwrap(),
                        None,
                        "out of reach"
                    );
                    let away = Ray {
                        origin: down.origin,
                        direction: sur.frame.w,
                    };
                    assert_eq!(view.first_hit(&away, 20.0).unwrap(), None);
                    tested += 1;
                }
                None => assert_eq!(
                    view.first_hit(&down, 20.0).unwrap(),
                    None,
                    "trimmed at ({s}, {t})"
                ),
            }
        }
        assert!(tested > 5 && tested < 40);
    }
}

#[test]
fn rays_outside_the_domain_miss() {
    let sur = bump();
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let beside = Ray {
        origin: world(&sur, -1.0, 7.5, 0.0),
        direction: sur.frame.u,
    };
    assert_eq!(view.first_hit(&beside, 100.0).unwrap(), None);
    let away = Ray {
        origin: world(&sur, -1.0, 3.0, 0.0),
        direction: -sur.frame.u,
    };
    assert_eq!(view.first_hit(&away, 100.0).unwrap(), None);
    let vertical_outside = Ray {
        origin: world(&sur, 8.0, 3.0, 5.0),
        direction: -sur.frame.w,
    };
    assert_eq!(view.first_hit(&vertical_outside, 100.0).unwrap(), None);
}

#[test]
fn rays_crossing_only_trimmed_parts_miss() {
    // A tilted plane w = s - 1 (inside the spline's linear-reproduction zone),
    // crossed by a slanted ray above cell (1, 1) at s = 1.5.
    let (cols, rows) = (5, 5);
    let plane: Vec<f64> = (0..cols * rows).map(|i| (i % cols) as f64 - 1.0).collect();
    // From (1.35, 1.3) at height 2, s grows 0.1 per unit of descent: it meets
    // w = s - 1 at (1.5, 1.3), inside the bottom triangle of cell (1, 1).
    let ray_for = |sur: &Surrogate| Ray {
        origin: world(sur, 1.35, 1.3, 2.0),
        direction: sur
            .frame
            .to_world(DVec3::new(0.1 * sur.domain.u_step, 0.0, -1.0)),
    };
    let mut trim = TrimMask::full(cols - 1, rows - 1);
    let full = assemble(
        [0.0, 0.0, -1.0],
        domain(cols, rows),
        trim.clone(),
        [Some(plane.clone()), None],
    );
    let hit = SideView::new(&full, Side::Upper)
        .unwrap()
        .first_hit(&ray_for(&full), 10.0)
        .unwrap()
        .unwrap();
    assert!(
        (hit.s - 1.5).abs() < 1e-9 && (hit.t - 1.3).abs() < 1e-9,
        "{hit:?}"
    );
    trim.bits[4 + 1] = 0; // cell (1, 1) trimmed entirely
    let holed = assemble(
        [0.0, 0.0, -1.0],
        domain(cols, rows),
        trim.clone(),
        [Some(plane.clone()), None],
    );
    assert_eq!(
        SideView::new(&holed, Side::Upper)
            .unwrap()
            .first_hit(&ray_for(&holed), 10.0)
            .unwrap(),
        None
    );
    // Keeping only the triangle the crossing is in brings the hit back.
    trim.bits[4 + 1] = crate::trim::triangle_of(hit.s - 1.0, hit.t - 1.0);
    let one = assemble(
        [0.0, 0.0, -1.0],
        domain(cols, rows),
        trim.clone(),
        [Some(plane.clone()), None],
    );
    let again = SideView::new(&one, Side::Upper)
        .unwrap()
        .first_hit(&ray_for(&one), 10.0)
        .unwrap()
        .unwrap();
    assert!((again.distance - hit.distance).abs() < 1e-12);
    trim.bits[4 + 1] = ALL & !trim.bits[4 + 1];
    let others = assemble(
        [0.0, 0.0, -1.0],
        domain(cols, rows),
        trim,
        [Some(plane), None],
    );
    assert_eq!(
        SideView::new(&others, Side::Upper)
            .unwrap()
            .first_hit(&ray_for(&others), 10.0)
            .unwrap(),
        None
    );
}

#[test]
fn normals_of_a_tilted_plane_point_toward_the_viewer() {
    let (cols, rows) = (6, 6);
    let plane: Vec<f64> = (0..cols * rows).map(|i| 0.5 * (i % cols) as f64).collect();
    let sur = assemble(
        [1.0, 2.0, -3.0],
        domain(cols, rows),
        TrimMask::full(5, 5),
        [Some(plane), None],
    );
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let ray = Ray {
        origin: world(&sur, 2.5, 2.5, 9.0),
        direction: -sur.frame.w,
    };
    let hit = view.first_hit(&ray, 20.0).unwrap().unwrap();
    let slope = 0.5 / sur.domain.u_step;
    let expected = (sur.frame.w - sur.frame.u * slope).normalize();
    assert!(
        (hit.normal - expected).length() < 1e-12,
        "{:?} vs {expected:?}",
        hit.normal
    );
}

#[test]
fn any_side_reports_the_nearest_surface_of_a_sandwich() {
    let sides = [Some(vec![1.0; 16]), Some(vec![-1.0; 16])];
    let sur = assemble([0.0, 0.0, -1.0], domain(4, 4), TrimMask::full(3, 3), sides);
    let down = |w: f64| Ray {
        origin: world(&sur, 1.5, 1.5, w),
        direction: -sur.frame.w,
    };
    let hit = first_hit_any(&sur, &down(3.0), 10.0).unwrap().unwrap();
    assert_eq!(hit.side, Side::Upper);
    assert!((hit.distance - 2.0).abs() < 1e-12);
    let hit = first_hit_any(&sur, &down(0.0), 10.0).unwrap().unwrap();
    assert_eq!(hit.side, Side::Lower);
    assert!((hit.distance - 1.0).abs() < 1e-12);
    let up = Ray {
        origin: world(&sur, 1.5, 1.5, 0.0),
        direction: sur.frame.w,
    };
    assert_eq!(
        first_hit_any(&sur, &up, 10.0).unwrap().unwrap().side,
        Side::Upper
    );
    assert_eq!(first_hit_any(&sur, &down(3.0), 1.5).unwrap(), None);
}

#[test]
fn malformed_rays_are_errors() {
    let sur = bump();
    let view = SideView::new(&sur, Side::Upper).unwrap();
    let ok = Ray {
        origin: DVec3::ZERO,
        direction: DVec3::X,
    };
    assert!(matches!(
        view.first_hit(
            &Ray {
                direction: DVec3::ZERO,
                ..ok
            },
            1.0
        ),
        Err(QueryError::BadRayDirection(..))
    ));
    let nan = Ray {
        origin: DVec3::new(f64::NAN, 0.0, 0.0),
        ..ok
    };
    assert!(matches!(
        view.first_hit(&nan, 1.0),
        Err(QueryError::BadRayOrigin(..))
    ));
    assert!(matches!(
        view.first_hit(&ok, -1.0),
        Err(QueryError::BadMaxDistance(_))
    ));
    assert!(matches!(
        view.first_hit(&ok, f64::INFINITY),
        Err(QueryError::BadMaxDistance(_))
    ));
}
