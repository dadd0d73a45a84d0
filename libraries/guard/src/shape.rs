//! Collision shapes of a link: spheres and capsules (a segment swept by a ball),
//! given in a link frame or, after forward kinematics, in the world.

use glam::{DAffine3, DVec3};
use serde::{Deserialize, Serialize};

/// A ball.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sphere {
    pub centre: DVec3,
    pub radius: f64,
}

/// Every point within `radius` of the segment `a`-`b`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Capsule {
    pub a: DVec3,
    pub b: DVec3,
    pub radius: f64,
}

/// A collision shape. A capsule counts as one shape (its clearance is computed
/// for the swept segment, not for covering spheres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Shape {
    Sphere(Sphere),
    Capsule(Capsule),
}

/// A shape in world coordinates and the index of the link that carries it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WorldShape {
    pub link: usize,
    pub shape: Shape,
}

impl Shape {
    pub fn sphere(centre: DVec3, radius: f64) -> Self {
        Shape::Sphere(Sphere { centre, radius })
    }

    pub fn capsule(a: DVec3, b: DVec3, radius: f64) -> Self {
        Shape::Capsule(Capsule { a, b, radius })
    }

    pub fn radius(&self) -> f64 {
        match self {
            Shape::Sphere(s) => s.radius,
            Shape::Capsule(c) => c.radius,
        }
    }

    /// Finite coordinates and a finite radius `> 0`.
    pub fn is_valid(&self) -> bool {
        let r = self.radius();
        let points_ok = match self {
            Shape::Sphere(s) => s.centre.is_finite(),
            Shape::Capsule(c) => c.a.is_finite() && c.b.is_finite(),
        };
        points_ok && r.is_finite() && r > 0.0
    }

    /// The shape moved by a rigid transform (radii are kept: forward kinematics
    /// only produces rotations and translations).
    pub fn transformed(&self, pose: &DAffine3) -> Shape {
        match self {
            Shape::Sphere(s) => Shape::sphere(pose.transform_point3(s.centre), s.radius),
            Shape::Capsule(c) => Shape::capsule(
                pose.transform_point3(c.a),
                pose.transform_point3(c.b),
                c.radius,
            ),
        }
    }

    /// Whether a world point lies in the shape (closed).
    pub fn contains(&self, p: DVec3) -> bool {
        self.distance_to(p) <= 0.0
    }

    /// Euclidean distance from a point to the shape (negative inside: the depth
    /// below the surface). The brute-force reference of the tests.
    pub fn distance_to(&self, p: DVec3) -> f64 {
        match self {
            Shape::Sphere(s) => (p - s.centre).length() - s.radius,
            Shape::Capsule(c) => {
                let d = c.b - c.a;
                let len2 = d.length_squared();
                let t = if len2 > 0.0 {
                    ((p - c.a).dot(d) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (p - (c.a + d * t)).length() - c.radius
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    #[test]
    fn distances_to_sphere_and_capsule() {
        let s = Shape::sphere(DVec3::new(1.0, 0.0, 0.0), 0.5);
        assert_eq!(s.distance_to(DVec3::new(3.0, 0.0, 0.0)), 1.5);
        assert!(s.contains(DVec3::new(1.2, 0.1, 0.0)));
        let c = Shape::capsule(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), 0.25);
        assert_eq!(c.distance_to(DVec3::new(1.0, 1.0, 0.0)), 0.75);
        assert_eq!(c.distance_to(DVec3::new(-1.0, 0.0, 0.0)), 0.75);
        assert_eq!(c.distance_to(DVec3::new(3.0, 0.0, 0.0)), 0.75);
        let degenerate = Shape::capsule(DVec3::ONE, DVec3::ONE, 1.0);
        assert_eq!(degenerate.distance_to(DVec3::new(1.0, 1.0, 3.0)), 1.0);
    }

    #[test]
    fn rigid_transform_keeps_radius_and_moves_points() {
        let pose = DAffine3::from_rotation_translation(
            DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
            DVec3::new(0.0, 0.0, 1.0),
        );
        let c = Shape::capsule(DVec3::ZERO, DVec3::X, 0.1).transformed(&pose);
        let Shape::Capsule(c) = c else {
            panic!("a capsule stays a capsule")
        };
        assert!((c.a - DVec3::Z).length() < 1e-15);
        assert!((c.b - DVec3::new(0.0, 1.0, 1.0)).length() < 1e-15);
        assert_eq!(c.radius, 0.1);
    }

    #[test]
    fn validity() {
        assert!(Shape::sphere(DVec3::ZERO, 1e-9).is_valid());
        assert!(!Shape::sphere(DVec3::ZERO, 0.0).is_valid());
        assert!(!Shape::sphere(DVec3::new(f64::NAN, 0.0, 0.0), 1.0).is_valid());
        assert!(!Shape::capsule(DVec3::ZERO, DVec3::INFINITY, 1.0).is_valid());
        assert!(!Shape::sphere(DVec3::ZERO, f64::INFINITY).is_valid());
    }
}
