//! The deterministic orthonormal frame (u, v, w) attached to a fitting direction.

use glam::DVec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum FrameError {
    #[error("the fitting direction must be finite and non-zero, got ({0:e}, {1:e}, {2:e})")]
    BadDirection(f64, f64, f64),
}

/// Orthonormal frame of a surrogate. `w` points *against* the fitting (viewing)
/// direction, so heights grow toward the viewer; `u`, `v` span the parameter plane.
///
/// The choice of `u` is deterministic: it is the cross product of `w` with the world
/// axis least aligned with `w`, so the same direction always yields the same frame
/// and a stored surrogate can be re-evaluated bit for bit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Frame {
    /// The unit fitting direction the user gave (the viewer looks along it).
    pub direction: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
}

impl Frame {
    pub fn from_direction(direction: DVec3) -> Result<Self, FrameError> {
        let bad = || FrameError::BadDirection(direction.x, direction.y, direction.z);
        // Scale by the largest component first, so that directions of any finite
        // magnitude (1e300 or 1e-200) normalise without overflow or underflow.
        let largest = direction.abs().max_element();
        if !direction.is_finite() || largest == 0.0 {
            return Err(bad());
        }
        let scaled = direction / largest;
        let d = scaled / scaled.length();
        if !d.is_finite() {
            return Err(bad());
        }
        let w = -d;
        let a = w.abs();
        // The world axis least aligned with w; ties resolved in x, y, z order.
        let axis = if a.x <= a.y && a.x <= a.z {
            DVec3::X
        } else if a.y <= a.z {
            DVec3::Y
        } else {
            DVec3::Z
        };
        let u = axis.cross(w).normalize();
        let v = w.cross(u);
        Ok(Self {
            direction: d,
            u,
            v,
            w,
        })
    }

    /// Frame coordinates (u, v, w) of a world point.
    #[inline]
    pub fn to_local(&self, p: DVec3) -> DVec3 {
        DVec3::new(p.dot(self.u), p.dot(self.v), p.dot(self.w))
    }

    /// World point of frame coordinates (u, v, w).
    #[inline]
    pub fn to_world(&self, l: DVec3) -> DVec3 {
        self.u * l.x + self.v * l.y + self.w * l.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_right_handed() {
        for d in [
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(-1e-8, 5.0, 0.0),
            DVec3::X,
        ] {
            let f = Frame::from_direction(d).unwrap();
            assert!((f.u.length() - 1.0).abs() < 1e-12);
            assert!((f.v.length() - 1.0).abs() < 1e-12);
            assert!(f.u.dot(f.v).abs() < 1e-12 && f.u.dot(f.w).abs() < 1e-12);
            assert!((f.u.cross(f.v) - f.w).length() < 1e-12);
            assert!((f.w + d.normalize()).length() < 1e-12);
            let p = DVec3::new(0.3, -2.0, 7.0);
            assert!((f.to_world(f.to_local(p)) - p).length() < 1e-12);
        }
    }

    #[test]
    fn down_direction_gives_z_heights() {
        let f = Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap();
        assert_eq!(f.w, DVec3::Z);
    }

    #[test]
    fn directions_of_extreme_magnitude_normalise() {
        for d in [
            DVec3::new(1e300, 1e300, -1e300),
            DVec3::new(0.0, 0.0, -1e-200),
            DVec3::new(0.0, -1e200, -1e200),
        ] {
            let f = Frame::from_direction(d).unwrap();
            assert!((f.direction.length() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn zero_and_nan_directions_are_rejected() {
        assert!(Frame::from_direction(DVec3::ZERO).is_err());
        assert!(Frame::from_direction(DVec3::new(f64::NAN, 0.0, 1.0)).is_err());
    }
}
