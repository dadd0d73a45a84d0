//! Where a ROS cloud's frame sits in shroud's world (a sensor's static
//! extrinsics, as a URDF or a calibration gives them), and, for a depth
//! camera, its pinhole field of view: what places the rays of an organised
//! cloud's points, returned or not.

use crate::CloudInError;
use glam::{DQuat, DVec3};
use shroud_msg::{Aperture, FieldOfView, SensorPose};

/// How far the mount's quaternion may be from unit length.
const UNIT_TOLERANCE: f64 = 1e-6;

/// A pinhole camera looking along its frame's +z, with +x to the right and
/// +y down (REP 103's optical frame, which depth camera drivers publish in),
/// its image `width x height` pixels of an organised cloud spread evenly in
/// the tangent plane over the fields of view.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinholeCamera {
    /// Full horizontal field of view, radians, in (0, pi).
    pub horizontal_fov: f64,
    /// Full vertical field of view, radians, in (0, pi).
    pub vertical_fov: f64,
    /// The farthest a return can come from, metres.
    pub max_range: f64,
}

/// The pose of a cloud's frame in shroud's world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CloudMount {
    pub position: [f64; 3],
    /// Unit quaternion `[x, y, z, w]` (ROS's order).
    pub orientation: [f64; 4],
    /// The camera that took the cloud, when it is a pinhole camera's
    /// organised image (needed to place rays without a return).
    pub camera: Option<PinholeCamera>,
}

impl Default for CloudMount {
    fn default() -> Self {
        Self {
            position: [0.0; 3],
            orientation: [0.0, 0.0, 0.0, 1.0],
            camera: None,
        }
    }
}

impl CloudMount {
    /// Refuses a non-finite position, a quaternion that is not unit, a
    /// field of view outside (0, pi) or a range that is not positive.
    pub fn validate(&self) -> Result<(), CloudInError> {
        let bad = |reason: String| Err(CloudInError::Mount(reason));
        if !self.position.iter().all(|v| v.is_finite()) {
            return bad(format!("position {:?} is not finite", self.position));
        }
        let norm = self.orientation.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm - 1.0).abs().le(&UNIT_TOLERANCE) {
            return bad(format!(
                "orientation {:?} is not a unit quaternion",
                self.orientation
            ));
        }
        let Some(camera) = self.camera else {
            return Ok(());
        };
        for (name, fov) in [
            ("horizontal", camera.horizontal_fov),
            ("vertical", camera.vertical_fov),
        ] {
            if !(fov > 0.0 && fov < std::f64::consts::PI) {
                return bad(format!("{name} field of view {fov} rad is not in (0, pi)"));
            }
        }
        if !(camera.max_range.is_finite() && camera.max_range > 0.0) {
            return bad(format!("range {} m is not positive", camera.max_range));
        }
        Ok(())
    }

    /// The frame's rotation in the world.
    pub fn rotation(&self) -> DQuat {
        DQuat::from_array(self.orientation).normalize()
    }

    /// A point of the cloud's frame in the world.
    pub fn place(&self, point: DVec3) -> DVec3 {
        self.rotation() * point + DVec3::from_array(self.position)
    }

    /// What places a cloud's points, computed once for all of them.
    pub fn placement(&self) -> impl Fn(DVec3) -> DVec3 {
        let (rotation, origin) = (self.rotation(), DVec3::from_array(self.position));
        move |point| rotation * point + origin
    }

    /// The sensor's pose in the world, as shroud's clouds carry it.
    pub fn pose(&self) -> SensorPose {
        SensorPose {
            position: self.position,
            orientation: self.rotation().to_array(),
        }
    }

    /// The camera's image rectangle in the world, when there is a camera.
    pub fn field_of_view(&self) -> Option<FieldOfView> {
        let camera = self.camera?;
        let rotation = self.rotation();
        Some(FieldOfView {
            apex: self.position,
            axis: (rotation * DVec3::Z).to_array(),
            aperture: Aperture::Rectangle {
                right: (rotation * DVec3::X).to_array(),
                half_angles: [camera.horizontal_fov / 2.0, camera.vertical_fov / 2.0],
            },
            max_range: camera.max_range,
        })
    }
}

impl PinholeCamera {
    /// Pixel `(row, column)`'s ray through its centre, in the camera frame
    /// (unit), for an image of `rows x columns`.
    pub fn ray(&self, rows: usize, columns: usize, row: usize, column: usize) -> DVec3 {
        let offset = |i: usize, n: usize, fov: f64| {
            ((i as f64 + 0.5) / n as f64 * 2.0 - 1.0) * (fov / 2.0).tan()
        };
        DVec3::new(
            offset(column, columns, self.horizontal_fov),
            offset(row, rows, self.vertical_fov),
            1.0,
        )
        .normalize()
    }

    /// A bound on the angle between a pixel's ray and any of its 8
    /// neighbours': their centres' distance on the image plane at unit
    /// depth (a gnomonic projection never shortens an angle).
    pub fn ray_spread(&self, rows: usize, columns: usize) -> f64 {
        let step = |n: usize, fov: f64| 2.0 * (fov / 2.0).tan() / n.max(1) as f64;
        step(columns, self.horizontal_fov).hypot(step(rows, self.vertical_fov))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> PinholeCamera {
        PinholeCamera {
            horizontal_fov: 90f64.to_radians(),
            vertical_fov: 70f64.to_radians(),
            max_range: 8.0,
        }
    }

    #[test]
    fn neighbouring_rays_are_never_farther_apart_than_the_spread() {
        let (rows, columns) = (12, 16);
        let c = camera();
        let spread = c.ray_spread(rows, columns);
        for r in 0..rows - 1 {
            for k in 0..columns - 1 {
                let a = c.ray(rows, columns, r, k);
                for (dr, dk) in [(0, 1), (1, 0), (1, 1)] {
                    let b = c.ray(rows, columns, r + dr, k + dk);
                    assert!(a.angle_between(b) <= spread + 1e-12);
                }
                let d = c.ray(rows, columns, r + 1, k);
                let e = c.ray(rows, columns, r, k + 1);
                assert!(d.angle_between(e) <= spread + 1e-12);
            }
        }
    }

    #[test]
    fn every_pixel_ray_lies_in_the_stated_field_of_view() {
        let mount = CloudMount {
            position: [0.0, 0.0, 3.0],
            orientation: [1.0, 0.0, 0.0, 0.0],
            camera: Some(camera()),
        };
        mount.validate().unwrap();
        let fov = mount.field_of_view().unwrap();
        fov.validate().unwrap();
        let Aperture::Rectangle { right, half_angles } = fov.aperture else {
            panic!("a camera states a rectangle");
        };
        let (axis, right) = (DVec3::from_array(fov.axis), DVec3::from_array(right));
        let up = axis.cross(right);
        let c = mount.camera.unwrap();
        for (r, k) in [(0, 0), (47, 63), (0, 63), (24, 32)] {
            let ray = mount.rotation() * c.ray(48, 64, r, k);
            let along = ray.dot(axis);
            assert!(ray.dot(right).atan2(along).abs() <= half_angles[0]);
            assert!(ray.dot(up).atan2(along).abs() <= half_angles[1]);
        }
        // Straight down from 3 m: the optical axis is the world's -z.
        assert!((axis - DVec3::NEG_Z).length() < 1e-12);
    }

    #[test]
    fn bad_mounts_are_named() {
        let m = CloudMount {
            orientation: [0.0, 0.0, 0.0, 2.0],
            ..CloudMount::default()
        };
        assert!(m
            .validate()
            .unwrap_err()
            .to_string()
            .contains("unit quaternion"));
        let mut m = CloudMount {
            camera: Some(PinholeCamera {
                horizontal_fov: 4.0,
                ..camera()
            }),
            ..CloudMount::default()
        };
        assert!(m.validate().unwrap_err().to_string().contains("horizontal"));
        m.position[0] = f64::NAN;
        assert!(m.validate().unwrap_err().to_string().contains("position"));
    }
}
