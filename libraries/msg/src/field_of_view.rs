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

/// A valid field of view (a cone), for tests of consumers.
/// Public only for the tests of other crates.
#[doc(hidden)]
pub fn sample_field_of_view() -> FieldOfView {
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

    fn any_f64() -> impl proptest::strategy::Strategy<Value = f64> {
        use proptest::prelude::*;
        prop_oneof![
            -10.0..10.0f64,
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(-0.0),
            any::<f64>()
        ]
    }

    /// A field of view near a valid one: unit directions (the right one
    /// perpendicular) from random vectors, then some values replaced by
    /// anything, so that both sides of every check are reached.
    fn near_valid() -> impl proptest::strategy::Strategy<Value = FieldOfView> {
        use proptest::prelude::*;
        let vector = proptest::array::uniform3(-1.0..1.0f64);
        (
            vector.clone(),
            vector,
            0.01..1.5f64,
            0.01..1.5f64,
            0.1..9.0f64,
            any::<bool>(),
        )
            .prop_filter_map("degenerate", |(a, r, h0, h1, range, cone)| {
                let norm = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
                let axis = a.map(|x| x / norm(a));
                let dot: f64 = (0..3).map(|i| r[i] * axis[i]).sum();
                let r: [f64; 3] = std::array::from_fn(|i| r[i] - dot * axis[i]);
                let right = r.map(|x| x / norm(r));
                (norm(a) > 0.1 && norm(r) > 0.1).then_some(FieldOfView {
                    apex: a,
                    axis,
                    aperture: if cone {
                        Aperture::Cone { half_angle: h0 }
                    } else {
                        Aperture::Rectangle {
                            right,
                            half_angles: [h0, h1],
                        }
                    },
                    max_range: range,
                })
            })
    }

    proptest::proptest! {
        #[test]
        fn valid_fields_of_view_are_accepted_and_round_trip(fov in near_valid()) {
            proptest::prop_assert!(fov.validate().is_ok(), "{fov:?}");
            let bytes = rmp_serde::to_vec_named(&fov).unwrap();
            let back: FieldOfView = rmp_serde::from_slice(&bytes).unwrap();
            proptest::prop_assert_eq!(back, fov);
        }

        #[test]
        fn a_spoiled_value_is_refused(
            fov in near_valid(),
            which in 0..5usize,
            side in 0..2usize,
            bad in any_f64(),
        ) {
            let mut fov = fov;
            let spoiled = match which {
                0 => { fov.apex[1] = bad; !bad.is_finite() }
                1 => {
                    fov.axis[2] = bad;
                    let norm = fov.axis.iter().map(|x| x * x).sum::<f64>().sqrt();
                    !(norm.is_finite() && (norm - 1.0).abs() <= UNIT_TOLERANCE)
                }
                2 => { fov.max_range = bad; !(bad.is_finite() && bad > 0.0) }
                3 => match &mut fov.aperture {
                    Aperture::Cone { half_angle } => {
                        *half_angle = bad;
                        !(bad > 0.0 && bad < std::f64::consts::FRAC_PI_2)
                    }
                    Aperture::Rectangle { half_angles, .. } => {
                        half_angles[side] = bad;
                        !(bad > 0.0 && bad < std::f64::consts::FRAC_PI_2)
                    }
                },
                _ => match &mut fov.aperture {
                    Aperture::Rectangle { right, .. } => {
                        // A spoiled component: still unit and perpendicular
                        // only by a fluke, which the check mirrors.
                        right[side] = bad;
                        let norm = right.iter().map(|x| x * x).sum::<f64>().sqrt();
                        let dot: f64 = (0..3).map(|i| right[i] * fov.axis[i]).sum();
                        !(right.iter().all(|x| x.is_finite())
                            && (norm - 1.0).abs() <= UNIT_TOLERANCE
                            && dot.abs() <= UNIT_TOLERANCE)
                    }
                    Aperture::Cone { .. } => false,
                },
            };
            if spoiled {
                proptest::prop_assert!(fov.validate().is_err(), "{fov:?}");
            }
        }

        /// Whatever numbers a stranger sends, validation answers without a
        /// panic, and what it accepts survives the wire unchanged.
        #[test]
        fn any_field_of_view_is_judged_and_accepted_ones_round_trip(
            apex in proptest::array::uniform3(any_f64()),
            axis in proptest::array::uniform3(any_f64()),
            right in proptest::array::uniform3(any_f64()),
            angles in proptest::array::uniform2(any_f64()),
            range in any_f64(),
            cone in proptest::bool::ANY,
        ) {
            let aperture = if cone {
                Aperture::Cone { half_angle: angles[0] }
            } else {
                Aperture::Rectangle { right, half_angles: angles }
            };
            let fov = FieldOfView { apex, axis, aperture, max_range: range };
            if fov.validate().is_ok() {
                let bytes = rmp_serde::to_vec_named(&fov).unwrap();
                let back: FieldOfView = rmp_serde::from_slice(&bytes).unwrap();
                proptest::prop_assert_eq!(back, fov);
            }
        }
    }

    /// The wire layout `docs/formats.md` documents, read back generically.
    #[test]
    fn the_wire_layout_is_the_documented_one() {
        let cone = FieldOfView {
            aperture: Aperture::Cone { half_angle: 0.5 },
            ..sample_field_of_view()
        };
        let read = |fov: &FieldOfView| -> serde_json::Value {
            rmp_serde::from_slice(&rmp_serde::to_vec_named(fov).unwrap()).unwrap()
        };
        assert_eq!(
            read(&sample_field_of_view()),
            serde_json::json!({"apex": [0.0, 0.0, 2.0], "axis": [0.0, 0.0, -1.0],
                "aperture": {"rectangle": {"right": [1.0, 0.0, 0.0], "half_angles": [0.6, 0.45]}},
                "max_range": 4.0})
        );
        assert_eq!(
            read(&cone)["aperture"],
            serde_json::json!({"cone": {"half_angle": 0.5}})
        );
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
