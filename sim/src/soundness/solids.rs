//! The true shapes of a soundness scene (floor, spheres, boxes, capsules moving
//! at constant velocity) and their exact signed distances to points.
//!
//! Truth must not come from shroud's own geometry, so everything here is
//! written from the definitions: a ball is the points within a radius of its
//! centre, a box the points whose local coordinates lie within its half
//! extents, a capsule the points within a radius of its axis segment.

use glam::{DQuat, DVec3};

/// Half the side of the floor square (the plane z = 0 between -x and x, -y
/// and y): much larger than the arm's reach, so that no pose sees its edge.
pub const FLOOR_HALF_WIDTH: f64 = 10.0;

/// The shape of a solid around its centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Body {
    Sphere {
        radius: f64,
    },
    /// A box with half extents `half` along the axes of `rotation`.
    Cuboid {
        half: DVec3,
        rotation: DQuat,
    },
    /// The points within `radius` of the segment centre ± `half_length` ·
    /// `axis` (`axis` is a unit vector).
    Capsule {
        half_length: f64,
        axis: DVec3,
        radius: f64,
    },
}

/// A solid of the scene: a body whose centre moves as `centre + velocity * t`
/// (seconds on the scene's clock). A black solid returns no range but still
/// blocks rays.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solid {
    pub body: Body,
    pub centre: DVec3,
    pub velocity: DVec3,
    pub black: bool,
}

impl Solid {
    /// Where the centre is at time `t`.
    pub fn centre_at(&self, t: f64) -> DVec3 {
        self.centre + self.velocity * t
    }

    /// Radius of a ball around the centre that holds the body (for culling).
    pub fn bounding_radius(&self) -> f64 {
        match self.body {
            Body::Sphere { radius } => radius,
            Body::Cuboid { half, .. } => half.length(),
            Body::Capsule {
                half_length,
                radius,
                ..
            } => half_length + radius,
        }
    }

    /// Signed distance from `p` to the body centred at `centre` (negative
    /// inside): exact for all three bodies, and convex in `p`, which the
    /// minimisations of `truth` rely on.
    pub fn signed_distance_centred(&self, centre: DVec3, p: DVec3) -> f64 {
        let d = p - centre;
        match self.body {
            Body::Sphere { radius } => d.length() - radius,
            Body::Cuboid { half, rotation } => {
                let local = rotation.inverse() * d;
                let q = local.abs() - half;
                let outside = q.max(DVec3::ZERO).length();
                let inside = q.max_element().min(0.0);
                outside + inside
            }
            Body::Capsule {
                half_length,
                axis,
                radius,
            } => {
                let along = d.dot(axis).clamp(-half_length, half_length);
                (d - axis * along).length() - radius
            }
        }
    }

    /// Signed distance from `p` to the solid where it is at time `t`.
    pub fn signed_distance(&self, p: DVec3, t: f64) -> f64 {
        self.signed_distance_centred(self.centre_at(t), p)
    }
}

/// Signed distance from `p` to the floor (the half-space z <= 0 under the
/// floor square; the arm never leaves the square, see [`FLOOR_HALF_WIDTH`]).
pub fn floor_distance(p: DVec3) -> f64 {
    p.z
}

/// Distance from `p` to the segment `a`-`b` (a point when `a == b`).
pub fn point_segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let len2 = d.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + d * s)).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid(body: Body) -> Solid {
        Solid {
            body,
            centre: DVec3::new(1.0, 0.0, 0.5),
            velocity: DVec3::new(0.0, 0.5, 0.0),
            black: false,
        }
    }

    #[test]
    fn distances_from_the_definitions() {
        let s = solid(Body::Sphere { radius: 0.25 });
        assert!((s.signed_distance(DVec3::new(2.0, 0.0, 0.5), 0.0) - 0.75).abs() < 1e-15);
        // After 2 s the centre is at y = 1.
        assert!((s.signed_distance(DVec3::new(1.0, 1.0, 0.5), 2.0) + 0.25).abs() < 1e-15);
        let rotation = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
        let b = solid(Body::Cuboid {
            half: DVec3::new(0.5, 0.1, 0.2),
            rotation,
        });
        // Rotated by 90 degrees about z: the long side lies along y.
        assert!((b.signed_distance(DVec3::new(1.0, 0.7, 0.5), 0.0) - 0.2).abs() < 1e-12);
        assert!((b.signed_distance(DVec3::new(1.3, 0.0, 0.5), 0.0) - 0.2).abs() < 1e-12);
        // Corner: distance to the corner point (0.1, 0.5, 0.2) away.
        let corner = DVec3::new(1.1 + 0.3, 0.5 + 0.4, 0.7);
        assert!((b.signed_distance(corner, 0.0) - 0.5).abs() < 1e-12);
        assert!((b.signed_distance(DVec3::new(1.0, 0.0, 0.5), 0.0) + 0.1).abs() < 1e-12);
        let c = solid(Body::Capsule {
            half_length: 0.5,
            axis: DVec3::X,
            radius: 0.1,
        });
        assert!((c.signed_distance(DVec3::new(1.4, 0.0, 1.0), 0.0) - 0.4).abs() < 1e-12);
        assert!((c.signed_distance(DVec3::new(2.0, 0.0, 0.5), 0.0) - 0.4).abs() < 1e-12);
        assert_eq!(floor_distance(DVec3::new(3.0, 4.0, 0.25)), 0.25);
    }

    #[test]
    fn segment_distance_covers_degenerate_segments() {
        let a = DVec3::new(0.0, 0.0, 0.0);
        assert_eq!(point_segment_distance(DVec3::new(0.0, 3.0, 0.0), a, a), 3.0);
        let b = DVec3::new(2.0, 0.0, 0.0);
        assert_eq!(point_segment_distance(DVec3::new(1.0, 1.0, 0.0), a, b), 1.0);
        assert_eq!(point_segment_distance(DVec3::new(3.0, 0.0, 0.0), a, b), 1.0);
    }
}
