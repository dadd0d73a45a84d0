//! The truth at one instant: the distance from an arm shape to every solid
//! where it is at that time, and to the floor, from the shapes' definitions
//! (the soundness harness's [`Solid`] signed distances; never shroud's
//! clearance code).
//!
//! A point core is exact; a segment core (a capsule) against a ball is the
//! exact point-to-segment distance, against a box or a capsule the minimum
//! of the convex signed distance along the segment by golden-section search,
//! every value an evaluation at a real point (it overestimates the minimum
//! by at most the final bracket, `0.618^60` of the segment, below 1e-12 m).

use super::super::solids::{point_segment_distance, Body, Solid};
use super::super::truth::{floor_clearance, golden_min, Core};

/// Distance from the shape `core` to `solid` at time `t`, less the core's
/// radius (negative: they overlap). Pairs whose bounding balls are further
/// apart than `cutoff` return that lower bound instead.
pub fn solid_distance_at(core: &Core, solid: &Solid, t: f64, cutoff: f64) -> f64 {
    let c = solid.centre_at(t);
    let mid = (core.a + core.b) * 0.5;
    let half = (core.b - core.a).length() * 0.5;
    let bound = (mid - c).length() - half - solid.bounding_radius() - core.radius;
    if bound > cutoff {
        return bound;
    }
    let distance = match (solid.body, core.is_point()) {
        (Body::Sphere { radius }, _) => point_segment_distance(c, core.a, core.b) - radius,
        (_, true) => solid.signed_distance_centred(c, core.a),
        (_, false) => {
            golden_min(|s| solid.signed_distance_centred(c, core.a + (core.b - core.a) * s))
        }
    };
    distance - core.radius
}

/// What a shape is nearest to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Nearest {
    Floor,
    Solid(usize),
}

/// The smallest distance from the shape to anything at time `t`, and what
/// it is (distances beyond `cutoff` may be lower bounds).
pub fn nearest_at(core: &Core, solids: &[Solid], t: f64, cutoff: f64) -> (f64, Nearest) {
    let mut best = (floor_clearance(core), Nearest::Floor);
    for (k, solid) in solids.iter().enumerate() {
        let d = solid_distance_at(core, solid, t, cutoff);
        if d < best.0 {
            best = (d, Nearest::Solid(k));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn instant_distances_match_dense_sampling() {
        let (bodies, cores) = crate::soundness::truth::test_bodies_and_cores();
        for body in bodies {
            let s = Solid {
                body,
                centre: DVec3::new(0.0, 0.0, 0.5),
                velocity: DVec3::new(0.4, 0.1, 0.0),
                black: false,
            };
            for core in &cores {
                let exact = solid_distance_at(core, &s, 0.7, f64::INFINITY);
                let brute = (0..=4000)
                    .map(|j| {
                        let p = core.a + (core.b - core.a) * (j as f64 / 4000.0);
                        s.signed_distance(p, 0.7)
                    })
                    .fold(f64::INFINITY, f64::min)
                    - core.radius;
                assert!(exact <= brute + 1e-12, "{body:?}: {exact} > {brute}");
                assert!(brute - exact < 1e-3, "{body:?}: {exact} vs {brute}");
                // Culling only ever returns a lower bound.
                let culled = solid_distance_at(core, &s, 0.7, -1.0);
                assert!(culled <= exact + 1e-12);
            }
        }
    }
}
