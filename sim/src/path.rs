//! Closed Lissajous paths along which the moving spheres' centres travel over time.

use crate::error::{check_finite_all, SceneError};
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_2;

/// A centre moving as `centre[k] + amplitude[k] * sin(angular_speed[k] * t + phase[k])`
/// per axis k, t in seconds. The path is closed (the animation loops) whenever the
/// angular speeds are rational multiples of each other; circles and ellipses are
/// the special case of equal speeds with a quarter-turn phase offset.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct LissajousPath {
    /// Mean position of the moving point.
    pub centre: [f64; 3],
    /// Half-extent of the motion along x, y, z.
    pub amplitude: [f64; 3],
    /// Angular speed per axis in rad/s.
    pub angular_speed: [f64; 3],
    /// Phase per axis in radians at t = 0.
    pub phase: [f64; 3],
}

impl Default for LissajousPath {
    /// A point that stays at the origin.
    fn default() -> Self {
        Self::stationary([0.0; 3])
    }
}

impl LissajousPath {
    /// A path that never moves: useful for a fixed sphere.
    pub fn stationary(centre: [f64; 3]) -> Self {
        Self {
            centre,
            amplitude: [0.0; 3],
            angular_speed: [0.0; 3],
            phase: [0.0; 3],
        }
    }

    /// A horizontal ellipse (radii `semi_axes` along x and y) traversed
    /// counter-clockwise seen from +z, starting on the +x side at t = 0.
    pub fn ellipse(centre: [f64; 3], semi_axes: [f64; 2], angular_speed: f64) -> Self {
        Self {
            centre,
            amplitude: [semi_axes[0], semi_axes[1], 0.0],
            angular_speed: [angular_speed, angular_speed, 0.0],
            phase: [FRAC_PI_2, 0.0, 0.0],
        }
    }

    /// Position on the path at `time` seconds.
    pub fn position(&self, time: f64) -> [f64; 3] {
        std::array::from_fn(|k| {
            self.centre[k]
                + self.amplitude[k] * (self.angular_speed[k] * time + self.phase[k]).sin()
        })
    }

    /// Checks that every field is finite; `parameter` prefixes the reported name.
    pub(crate) fn validate(&self, parameter: &str) -> Result<(), SceneError> {
        check_finite_all(&format!("{parameter}.centre"), &self.centre)?;
        check_finite_all(&format!("{parameter}.amplitude"), &self.amplitude)?;
        check_finite_all(&format!("{parameter}.angular_speed"), &self.angular_speed)?;
        check_finite_all(&format!("{parameter}.phase"), &self.phase)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn stationary_path_stays_put() {
        let path = LissajousPath::stationary([1.0, 2.0, 3.0]);
        assert!(close(path.position(0.0), [1.0, 2.0, 3.0]));
        assert!(close(path.position(17.5), [1.0, 2.0, 3.0]));
    }

    #[test]
    fn ellipse_starts_on_x_axis_and_closes() {
        let path = LissajousPath::ellipse([0.0, 0.0, 1.0], [2.0, 1.0], 0.5);
        assert!(close(path.position(0.0), [2.0, 0.0, 1.0]));
        assert!(close(path.position(PI), [0.0, 1.0, 1.0]));
        assert!(close(path.position(4.0 * PI), path.position(0.0)));
    }

    #[test]
    fn non_finite_field_is_reported_by_name() {
        let mut path = LissajousPath::default();
        path.phase[2] = f64::NAN;
        let err = path.validate("paths[1]").unwrap_err();
        assert!(err.to_string().contains("paths[1].phase[2]"), "{err}");
    }
}
