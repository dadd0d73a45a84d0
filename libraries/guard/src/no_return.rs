//! Distance from a shape to the directions in which a view's sensor got no
//! return.
//!
//! A black object returns no range, and the surface fitted around it is
//! interpolated from the returns of its neighbours (a floor behind it, say),
//! so a kept triangle can vouch for space the object fills. When the cloud
//! lists the directions that came back empty ([`NoReturn`]), every one of
//! them is unseen from the apex outwards: the guard's bound is the distance to
//! the nearest such cone.
//!
//! Each cone `K` (apex `a`, unit axis `u`, half angle `alpha < pi/2`) is
//! convex. For a point at distance `L` from the apex, at angle `theta` from
//! the axis, the distance to `K` is 0 when `theta <= alpha`, `L` when
//! `theta >= alpha + pi/2` (the apex is nearest), and `L sin(theta - alpha)`
//! between, which is `across cos(alpha) - along sin(alpha)` with `along` and
//! `across` the point's components along and off the axis. Cones are not cut
//! at the range (nearer bounds, never farther). The distance to a convex set
//! is convex and 1-Lipschitz along a capsule's segment, so a golden-section
//! search brackets its minimum, and the bracket's half width bounds the
//! error from below.

use super::dark_groups::{
    cone_distance, cone_distance_and_side, cone_distance_at, cone_tree, tree_depth, Cone, ConeNode,
    ROUNDING_REL,
};
use super::shape::Shape;
use glam::DVec3;
use shroud_msg::NoReturn;

/// Nodes a sphere's search of the tree holds at once: one more than the
/// tree's depth at most (a deeper tree, of millions of cones, is searched
/// cone by cone instead).
const STACK: usize = 24;

/// Golden-section steps on a capsule's segment: the bracket shrinks to
/// 0.618^40 (about 4e-9) of the segment.
const SEARCH_STEPS: usize = 40;

/// A [`NoReturn`] ready for distance queries: unit axes and the sine and
/// cosine of every half angle.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DarkCones {
    apex: DVec3,
    /// Axis (renormalised: the wire allows 1e-6 off unit), `sin`, `cos`.
    cones: Vec<Cone>,
    /// The cones gathered by direction (in the tree's order), the tree
    /// over them (`guard::dark_groups`) and its depth, for spheres.
    sorted: Vec<Cone>,
    tree: Vec<ConeNode>,
    depth: usize,
}

impl DarkCones {
    pub(crate) fn new(no_return: &NoReturn) -> Self {
        let cones: Vec<Cone> = no_return
            .cones
            .iter()
            .map(|c| {
                let (sin, cos) = c.half_angle.sin_cos();
                (DVec3::from_array(c.axis).normalize(), sin, cos)
            })
            .collect();
        let (order, tree) = cone_tree(&cones);
        Self {
            apex: DVec3::from_array(no_return.apex),
            sorted: order.iter().map(|&k| cones[k]).collect(),
            depth: tree_depth(&tree),
            cones,
            tree,
        }
    }

    /// Distance from `p` to cone `k`.
    fn distance(&self, k: usize, p: DVec3) -> f64 {
        cone_distance(self.apex, self.cones[k], p)
    }

    /// Lower bound on the distance from segment `a`-`b` to cone `k`
    /// (golden-section search of a convex, 1-Lipschitz function).
    fn segment_distance(&self, k: usize, a: DVec3, b: DVec3) -> f64 {
        let length = (b - a).length();
        let f = |t: f64| self.distance(k, a + (b - a) * t);
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        let (mut x1, mut x2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
        let (mut f1, mut f2) = (f(x1), f(x2));
        for _ in 0..SEARCH_STEPS {
            if f1 <= f2 {
                hi = x2;
                (x2, f2) = (x1, f1);
                x1 = hi - ratio * (hi - lo);
                f1 = f(x1);
            } else {
                lo = x1;
                (x1, f1) = (x2, f2);
                x2 = lo + ratio * (hi - lo);
                f2 = f(x2);
            }
        }
        // The minimiser lies in [lo, hi]; the midpoint is within half the
        // bracket of it, and f changes at most by the distance moved.
        let mid = 0.5 * (lo + hi);
        (f(mid) - 0.5 * (hi - lo) * length).min(f(0.0)).min(f(1.0))
    }

    /// Lower bound on the distance from `shape` to every cone, in `[0, cap]`.
    pub(crate) fn clearance(&self, shape: &Shape, cap: f64) -> f64 {
        let (a, b) = match shape {
            Shape::Sphere(s) => (s.centre, s.centre),
            Shape::Capsule(c) => (c.a, c.b),
        };
        let (mid, half) = ((a + b) * 0.5, 0.5 * (b - a).length());
        let radius = shape.radius();
        if cap.is_nan() || cap <= 0.0 {
            // Nothing to find below 0 (a shape outside the field of view).
            return 0.0;
        }
        if half == 0.0 {
            return self.sphere_clearance(mid, radius, cap);
        }
        self.each_cone_clearance((a, b), radius, cap)
    }

    /// [`Self::clearance`] of a capsule (or of any shape, by the tests):
    /// every cone in the given order, the midpoint's distance less the half
    /// length first.
    fn each_cone_clearance(&self, (a, b): (DVec3, DVec3), radius: f64, cap: f64) -> f64 {
        let (mid, half) = ((a + b) * 0.5, 0.5 * (b - a).length());
        let mut best = cap;
        for k in 0..self.cones.len() {
            // Cheap first: the midpoint's distance less the half length.
            if self.distance(k, mid) - half - radius >= best {
                continue;
            }
            let d = if half == 0.0 {
                self.distance(k, mid)
            } else {
                self.segment_distance(k, a, b)
            };
            best = best.min(d - radius);
            if best <= 0.0 {
                return 0.0;
            }
        }
        best.clamp(0.0, cap)
    }

    /// [`Self::each_cone_clearance`] of a sphere, bit for bit, down the
    /// tree: a node whose bounding cone is no nearer than the bound so far
    /// is skipped with everything below it (`guard::dark_groups`), and of
    /// two halves the one the centre is deeper in (or nearer to) is searched
    /// first, so that the bound drops early. A sphere's answer is the smallest of its cones' distances, in
    /// any order.
    fn sphere_clearance(&self, centre: DVec3, radius: f64, cap: f64) -> f64 {
        if self.depth >= STACK {
            return self.each_cone_clearance((centre, centre), radius, cap);
        }
        // The centre from the apex, and its squared length, for every cone.
        let d = centre - self.apex;
        let d2 = d.length_squared();
        let rounding = ROUNDING_REL * (1.0 + (centre - self.apex).length());
        // How near a node's members may be, at best: its bounding cone's
        // distance less the allowances (-inf without a bounding cone); and
        // how far off its lateral surface the centre is, to order by.
        let near = |node: &ConeNode| {
            node.bound
                .map_or((f64::NEG_INFINITY, f64::NEG_INFINITY), |bound| {
                    let (distance, side) = cone_distance_and_side(d, d2, bound);
                    (distance - rounding - radius, side)
                })
        };
        let mut best = cap;
        // Nodes still to search, with how near their members may be.
        let mut stack = [(0usize, 0.0f64); STACK];
        stack[0] = (0, near(&self.tree[0]).0);
        let mut waiting = 1;
        while waiting > 0 {
            waiting -= 1;
            let (index, nearest) = stack[waiting];
            if nearest >= best {
                continue;
            }
            let node = &self.tree[index];
            let Some([a, b]) = node.halves else {
                for &cone in &self.sorted[node.members[0]..node.members[1]] {
                    best = best.min(cone_distance_at(d, d2, cone) - radius);
                    if best <= 0.0 {
                        return 0.0;
                    }
                }
                continue;
            };
            let ((na, sa), (nb, sb)) = (near(&self.tree[a]), near(&self.tree[b]));
            // The half the centre is deeper in (or nearer to) on top,
            // searched next: the bound drops fastest there.
            let (first, second) = if sb < sa {
                ((b, nb), (a, na))
            } else {
                ((a, na), (b, nb))
            };
            stack[waiting] = second;
            stack[waiting + 1] = first;
            waiting += 2;
        }
        best.clamp(0.0, cap)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field_of_view::tests::random_unit as unit;
    use crate::{Capsule, Sphere};
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;
    use shroud_msg::DarkCone;

    /// Up to `MAX_DARK_CONES` cones from a random apex: a grid across a
    /// cone of view (as a camera lists them), a few tight clusters, or
    /// anywhere.
    fn random_cones(rng: &mut Pcg64) -> NoReturn {
        let centre = unit(rng);
        let (e1, e2) = centre.any_orthonormal_pair();
        let n = rng.random_range(1..=shroud_msg::MAX_DARK_CONES);
        let (kind, side) = (rng.random_range(0..3), (n as f64).sqrt().ceil() as usize);
        let span = rng.random_range(0.05..1.0);
        let cones = (0..n)
            .map(|k| {
                let axis = match kind {
                    0 => {
                        let at = |x: usize| span * (2.0 * (x as f64 + 0.5) / side as f64 - 1.0);
                        centre + e1 * at(k % side) + e2 * at(k / side)
                    }
                    1 => centre + unit(rng) * span * 0.1 + e1 * (k % 4) as f64 * span,
                    _ => unit(rng),
                };
                DarkCone {
                    axis: axis.normalize().to_array(),
                    half_angle: rng.random_range(0.001..0.2),
                }
            })
            .collect();
        NoReturn {
            apex: [0; 3].map(|_| rng.random_range(-2.0..2.0)),
            cones,
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

        /// A sphere's bound down the tree is, bit for bit, the bound over
        /// every cone in turn: never larger (that would be optimistic), never
        /// smaller.
        #[test]
        fn spheres_down_the_tree_are_bounded_as_by_every_cone(seed in any::<u64>(), cap in 0.01..3.0f64) {
            let mut rng = Pcg64::seed_from_u64(seed);
            let no_return = random_cones(&mut rng);
            let cones = DarkCones::new(&no_return);
            let apex = DVec3::from_array(no_return.apex);
            let axis = DVec3::from_array(no_return.cones[0].axis);
            for _ in 0..100 {
                // Near the cones and anywhere around the apex.
                let centre = apex
                    + (axis * rng.random_range(0.0..3.0) + unit(&mut rng) * rng.random_range(0.0..1.0));
                let radius = rng.random_range(0.001..0.3);
                let sphere = Shape::Sphere(Sphere { centre, radius });
                let by_tree = cones.clearance(&sphere, cap);
                let every = cones.each_cone_clearance((centre, centre), radius, cap);
                prop_assert!(by_tree == every, "{centre} r {radius}: {by_tree} vs {every}");
            }
        }
    }

    /// A tree too deep for the search's stack is searched cone by cone,
    /// with the same answers.
    #[test]
    fn a_tree_too_deep_is_searched_cone_by_cone() {
        let mut rng = Pcg64::seed_from_u64(17);
        for _ in 0..20 {
            let no_return = random_cones(&mut rng);
            let cones = DarkCones::new(&no_return);
            assert!(cones.depth < STACK);
            let deep = DarkCones {
                depth: STACK,
                ..cones.clone()
            };
            let apex = DVec3::from_array(no_return.apex);
            for _ in 0..50 {
                let centre = apex + unit(&mut rng) * rng.random_range(0.0..3.0);
                let radius = rng.random_range(0.001..0.3);
                let sphere = Shape::Sphere(Sphere { centre, radius });
                assert_eq!(
                    cones.clearance(&sphere, 1.0).to_bits(),
                    deep.clearance(&sphere, 1.0).to_bits()
                );
            }
        }
    }

    /// The distance from `p` to one cone by brute force: the nearest of
    /// 4000 generators (rays from the apex on the cone's surface), each an
    /// exact point-to-ray distance, or 0 inside. Never below the truth, and
    /// above it by at most the generators' spacing times the distance.
    fn brute(apex: DVec3, axis: DVec3, alpha: f64, p: DVec3) -> f64 {
        let d = p - apex;
        if d.length() == 0.0 || d.normalize().dot(axis).acos() <= alpha {
            return 0.0;
        }
        let e1 = axis.any_orthonormal_vector();
        let e2 = axis.cross(e1);
        (0..4000)
            .map(|i| {
                let phi = i as f64 / 4000.0 * std::f64::consts::TAU;
                let g = axis * alpha.cos() + (e1 * phi.cos() + e2 * phi.sin()) * alpha.sin();
                (d - g * d.dot(g).max(0.0)).length()
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn distances_to_cones_match_brute_force_and_bound_capsules_from_below() {
        let mut rng = Pcg64::seed_from_u64(11);
        for _ in 0..120 {
            let apex = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(0.0..2.0),
            );
            let axis = unit(&mut rng);
            let alpha = rng.random_range(0.001..1.4);
            let cones = DarkCones::new(&NoReturn {
                apex: apex.to_array(),
                cones: vec![DarkCone {
                    axis: axis.to_array(),
                    half_angle: alpha,
                }],
            });
            let p = apex + unit(&mut rng) * rng.random_range(0.0..3.0);
            let exact = cones.distance(0, p);
            let sampled = brute(apex, axis, alpha, p);
            let spacing = std::f64::consts::TAU / 4000.0 * (p - apex).length();
            assert!(exact <= sampled + 1e-12, "{exact} > {sampled}");
            assert!(exact >= sampled - spacing, "{exact} << {sampled}");
            // A sphere: the centre's distance less the radius, clamped.
            let r = rng.random_range(0.0..0.3);
            let sphere = Shape::Sphere(Sphere {
                centre: p,
                radius: r,
            });
            let got = cones.clearance(&sphere, 10.0);
            assert!((got - (exact - r).clamp(0.0, 10.0)).abs() < 1e-12);
            // A capsule: never above the distance of any point of its core
            // (each exact, the point distance being checked just above), and
            // within the samples' spacing of the smallest.
            let q = p + unit(&mut rng) * rng.random_range(0.0..1.0);
            let capsule = Shape::Capsule(Capsule {
                a: p,
                b: q,
                radius: r,
            });
            let bound = cones.clearance(&capsule, 10.0);
            let along = (0..=2000)
                .map(|i| cones.distance(0, p + (q - p) * (i as f64 / 2000.0)))
                .fold(f64::INFINITY, f64::min);
            assert!(bound <= (along - r).max(0.0) + 1e-9, "{bound} vs {along}");
            let slack = (q - p).length() / 2000.0 + 1e-8;
            assert!(bound >= along - r - slack, "{bound} far below {along}");
        }
    }

    #[test]
    fn the_nearest_of_several_cones_and_the_cap_decide() {
        let no_return = NoReturn {
            apex: [0.0, 0.0, 2.0],
            cones: vec![
                DarkCone {
                    axis: [0.0, 0.0, -1.0],
                    half_angle: 0.1,
                },
                DarkCone {
                    axis: [0.6, 0.0, -0.8],
                    half_angle: 0.05,
                },
            ],
        };
        let cones = DarkCones::new(&no_return);
        let inside = Shape::Sphere(Sphere {
            centre: DVec3::new(0.0, 0.0, 1.0),
            radius: 0.01,
        });
        assert_eq!(cones.clearance(&inside, 0.2), 0.0);
        // 0.5 m off the vertical axis at 1 m below the apex: 0.5 cos(0.1) -
        // 1 sin(0.1) from the first cone, farther from the second.
        let beside = Shape::Sphere(Sphere {
            centre: DVec3::new(-0.5, 0.0, 1.0),
            radius: 0.0,
        });
        let want = 0.5 * 0.1f64.cos() - 0.1f64.sin();
        assert!((cones.clearance(&beside, 1.0) - want).abs() < 1e-12);
        assert_eq!(cones.clearance(&beside, 0.2), 0.2);
        // Behind the apex the apex itself is nearest.
        let behind = Shape::Sphere(Sphere {
            centre: DVec3::new(0.0, 0.0, 2.5),
            radius: 0.1,
        });
        assert!((cones.clearance(&behind, 1.0) - 0.4).abs() < 1e-12);
        // No cones: nothing unseen here.
        let none = DarkCones::new(&NoReturn {
            apex: [0.0; 3],
            cones: Vec::new(),
        });
        assert_eq!(none.clearance(&inside, 0.2), 0.2);
    }
}
