//! A sensor's field of view on the wire: the convex region its rays could
//! sample (a cone or a rectangular pyramid from its optical centre, cut at its
//! range), so that a consumer knows where the cloud says nothing at all.

use super::error::MessageError;
use serde::{Deserialize, Serialize};

/// How far a direction may be from unit length, or two directions from
/// perpendicular, on the wire (encoders normalise; consumers renormalise).
const UNIT_TOLERANCE: f64 = 1e-6;

/// The region a sensor's rays covered when it took a cloud, in the frame of
/// the cloud's points: the points of its [`Aperture`] around `axis` from
/// `apex`, no farther than `max_range` from it. Everything outside it the
/// sensor did not look at, whatever the cloud's points suggest.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FieldOfView {
    /// The optical centre: every ray starts here.
    pub apex: [f64; 3],
    /// The look direction (unit).
    pub axis: [f64; 3],
    pub aperture: Aperture,
    /// The farthest a return can come from, metres (finite, > 0).
    pub max_range: f64,
}

/// The angular extent of a field of view around its axis. Half angles are in
/// radians, strictly between 0 and pi/2, so the region is convex.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Aperture {
    /// Rays within `half_angle` of the axis (a round lens, a spinning
    /// lidar's beam cone).
    Cone { half_angle: f64 },
    /// Rays within `half_angles[0]` of the axis towards `right` (unit,
    /// perpendicular to the axis) and `half_angles[1]` towards the axis cross
    /// `right`: a depth camera's image rectangle.
    Rectangle {
        right: [f64; 3],
        half_angles: [f64; 2],
    },
}

impl FieldOfView {
    /// Refuses a field of view that is not a convex region: non-finite
    /// values, directions that are not unit or not perpendicular, half angles
    /// outside (0, pi/2), a range that is not a positive distance.
    pub fn validate(&self) -> Result<(), MessageError> {
        let bad = |reason: String| {
            Err(MessageError::Invalid {
                field: "field_of_view",
                reason,
            })
        };
        if !self.apex.iter().all(|v| v.is_finite()) {
            return bad(format!("apex {:?} is not finite", self.apex));
        }
        check_unit("axis", self.axis)?;
        if !(self.max_range.is_finite() && self.max_range > 0.0) {
            return bad(format!(
                "max_range {} is not a positive distance",
                self.max_range
            ));
        }
        match self.aperture {
            Aperture::Cone { half_angle } => check_half_angle(half_angle),
            Aperture::Rectangle { right, half_angles } => {
                check_unit("right", right)?;
                let dot: f64 = (0..3).map(|i| right[i] * self.axis[i]).sum();
                if dot.abs() > UNIT_TOLERANCE {
                    return bad(format!("right is not perpendicular to axis (dot {dot})"));
                }
                half_angles.iter().try_for_each(|a| check_half_angle(*a))
            }
        }
    }
}

fn check_unit(name: &str, v: [f64; 3]) -> Result<(), MessageError> {
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if v.iter().all(|x| x.is_finite()) && (norm - 1.0).abs() <= UNIT_TOLERANCE {
        Ok(())
    } else {
        Err(MessageError::Invalid {
            field: "field_of_view",
            reason: format!("{name} {v:?} is not a unit vector"),
        })
    }
}

fn check_half_angle(a: f64) -> Result<(), MessageError> {
    if a.is_finite() && a > 0.0 && a < std::f64::consts::FRAC_PI_2 {
        Ok(())
    } else {
        Err(MessageError::Invalid {
            field: "field_of_view",
            reason: format!("half angle {a} rad is not in (0, pi/2)"),
        })
    }
}

#[cfg(test)]
pub(crate) fn sample_field_of_view() -> FieldOfView {
    FieldOfView {
        apex: [0.0, 0.0, 2.0],
        axis: [0.0, 0.0, -1.0],
        aperture: Aperture::Rectangle {
            right: [1.0, 0.0, 0.0],
            half_angles: [0.6, 0.45],
        },
        max_range: 4.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_convex_field_of_view_is_valid() {
        sample_field_of_view().validate().unwrap();
        let cone = FieldOfView {
            aperture: Aperture::Cone { half_angle: 0.3 },
            ..sample_field_of_view()
        };
        cone.validate().unwrap();
    }

    #[test]
    fn every_defect_is_named() {
        let base = sample_field_of_view();
        let cases = [
            (
                FieldOfView {
                    apex: [f64::NAN, 0.0, 0.0],
                    ..base
                },
                "apex",
            ),
            (
                FieldOfView {
                    axis: [0.0, 0.0, -2.0],
                    ..base
                },
                "axis",
            ),
            (
                FieldOfView {
                    max_range: 0.0,
                    ..base
                },
                "max_range",
            ),
            (
                FieldOfView {
                    max_range: f64::INFINITY,
                    ..base
                },
                "max_range",
            ),
            (
                FieldOfView {
                    aperture: Aperture::Cone { half_angle: 1.6 },
                    ..base
                },
                "half angle",
            ),
            (
                FieldOfView {
                    aperture: Aperture::Rectangle {
                        right: [0.0, 0.6, -0.8],
                        half_angles: [0.5, 0.5],
                    },
                    ..base
                },
                "perpendicular",
            ),
            (
                FieldOfView {
                    aperture: Aperture::Rectangle {
                        right: [1.0, 0.0, 0.0],
                        half_angles: [0.5, 0.0],
                    },
                    ..base
                },
                "half angle",
            ),
        ];
        for (fov, word) in cases {
            let e = fov.validate().unwrap_err().to_string();
            assert!(
                e.contains("field_of_view") && e.contains(word),
                "{word}: {e}"
            );
        }
    }
}
