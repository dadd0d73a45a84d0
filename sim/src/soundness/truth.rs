//! Ground truth for the guard: the smallest distance from an arm shape to
//! the floor and to every solid while the solids move over a time interval,
//! from the shapes' definitions alone (never shroud's clearance code).
//!
//! A solid moving at velocity `v` is, relative to the arm, the arm moving at
//! `-v`: the distance over `[t0, t1]` is the distance from the body (at its
//! reference place) to the arm shape's core swept by `-v [t0, t1]`, less the
//! shape's radius. The signed distance to a convex body is convex, and the
//! swept core is an affine image of a segment or a square, so its minimum is
//! found by golden-section search (nested for a capsule core); every value is
//! an evaluation at a real point, so the result overestimates the minimum by
//! at most the bracket (`0.618^60` of the core's extent, below 1e-12 m here).

use super::solids::{floor_distance, point_segment_distance, Body, Solid};
use glam::DVec3;
use shroud_guard::{Shape, WorldShape};

/// Golden-section steps: the bracket shrinks to `0.618^60 ≈ 3e-13` of its
/// start.
const GOLDEN_STEPS: usize = 60;

/// An arm shape as a core (a point when `a == b`) and a radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Core {
    pub a: DVec3,
    pub b: DVec3,
    pub radius: f64,
}

impl Core {
    /// The core of a guard shape (its centre and radius are read, never its
    /// distances).
    pub fn of(shape: &WorldShape) -> Self {
        match shape.shape {
            Shape::Sphere(s) => Self {
                a: s.centre,
                b: s.centre,
                radius: s.radius,
            },
            Shape::Capsule(c) => Self {
                a: c.a,
                b: c.b,
                radius: c.radius,
            },
        }
    }

    pub fn is_point(&self) -> bool {
        self.a == self.b
    }

    /// The points the guard's "in view" check samples: the ends (one for a
    /// sphere) and, for a capsule, the middle.
    pub fn samples(&self) -> Vec<DVec3> {
        if self.is_point() {
            vec![self.a]
        } else {
            vec![self.a, (self.a + self.b) * 0.5, self.b]
        }
    }
}

/// Minimum of a convex function on `[0, 1]`, evaluated at real points.
pub(super) fn golden_min(f: impl Fn(f64) -> f64) -> f64 {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (0.0, 1.0);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..GOLDEN_STEPS {
        if f1 <= f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - g * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + g * (hi - lo);
            f2 = f(x2);
        }
    }
    f1.min(f2).min(f(0.0)).min(f(1.0))
}

/// Distance from the core to `solid` while it moves over `[t0, t1]`, less
/// the core's radius (negative: they overlap). Pairs whose bounding balls are
/// further apart than `cutoff` return that lower bound instead (it is all a
/// caller comparing against `cutoff` needs).
pub fn solid_distance(core: &Core, solid: &Solid, t0: f64, t1: f64, cutoff: f64) -> f64 {
    let (v, c) = (solid.velocity, solid.centre);
    // The core at `s` when the solid is at `tau`, relative to the solid's
    // reference place.
    let at = |s: f64, tau: f64| core.a + (core.b - core.a) * s - v * (t0 + (t1 - t0) * tau);
    let middle = at(0.5, 0.5);
    let spread = (core.b - core.a).length() * 0.5 + v.length() * (t1 - t0) * 0.5;
    let bound = (middle - c).length() - spread - solid.bounding_radius() - core.radius;
    if bound > cutoff {
        return bound;
    }
    let sd = |p: DVec3| solid.signed_distance_centred(c, p);
    let distance = match (solid.body, core.is_point()) {
        // A ball against a point swept along a segment: exact.
        (Body::Sphere { radius }, true) => {
            point_segment_distance(c, at(0.0, 0.0), at(0.0, 1.0)) - radius
        }
        (_, true) => golden_min(|tau| sd(at(0.0, tau))),
        (_, false) => golden_min(|s| golden_min(|tau| sd(at(s, tau)))),
    };
    distance - core.radius
}

/// Distance from the core to the floor (which does not move).
pub fn floor_clearance(core: &Core) -> f64 {
    floor_distance(core.a).min(floor_distance(core.b)) - core.radius
}

/// The smallest distance from the core to anything over `[t0, t1]`, and
/// what it is (`None`: the floor).
pub fn nearest(
    core: &Core,
    solids: &[Solid],
    t0: f64,
    t1: f64,
    cutoff: f64,
) -> (f64, Option<usize>) {
    let mut best = (floor_clearance(core), None);
    for (k, solid) in solids.iter().enumerate() {
        let d = solid_distance(core, solid, t0, t1, cutoff);
        if d < best.0 {
            best = (d, Some(k));
        }
    }
    best
}

/// The point of `solid` at time `t` nearest to `p` (on its surface).
pub fn nearest_surface_point(solid: &Solid, t: f64, p: DVec3) -> DVec3 {
    let c = solid.centre_at(t);
    let d = p - c;
    let towards = |from: DVec3, r: f64| {
        let e = p - from;
        let n = if e.length() > 0.0 {
            e.normalize()
        } else {
            DVec3::Z
        };
        from + n * r
    };
    match solid.body {
        Body::Sphere { radius } => towards(c, radius),
        Body::Capsule {
            half_length,
            axis,
            radius,
        } => towards(
            c + axis * d.dot(axis).clamp(-half_length, half_length),
            radius,
        ),
        Body::Cuboid { half, rotation } => {
            let local = rotation.inverse() * d;
            let clamped = local.clamp(-half, half);
            let surface = if clamped == local {
                // Inside: the nearest face.
                let gap = half - local.abs();
                let k = if gap.x <= gap.y && gap.x <= gap.z {
                    0
                } else if gap.y <= gap.z {
                    1
                } else {
                    2
                };
                let mut q = local;
                q[k] = half[k].copysign(local[k]);
                q
            } else {
                clamped
            };
            c + rotation * surface
        }
    }
}

/// Three bodies (a sphere, a rotated box, a tilted capsule) and two cores
/// (a ball, a slanted segment) that the distance tests check against dense
/// sampling.
#[cfg(test)]
pub(super) fn test_bodies_and_cores() -> ([Body; 3], [Core; 2]) {
    use glam::DQuat;
    let bodies = [
        Body::Sphere { radius: 0.2 },
        Body::Cuboid {
            half: DVec3::new(0.3, 0.1, 0.2),
            rotation: DQuat::from_rotation_z(0.4) * DQuat::from_rotation_y(0.3),
        },
        Body::Capsule {
            half_length: 0.3,
            axis: DVec3::new(0.0, 1.0, 1.0).normalize(),
            radius: 0.05,
        },
    ];
    let cores = [
        Core {
            a: DVec3::new(0.8, 0.3, 0.6),
            b: DVec3::new(0.8, 0.3, 0.6),
            radius: 0.05,
        },
        Core {
            a: DVec3::new(0.6, -0.5, 0.2),
            b: DVec3::new(0.9, 0.4, 0.9),
            radius: 0.04,
        },
    ];
    (bodies, cores)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid(body: Body, velocity: DVec3) -> Solid {
        Solid {
            body,
            centre: DVec3::new(0.0, 0.0, 0.5),
            velocity,
            black: false,
        }
    }

    /// Brute force: dense samples of time and of the core.
    fn sampled(core: &Core, s: &Solid, t0: f64, t1: f64) -> f64 {
        let mut best = f64::INFINITY;
        for i in 0..=200 {
            let t = t0 + (t1 - t0) * i as f64 / 200.0;
            for j in 0..=40 {
                let p = core.a + (core.b - core.a) * (j as f64 / 40.0);
                best = best.min(s.signed_distance(p, t));
            }
        }
        best - core.radius
    }

    #[test]
    fn swept_distances_match_dense_sampling() {
        let (bodies, cores) = test_bodies_and_cores();
        for body in bodies {
            let s = solid(body, DVec3::new(0.4, 0.1, 0.0));
            for core in &cores {
                let exact = solid_distance(core, &s, 0.2, 1.0, f64::INFINITY);
                let brute = sampled(core, &s, 0.2, 1.0);
                // Sampling only overestimates, by at most the sample spacing.
                assert!(exact <= brute + 1e-12, "{body:?}: {exact} > {brute}");
                assert!(brute - exact < 0.01, "{body:?}: {exact} vs {brute}");
            }
        }
    }

    #[test]
    fn culling_returns_a_lower_bound_and_floor_counts() {
        let s = solid(Body::Sphere { radius: 0.1 }, DVec3::ZERO);
        let far = Core {
            a: DVec3::new(5.0, 0.0, 0.5),
            b: DVec3::new(5.0, 0.0, 0.5),
            radius: 0.1,
        };
        let bound = solid_distance(&far, &s, 0.0, 0.1, 0.5);
        assert!(bound > 0.5 && bound <= 4.8 + 1e-12);
        let (d, what) = nearest(&far, &[s], 0.0, 0.1, 0.5);
        assert_eq!(what, None);
        assert!((d - 0.4).abs() < 1e-12);
        let p = nearest_surface_point(&s, 0.0, DVec3::new(1.0, 0.0, 0.5));
        assert!((p - DVec3::new(0.1, 0.0, 0.5)).length() < 1e-12);
    }
}
