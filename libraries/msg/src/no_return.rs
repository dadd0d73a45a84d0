//! Where a sensor looked and got nothing back, on the wire: cones of
//! directions from its optical centre whose rays returned no range. A black
//! object, a mirror or glass returns nothing, exactly like empty space out to
//! the range, so a consumer must count these directions as unseen.

use super::error::MessageError;
use serde::{Deserialize, Serialize};

/// Most cones one message may carry: a producer merges neighbouring rays into
/// wider cones to stay under it, and a consumer's cost stays bounded.
pub const MAX_DARK_CONES: usize = 1024;

/// How far a cone's axis may be from unit length on the wire.
const UNIT_TOLERANCE: f64 = 1e-6;

/// The directions, from `apex`, in which the sensor's rays returned nothing:
/// the union of `cones`. Each cone covers its rays and the space between them
/// and their neighbours. Which empty rays a producer lists is its choice;
/// shroud's (`cloud::dark_cones`) lists the groups of empty rays that hold a
/// 2 x 2 block, so that an object touching such a ray lies in some cone
/// wherever it is along the ray, and leaves lone dropouts out.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NoReturn {
    /// The optical centre, in the frame of the cloud's points.
    pub apex: [f64; 3],
    /// At most [`MAX_DARK_CONES`].
    pub cones: Vec<DarkCone>,
}

/// The directions within `half_angle` (radians, in (0, pi/2)) of `axis`
/// (unit).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DarkCone {
    pub axis: [f64; 3],
    pub half_angle: f64,
}

impl NoReturn {
    /// Refuses a non-finite apex, more than [`MAX_DARK_CONES`] cones, an axis
    /// that is not unit, a half angle outside (0, pi/2).
    pub fn validate(&self) -> Result<(), MessageError> {
        let bad = |reason: String| {
            Err(MessageError::Invalid {
                field: "no_return",
                reason,
            })
        };
        if !self.apex.iter().all(|v| v.is_finite()) {
            return bad(format!("apex {:?} is not finite", self.apex));
        }
        if self.cones.len() > MAX_DARK_CONES {
            return bad(format!(
                "{} cones, at most {MAX_DARK_CONES}",
                self.cones.len()
            ));
        }
        for (k, cone) in self.cones.iter().enumerate() {
            let norm = cone.axis.iter().map(|x| x * x).sum::<f64>().sqrt();
            if !(cone.axis.iter().all(|x| x.is_finite()) && (norm - 1.0).abs() <= UNIT_TOLERANCE) {
                return bad(format!(
                    "cone {k}: axis {:?} is not a unit vector",
                    cone.axis
                ));
            }
            let a = cone.half_angle;
            if !(a.is_finite() && a > 0.0 && a < std::f64::consts::FRAC_PI_2) {
                return bad(format!("cone {k}: half angle {a} rad is not in (0, pi/2)"));
            }
        }
        Ok(())
    }
}

/// Valid empty rays (an apex and two cones), for tests of consumers.
/// Public only for the tests of other crates.
#[doc(hidden)]
pub fn sample_no_return() -> NoReturn {
    NoReturn {
        apex: [0.0, 0.0, 2.0],
        cones: vec![
            DarkCone {
                axis: [0.0, 0.0, -1.0],
                half_angle: 0.05,
            },
            DarkCone {
                axis: [0.6, 0.0, -0.8],
                half_angle: 0.02,
            },
        ],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn the_sample_is_valid_and_too_many_cones_are_refused() {
        sample_no_return().validate().unwrap();
        let mut many = sample_no_return();
        many.cones = vec![many.cones[0]; MAX_DARK_CONES + 1];
        let err = many.validate().unwrap_err().to_string();
        assert!(err.contains("1025 cones"), "{err}");
    }

    fn any_f64() -> impl Strategy<Value = f64> {
        prop_oneof![
            -2.0..2.0f64,
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(0.0),
            Just(std::f64::consts::FRAC_PI_2),
            any::<f64>()
        ]
    }

    fn valid() -> impl Strategy<Value = NoReturn> {
        let cone = (proptest::array::uniform3(-1.0..1.0f64), 0.001..1.5f64).prop_filter_map(
            "degenerate axis",
            |(a, half_angle)| {
                let norm = a.iter().map(|x| x * x).sum::<f64>().sqrt();
                (norm > 0.1).then(|| DarkCone {
                    axis: a.map(|x| x / norm),
                    half_angle,
                })
            },
        );
        (
            proptest::array::uniform3(-5.0..5.0f64),
            proptest::collection::vec(cone, 0..20),
        )
            .prop_map(|(apex, cones)| NoReturn { apex, cones })
    }

    proptest! {
        #[test]
        fn valid_ones_round_trip(nr in valid()) {
            prop_assert!(nr.validate().is_ok(), "{nr:?}");
            let bytes = rmp_serde::to_vec_named(&nr).unwrap();
            let back: NoReturn = rmp_serde::from_slice(&bytes).unwrap();
            prop_assert_eq!(back, nr);
        }

        #[test]
        fn a_spoiled_value_is_refused(nr in valid(), which in 0..3usize, i in 0..3usize, bad in any_f64()) {
            let mut nr = nr;
            let spoiled = match (which, nr.cones.first_mut()) {
                (0, _) | (_, None) => { nr.apex[i] = bad; !bad.is_finite() }
                (1, Some(c)) => {
                    c.axis[i] = bad;
                    let norm = c.axis.iter().map(|x| x * x).sum::<f64>().sqrt();
                    !(norm.is_finite() && (norm - 1.0).abs() <= UNIT_TOLERANCE)
                }
                (_, Some(c)) => {
                    c.half_angle = bad;
                    !(bad > 0.0 && bad < std::f64::consts::FRAC_PI_2)
                }
            };
            prop_assert_eq!(nr.validate().is_err(), spoiled, "{:?}", nr);
        }
    }
}
