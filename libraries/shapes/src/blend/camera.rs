//! A pinhole camera (look-at plus perspective) standing in for the OpenGL view,
//! projection and viewport matrices of Zou et al., Section 3.2: world points to
//! pixels with a depth in [0, 1), and back.

use super::error::BlendError;
use glam::{DVec2, DVec3};

/// Camera looking from `eye` at `target`; pixel (0, 0) is the top-left corner and
/// depth grows linearly from 0 at `near` to 1 at `far` (1.0 is "no surface").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub eye: DVec3,
    pub target: DVec3,
    pub up: DVec3,
    /// Vertical field of view, radians.
    pub fov_y: f64,
    pub width: usize,
    pub height: usize,
    pub near: f64,
    pub far: f64,
}

/// The camera's orthonormal frame, cached.
#[derive(Debug, Clone, Copy)]
struct Frame {
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    tan_y: f64,
    aspect: f64,
}

impl Camera {
    /// Checks the parameters (finite, positive sizes, 0 < fov < pi, 0 < near < far,
    /// eye != target, up not along the view direction).
    pub fn validate(&self) -> Result<(), BlendError> {
        let bad = |reason| Err(BlendError::DegenerateCamera { reason });
        if !(self.eye.is_finite() && self.target.is_finite() && self.up.is_finite()) {
            return bad("non-finite eye, target or up");
        }
        if self.width == 0 || self.height == 0 || self.width > 1 << 14 || self.height > 1 << 14 {
            return bad("image size must be 1..=16384 pixels each way");
        }
        if self.width * self.height > 1 << 24 {
            return bad("image larger than 16 megapixels");
        }
        if !(self.fov_y > 0.0 && self.fov_y < 3.1) {
            return bad("field of view must be in (0, 3.1) radians");
        }
        if !(self.near > 0.0 && self.far > self.near && self.far.is_finite()) {
            return bad("need 0 < near < far");
        }
        let forward = (self.target - self.eye).normalize_or_zero();
        if forward == DVec3::ZERO {
            return bad("eye and target coincide");
        }
        if forward.cross(self.up).length() < 1e-9 * self.up.length().max(1e-300) {
            return bad("up is parallel to the view direction");
        }
        Ok(())
    }

    fn frame(&self) -> Frame {
        let forward = (self.target - self.eye).normalize_or(DVec3::NEG_Z);
        let right = forward.cross(self.up).normalize_or(DVec3::X);
        Frame {
            forward,
            right,
            up: right.cross(forward),
            tan_y: (0.5 * self.fov_y).tan(),
            aspect: self.width as f64 / self.height as f64,
        }
    }

    /// Pixel coordinates (continuous; pixel `(i, j)` covers `[i, i+1) x [j, j+1)`)
    /// and depth of `p`, or `None` outside the view frustum's depth range.
    pub fn project(&self, p: DVec3) -> Option<(DVec2, f64)> {
        let f = self.frame();
        let d = p - self.eye;
        let z = d.dot(f.forward);
        if !(z > self.near && z < self.far) {
            return None;
        }
        let x_ndc = d.dot(f.right) / (z * f.tan_y * f.aspect);
        let y_ndc = d.dot(f.up) / (z * f.tan_y);
        let pixel = DVec2::new(
            0.5 * (x_ndc + 1.0) * self.width as f64,
            0.5 * (1.0 - y_ndc) * self.height as f64,
        );
        Some((pixel, (z - self.near) / (self.far - self.near)))
    }

    /// The world point seen at `pixel` with `depth` (inverse of [`Camera::project`]).
    pub fn unproject(&self, pixel: DVec2, depth: f64) -> DVec3 {
        let f = self.frame();
        let z = self.near + depth * (self.far - self.near);
        let x_ndc = 2.0 * pixel.x / self.width as f64 - 1.0;
        let y_ndc = 1.0 - 2.0 * pixel.y / self.height as f64;
        self.eye + z * (f.forward + x_ndc * f.tan_y * f.aspect * f.right + y_ndc * f.tan_y * f.up)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn project_unproject_round_trip() {
        let cam = Camera {
            eye: DVec3::new(0.0, -3.0, 4.0),
            target: DVec3::ZERO,
            up: DVec3::Z,
            fov_y: 0.9,
            width: 640,
            height: 480,
            near: 0.1,
            far: 20.0,
        };
        cam.validate().unwrap();
        let p = DVec3::new(0.4, 0.3, -0.2);
        let (px, depth) = cam.project(p).unwrap();
        assert!((cam.unproject(px, depth) - p).length() < 1e-12);
        let (centre, _) = cam.project(DVec3::ZERO).unwrap();
        assert!((centre - DVec2::new(320.0, 240.0)).length() < 1e-9);
        let bad = Camera {
            up: DVec3::new(0.0, -3.0, 4.0),
            ..cam
        };
        assert!(bad.validate().is_err());
    }
}
