//! Where the scanner is and where it looks, over time.

use crate::error::{check_finite_all, SceneError};
use crate::path::LissajousPath;
use serde::{Deserialize, Serialize};

/// The scanner's pose over time: its position follows a [`LissajousPath`] (a
/// fixed point, an orbit, any Lissajous sweep) and it always looks at `target`.
/// The image's up direction is world +z projected onto the image plane (+y
/// when looking straight up or down).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ScanPose {
    /// Path of the scanner's optical centre.
    pub position: LissajousPath,
    /// The point the scanner looks at (the centre of its field of view).
    pub target: [f64; 3],
}

/// The scanner's frame at one time: position and three orthonormal axes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SensorPose {
    /// Optical centre, world coordinates.
    pub position: [f64; 3],
    /// Unit viewing direction (centre of the field of view).
    pub forward: [f64; 3],
    /// Unit vector to the right of the image (`forward x up`).
    pub right: [f64; 3],
    /// Unit vector to the top of the image.
    pub up: [f64; 3],
}

impl Default for ScanPose {
    /// Orbiting the origin at radius 4, 9 above it (looking down at 66°, from
    /// 9.85 away), one turn every 4π s (0.5 rad/s).
    fn default() -> Self {
        Self::orbit([0.0; 3], 4.0, 9.0, 0.5)
    }
}

impl ScanPose {
    /// A scanner standing still at `position`, looking at `target`.
    pub fn fixed(position: [f64; 3], target: [f64; 3]) -> Self {
        Self {
            position: LissajousPath::stationary(position),
            target,
        }
    }

    /// A scanner circling `target` counter-clockwise (seen from +z) at `radius`,
    /// `height` above it, at `angular_speed` rad/s, starting on the +x side.
    pub fn orbit(target: [f64; 3], radius: f64, height: f64, angular_speed: f64) -> Self {
        let centre = [target[0], target[1], target[2] + height];
        Self {
            position: LissajousPath::ellipse(centre, [radius, radius], angular_speed),
            target,
        }
    }

    /// Whether the position changes with time.
    pub fn moves(&self) -> bool {
        let p = &self.position;
        (0..3).any(|k| p.amplitude[k] != 0.0 && p.angular_speed[k] != 0.0)
    }

    /// Checks that every field is finite.
    pub(crate) fn validate(&self, parameter: &str) -> Result<(), SceneError> {
        self.position.validate(&format!("{parameter}.position"))?;
        check_finite_all(&format!("{parameter}.target"), &self.target)
    }

    /// The sensor frame at `time`; fails if the scanner sits on its target.
    pub fn sensor(&self, time: f64) -> Result<SensorPose, SceneError> {
        let position = self.position.position(time);
        let forward = normalize(sub(self.target, position)).ok_or(SceneError::Degenerate {
            parameter: "pose".into(),
            reason: "the scanner position coincides with its target",
        })?;
        // Looking (almost) straight up or down, world +z gives no right vector.
        let right = normalize(cross(forward, [0.0, 0.0, 1.0]))
            .filter(|_| forward[2].abs() < 1.0 - 1e-9)
            .or_else(|| normalize(cross(forward, [0.0, 1.0, 0.0])))
            .unwrap_or([1.0, 0.0, 0.0]);
        let up = cross(right, forward);
        Ok(SensorPose {
            position,
            forward,
            right,
            up,
        })
    }
}

impl SensorPose {
    /// Unit direction of the ray at azimuth `azimuth` (to the right) and
    /// elevation `elevation` (up) from the forward axis, both in radians, given
    /// as `(sin, cos)` pairs.
    #[inline]
    pub(crate) fn direction(&self, azimuth: (f64, f64), elevation: (f64, f64)) -> [f64; 3] {
        let (sa, ca) = azimuth;
        let (se, ce) = elevation;
        std::array::from_fn(|k| ce * (ca * self.forward[k] + sa * self.right[k]) + se * self.up[k])
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `v / |v|`, or `None` for a zero or non-finite vector.
fn normalize(v: [f64; 3]) -> Option<[f64; 3]> {
    let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (length > 0.0 && length.is_finite()).then(|| v.map(|c| c / length))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    fn assert_orthonormal(s: &SensorPose) {
        for (a, b) in [(s.forward, s.right), (s.right, s.up), (s.up, s.forward)] {
            assert!(dot(a, b).abs() < 1e-12);
        }
        for v in [s.forward, s.right, s.up] {
            assert!((dot(v, v) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn frames_are_right_handed_and_upright() {
        let s = ScanPose::fixed([-5.0, 0.0, 0.0], [0.0; 3])
            .sensor(0.0)
            .unwrap();
        assert_eq!(s.forward, [1.0, 0.0, 0.0]);
        assert_eq!(s.right, [0.0, -1.0, 0.0]);
        assert_eq!(s.up, [0.0, 0.0, 1.0]);
        let down = ScanPose::fixed([1.0, 2.0, 10.0], [1.0, 2.0, 0.0])
            .sensor(3.0)
            .unwrap();
        assert_eq!(down.forward, [0.0, 0.0, -1.0]);
        assert_eq!(down.right, [1.0, 0.0, 0.0]);
        assert_eq!(down.up, [0.0, 1.0, 0.0]);
        let orbit = ScanPose::orbit([1.0, 1.0, 0.0], 3.0, 2.0, 0.7);
        assert!(orbit.moves() && !ScanPose::fixed([0.0; 3], [1.0; 3]).moves());
        for t in [0.0, 1.0, 2.5] {
            let s = orbit.sensor(t).unwrap();
            assert_orthonormal(&s);
            assert!(s.up[2] > 0.0);
            let p = s.position;
            assert!(((p[0] - 1.0).hypot(p[1] - 1.0) - 3.0).abs() < 1e-12 && p[2] == 2.0);
        }
        assert_eq!(orbit.sensor(0.0).unwrap().position, [4.0, 1.0, 2.0]);
    }

    #[test]
    fn directions_span_the_field_of_view() {
        let s = ScanPose::fixed([0.0, 0.0, 10.0], [0.0; 3])
            .sensor(0.0)
            .unwrap();
        let a = 0.3f64;
        let d = s.direction(a.sin_cos(), (0.0, 1.0));
        assert!((dot(d, s.forward) - a.cos()).abs() < 1e-12 && dot(d, s.right) > 0.0);
        let d = s.direction((0.0, 1.0), a.sin_cos());
        assert!((dot(d, s.up) - a.sin()).abs() < 1e-12);
    }

    #[test]
    fn sitting_on_the_target_is_an_error() {
        let err = ScanPose::fixed([1.0; 3], [1.0; 3]).sensor(0.0).unwrap_err();
        assert!(err.to_string().contains("pose"), "{err}");
        let mut pose = ScanPose::default();
        pose.target[1] = f64::INFINITY;
        assert!(pose
            .validate("pose")
            .unwrap_err()
            .to_string()
            .contains("pose.target[1]"));
    }
}
