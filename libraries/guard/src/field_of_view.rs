//! Distance from a shape to the space outside a sensor's field of view.
//!
//! A surrogate's kept triangle may reach past the edge of its sensor's field
//! of view: the surface there is interpolated from points inside it, and an
//! obstacle just outside was never looked at. When the cloud states its field
//! of view, that space counts as unseen.
//!
//! The field of view is convex (a cone or a rectangular pyramid cut by a
//! ball), so for a point inside it the distance to its complement is the
//! smallest distance to one of the bounding surfaces, exactly: the lateral
//! cone at angle `alpha` from a point at angle `theta` and distance `d` from
//! the apex is `d sin(alpha - theta)` away, a face of the pyramid is a plane
//! through the apex, the range sphere is `max_range - d` away. That distance is
//! a concave function inside a convex set, so over a capsule's segment its
//! minimum is at an end.

use super::shape::Shape;
use glam::DVec3;
use shroud_msg::{Aperture, FieldOfView};

/// How deep `p` lies inside `fov`: the distance from `p` to the nearest point
/// outside it; 0 or less when `p` is outside.
pub fn depth_inside(fov: &FieldOfView, p: DVec3) -> f64 {
    ViewRegion::new(fov).depth(p)
}

/// A stated field of view ready for depth queries, computed once per cloud:
/// its unit axis, its image axes, and the sines and cosines of its half
/// angles (each query used to compute them anew, the same way).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ViewRegion {
    apex: DVec3,
    axis: DVec3,
    max_range: f64,
    lateral: Lateral,
}

/// The lateral bound of a [`ViewRegion`].
#[derive(Debug, Clone, PartialEq)]
enum Lateral {
    /// `sin` and `cos` of the half angle.
    Cone { sin: f64, cos: f64 },
    /// The image's right and up axes, and per axis the `sin` and `cos` of
    /// its half angle.
    Rectangle {
        right: DVec3,
        up: DVec3,
        sin: [f64; 2],
        cos: [f64; 2],
    },
}

impl ViewRegion {
    pub(crate) fn new(fov: &FieldOfView) -> Self {
        // Renormalised: the wire allows directions within 1e-6 of unit.
        let axis = DVec3::from_array(fov.axis).normalize();
        let lateral = match fov.aperture {
            Aperture::Cone { half_angle } => Lateral::Cone {
                sin: half_angle.sin(),
                cos: half_angle.cos(),
            },
            Aperture::Rectangle { right, half_angles } => {
                let right = DVec3::from_array(right);
                let right = (right - right.dot(axis) * axis).normalize();
                Lateral::Rectangle {
                    right,
                    up: axis.cross(right),
                    sin: half_angles.map(f64::sin),
                    cos: half_angles.map(f64::cos),
                }
            }
        };
        Self {
            apex: DVec3::from_array(fov.apex),
            axis,
            max_range: fov.max_range,
            lateral,
        }
    }

    /// How deep `p` lies inside: see [`depth_inside`].
    pub(crate) fn depth(&self, p: DVec3) -> f64 {
        let d = p - self.apex;
        let along = d.dot(self.axis);
        let range = self.max_range - d.length();
        let lateral = match &self.lateral {
            Lateral::Cone { sin, cos } => {
                let across = (d - along * self.axis).length();
                // d sin(alpha - theta) = sin(alpha) along - cos(alpha) across.
                sin * along - cos * across
            }
            Lateral::Rectangle {
                right,
                up,
                sin,
                cos,
            } => {
                // Each face is the plane through the apex at the half angle
                // from the axis; its unit normal is (side cos(beta) - axis
                // sin(beta)).
                let face = |side: f64, k: usize| sin[k] * along - cos[k] * side.abs();
                face(d.dot(*right), 0).min(face(d.dot(*up), 1))
            }
        };
        range.min(lateral)
    }
}

/// Lower bound on the distance from `shape` to the space outside `region`,
/// in `[0, cap]`.
pub(crate) fn clearance_outside(region: &ViewRegion, shape: &Shape, cap: f64) -> f64 {
    let deepest = match shape {
        Shape::Sphere(s) => region.depth(s.centre),
        Shape::Capsule(c) => region.depth(c.a).min(region.depth(c.b)),
    };
    (deepest - shape.radius()).clamp(0.0, cap)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::{Capsule, Sphere};
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    pub(crate) fn random_fov(rng: &mut Pcg64) -> FieldOfView {
        let axis = random_unit(rng);
        let helper = if axis.x.abs() < 0.9 {
            DVec3::X
        } else {
            DVec3::Y
        };
        let right = axis.cross(helper).normalize();
        let aperture = if rng.random_bool(0.5) {
            Aperture::Cone {
                half_angle: rng.random_range(0.1..1.4),
            }
        } else {
            Aperture::Rectangle {
                right: right.to_array(),
                half_angles: [rng.random_range(0.1..1.4), rng.random_range(0.1..1.4)],
            }
        };
        FieldOfView {
            apex: [
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ],
            axis: axis.to_array(),
            aperture,
            max_range: rng.random_range(0.5..4.0),
        }
    }

    pub(crate) fn random_unit(rng: &mut Pcg64) -> DVec3 {
        loop {
            let v = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            if (0.1..1.0).contains(&v.length()) {
                return v.normalize();
            }
        }
    }

    /// Membership written from the definition: within range, and within the
    /// half angles of the axis (per image direction for a rectangle).
    fn inside(fov: &FieldOfView, p: DVec3) -> bool {
        let axis = DVec3::from_array(fov.axis);
        let d = p - DVec3::from_array(fov.apex);
        let along = d.dot(axis);
        if d.length() > fov.max_range || along <= 0.0 {
            return false;
        }
        match fov.aperture {
            Aperture::Cone { half_angle } => (d.dot(axis) / d.length()).acos() <= half_angle,
            Aperture::Rectangle { right, half_angles } => {
                let right = DVec3::from_array(right);
                let up = axis.cross(right);
                d.dot(right).abs().atan2(along) <= half_angles[0]
                    && d.dot(up).abs().atan2(along) <= half_angles[1]
            }
        }
    }

    /// The apex is on the boundary of every valid field of view, the extreme
    /// apertures the wire accepts included (half angles from 0.01 to 1.5
    /// rad): its depth is finite and not inside.
    #[test]
    fn the_apex_is_never_inside() {
        let mut rng = Pcg64::seed_from_u64(5);
        for _ in 0..2000 {
            let mut fov = random_fov(&mut rng);
            let extreme = |rng: &mut Pcg64| {
                *[0.01, 1.5, rng.random_range(0.01..1.5)]
                    .get(rng.random_range(0..3))
                    .unwrap()
            };
            fov.aperture = match fov.aperture {
                Aperture::Cone { .. } => Aperture::Cone {
                    half_angle: extreme(&mut rng),
                },
                Aperture::Rectangle { right, .. } => Aperture::Rectangle {
                    right,
                    half_angles: [extreme(&mut rng), extreme(&mut rng)],
                },
            };
            fov.validate().unwrap();
            let depth = depth_inside(&fov, DVec3::from_array(fov.apex));
            assert!(depth.is_finite() && depth <= 0.0, "{fov:?}: {depth}");
        }
    }

    /// Brute force against the definition: for random fields of view and
    /// points inside them, no point outside is nearer than the depth (a ring
    /// of probes at the depth less a hair stays inside), and one is found
    /// within a hair beyond it (the depth is tight).
    #[test]
    fn the_depth_is_the_exact_distance_to_the_outside() {
        let mut rng = Pcg64::seed_from_u64(23);
        let mut checked = 0;
        while checked < 400 {
            let fov = random_fov(&mut rng);
            fov.validate().unwrap();
            let p = DVec3::from_array(fov.apex)
                + random_unit(&mut rng) * rng.random_range(0.0..fov.max_range);
            if !inside(&fov, p) {
                assert!(depth_inside(&fov, p) <= 1e-12, "{fov:?} {p}");
                continue;
            }
            let depth = depth_inside(&fov, p);
            assert!(depth >= 0.0);
            let directions: Vec<DVec3> = (0..3000).map(|_| random_unit(&mut rng)).collect();
            let hair = 1e-3 * depth.max(1e-3);
            for dir in &directions {
                assert!(
                    inside(&fov, p + dir * (depth - hair).max(0.0)),
                    "{fov:?}: {p} at depth {depth} leaves along {dir}"
                );
            }
            // Tight: along some direction the outside is within 2 % more
            // (3000 random directions find the nearest face's normal to
            // within a few degrees).
            let out = directions
                .iter()
                .any(|dir| !inside(&fov, p + dir * (depth * 1.02 + hair)));
            assert!(out, "{fov:?}: {p}: nothing outside at {depth}");
            checked += 1;
        }
    }

    #[test]
    fn a_capsule_is_as_deep_as_its_shallower_end_less_its_radius() {
        let mut rng = Pcg64::seed_from_u64(5);
        for _ in 0..200 {
            let fov = random_fov(&mut rng);
            let apex = DVec3::from_array(fov.apex);
            let a = apex + random_unit(&mut rng) * rng.random_range(0.0..fov.max_range);
            let b = apex + random_unit(&mut rng) * rng.random_range(0.0..fov.max_range);
            let shape = Shape::Capsule(Capsule { a, b, radius: 0.01 });
            let got = clearance_outside(&ViewRegion::new(&fov), &shape, 10.0);
            // Concave depth: no sample of the segment is shallower than the
            // ends, so the samples' minimum bounds the result from above.
            let sampled = (0..=100)
                .map(|i| depth_inside(&fov, a.lerp(b, i as f64 / 100.0)))
                .fold(f64::INFINITY, f64::min);
            assert!(got <= (sampled - 0.01).max(0.0) + 1e-12, "{got} {sampled}");
            assert!((got - (sampled - 0.01).clamp(0.0, 10.0)).abs() < 1e-9);
        }
        let fov = random_fov(&mut rng);
        let far = Shape::Sphere(Sphere {
            centre: DVec3::from_array(fov.apex) - 5.0 * DVec3::from_array(fov.axis),
            radius: 0.1,
        });
        assert_eq!(clearance_outside(&ViewRegion::new(&fov), &far, 1.0), 0.0);
    }
}
