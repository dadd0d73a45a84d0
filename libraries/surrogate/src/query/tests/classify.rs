//! Every certified cloud point classifies on the side its certificate promises.

use super::fixtures::{assemble, domain, fitted, spheres, terrain, to_dvec, trimmed_surrogate};
use crate::query::{Classify, PointClass, SideView, SurrogateView};
use crate::{Side, Sides, TrimMask};
use glam::DVec3;

fn check_promises(points: &[[f32; 3]], sides: Sides, direction: [f64; 3]) {
    let sur = fitted(points, sides, direction, 16);
    let view = SurrogateView::new(&sur).unwrap();
    for (i, p) in points.iter().enumerate() {
        let class = view.classify(to_dvec(p));
        let kept = match (sides, class) {
            (Sides::Upper, PointClass::Below { gap })
            | (Sides::Lower, PointClass::Above { gap }) => gap > 0.0,
            (
                Sides::Sandwich,
                PointClass::Between {
                    above_lower,
                    below_upper,
                },
            ) => above_lower > 0.0 && below_upper > 0.0,
            _ => false,
        };
        assert!(
            kept,
            "{sides:?} along {direction:?}: point {i} {p:?} is {class:?}"
        );
        // Each side on its own agrees.
        for side in view.sides() {
            let alone = side.classify(to_dvec(p));
            let promised = match side.side() {
                Side::Upper => matches!(alone, PointClass::Below { .. }),
                Side::Lower => matches!(alone, PointClass::Above { .. }),
            };
            assert!(promised, "{:?} alone: point {i} is {alone:?}", side.side());
        }
    }
}

#[test]
fn fitted_terrain_points_are_on_their_promised_sides() {
    let points = terrain(20_000);
    check_promises(&points, Sides::Upper, [0.0, 0.0, -1.0]);
    check_promises(&points, Sides::Lower, [0.0, 0.0, -1.0]);
    check_promises(&points, Sides::Sandwich, [0.3, -0.2, -1.0]);
}

#[test]
fn fitted_sphere_points_are_on_their_promised_sides() {
    let points = spheres(20_000, 1.3);
    check_promises(&points, Sides::Sandwich, [0.0, 0.0, -1.0]);
    check_promises(&points, Sides::Upper, [1.0, 2.0, -0.5]);
}

#[test]
fn points_off_the_domain_or_in_trimmed_triangles_say_so() {
    let sur = trimmed_surrogate();
    let view = SurrogateView::new(&sur).unwrap();
    let at = |s: f64, t: f64, w: f64| {
        let (u, v) = sur.domain.frame_uv(s, t);
        sur.frame.to_world(DVec3::new(u, v, w))
    };
    assert_eq!(view.classify(at(-0.5, 1.0, 0.0)), PointClass::OutsideDomain);
    assert_eq!(view.classify(at(1.0, 2.5, 0.0)), PointClass::OutsideDomain);
    assert_eq!(view.classify(at(0.5, 0.9, 0.0)), PointClass::Trimmed);
    assert!(matches!(
        view.classify(at(0.5, 0.1, 5.0)),
        PointClass::Above { .. }
    ));
    assert!(matches!(
        view.classify(at(0.5, 0.1, -5.0)),
        PointClass::Below { .. }
    ));
}

#[test]
fn sandwich_gaps_are_distances_to_each_surface() {
    let (cols, rows) = (4, 4);
    let sides = [Some(vec![2.0; cols * rows]), Some(vec![-1.0; cols * rows])];
    let sur = assemble(
        [0.0, 0.0, -1.0],
        domain(cols, rows),
        TrimMask::full(3, 3),
        sides,
    );
    let view = SurrogateView::new(&sur).unwrap();
    let (u, v) = sur.domain.frame_uv(1.5, 1.5);
    let at = |w: f64| sur.frame.to_world(DVec3::new(u, v, w));
    assert_eq!(
        view.classify(at(0.5)),
        PointClass::Between {
            above_lower: 1.5,
            below_upper: 1.5
        }
    );
    assert_eq!(view.classify(at(3.0)), PointClass::Above { gap: 1.0 });
    assert_eq!(view.classify(at(-3.0)), PointClass::Below { gap: 2.0 });
    let lower = SideView::new(&sur, Side::Lower).unwrap();
    assert_eq!(lower.classify(at(0.5)), PointClass::Above { gap: 1.5 });
}
