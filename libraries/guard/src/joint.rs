//! Joints of a serial chain, URDF style: an origin transform (the child link's
//! frame in the parent link's frame at zero joint value, `xyz` then `rpy`) followed
//! by the joint's motion about or along its axis.

use super::error::GuardError;
use glam::{DAffine3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// How a joint moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    /// Rotation about the axis by the joint value (radians, right-handed).
    Revolute,
    /// Translation along the axis by the joint value (metres).
    Prismatic,
    /// No motion; takes no joint value.
    Fixed,
}

/// Closed range of joint values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Limits {
    pub lower: f64,
    pub upper: f64,
}

impl Limits {
    pub fn contains(&self, q: f64) -> bool {
        (self.lower..=self.upper).contains(&q)
    }
}

/// A validated joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    name: String,
    kind: JointKind,
    axis: DVec3,
    origin: DAffine3,
    limits: Option<Limits>,
}

impl Joint {
    /// Checks the numbers: finite origin, a finite non-zero axis (normalised here;
    /// ignored for fixed joints), limits finite and ordered (none on fixed joints).
    pub fn new(
        name: &str,
        kind: JointKind,
        axis: [f64; 3],
        xyz: [f64; 3],
        rpy: [f64; 3],
        limits: Option<[f64; 2]>,
    ) -> Result<Self, GuardError> {
        if name.is_empty() {
            return Err(GuardError::EmptyName { kind: "joint" });
        }
        let origin = origin_from_xyz_rpy(&format!("joint '{name}' origin"), xyz, rpy)?;
        let axis = match kind {
            JointKind::Fixed => DVec3::Z,
            _ => unit_axis(axis).ok_or_else(|| GuardError::BadAxis {
                joint: name.to_string(),
                axis,
            })?,
        };
        let limits = match (kind, limits) {
            (_, None) => None,
            (JointKind::Fixed, Some(_)) => return Err(GuardError::FixedWithLimits(name.into())),
            (_, Some([lower, upper])) => {
                if !(lower.is_finite() && upper.is_finite() && lower <= upper) {
                    return Err(GuardError::BadLimits {
                        joint: name.to_string(),
                        lower,
                        upper,
                    });
                }
                Some(Limits { lower, upper })
            }
        };
        Ok(Self {
            name: name.to_string(),
            kind,
            axis,
            origin,
            limits,
        })
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn kind(&self) -> JointKind {
        self.kind
    }

    /// Unit axis in the child link's frame (the frame after the origin).
    pub fn axis(&self) -> DVec3 {
        self.axis
    }

    /// The child link's frame in the parent's at joint value zero.
    pub fn origin(&self) -> &DAffine3 {
        &self.origin
    }

    pub fn limits(&self) -> Option<Limits> {
        self.limits
    }

    /// Whether the joint takes a value (revolute or prismatic).
    pub fn is_actuated(&self) -> bool {
        self.kind != JointKind::Fixed
    }

    /// The child link's frame in the parent's at joint value `q`.
    pub fn transform(&self, q: f64) -> DAffine3 {
        match self.kind {
            JointKind::Fixed => self.origin,
            JointKind::Revolute => self.origin * DAffine3::from_axis_angle(self.axis, q),
            JointKind::Prismatic => self.origin * DAffine3::from_translation(self.axis * q),
        }
    }
}

/// URDF `<origin xyz rpy>`: translation `xyz`, rotation `Rz(yaw) Ry(pitch) Rx(roll)`
/// (fixed-axis roll about x, then pitch about y, then yaw about z).
pub fn origin_from_xyz_rpy(
    what: &str,
    xyz: [f64; 3],
    rpy: [f64; 3],
) -> Result<DAffine3, GuardError> {
    if let Some(&value) = xyz.iter().chain(&rpy).find(|x| !x.is_finite()) {
        return Err(GuardError::NonFinite {
            what: what.to_string(),
            value,
        });
    }
    let [roll, pitch, yaw] = rpy;
    let rotation =
        DQuat::from_rotation_z(yaw) * DQuat::from_rotation_y(pitch) * DQuat::from_rotation_x(roll);
    Ok(DAffine3::from_rotation_translation(
        rotation,
        DVec3::from_array(xyz),
    ))
}

/// The unit vector along `axis`, scaled first so any finite magnitude normalises.
fn unit_axis(axis: [f64; 3]) -> Option<DVec3> {
    let a = DVec3::from_array(axis);
    let largest = a.abs().max_element();
    if !a.is_finite() || largest == 0.0 {
        return None;
    }
    let scaled = a / largest;
    let unit = scaled / scaled.length();
    unit.is_finite().then_some(unit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn rpy_follows_urdf_fixed_axis_order() {
        // Roll a quarter turn about x, then yaw a quarter turn about z: x stays x
        // after the roll, then becomes y; z becomes -y after the roll, then x.
        let t = origin_from_xyz_rpy("t", [1.0, 2.0, 3.0], [FRAC_PI_2, 0.0, FRAC_PI_2]).unwrap();
        assert!(close(t.transform_vector3(DVec3::X), DVec3::Y));
        assert!(close(t.transform_vector3(DVec3::Z), DVec3::X));
        assert!(close(
            t.transform_point3(DVec3::ZERO),
            DVec3::new(1.0, 2.0, 3.0)
        ));
    }

    #[test]
    fn revolute_and_prismatic_motion() {
        let j = Joint::new(
            "j",
            JointKind::Revolute,
            [0.0, 0.0, 5.0],
            [0.0, 0.0, 1.0],
            [0.0; 3],
            Some([-1.0, 2.0]),
        )
        .unwrap();
        assert!(close(
            j.transform(FRAC_PI_2).transform_point3(DVec3::X),
            DVec3::new(0.0, 1.0, 1.0)
        ));
        let p = Joint::new(
            "p",
            JointKind::Prismatic,
            [2.0, 0.0, 0.0],
            [0.0; 3],
            [0.0; 3],
            None,
        )
        .unwrap();
        assert!(close(
            p.transform(0.25).transform_point3(DVec3::ZERO),
            DVec3::new(0.25, 0.0, 0.0)
        ));
        let f = Joint::new("f", JointKind::Fixed, [0.0; 3], [1.0; 3], [0.0; 3], None).unwrap();
        assert!(!f.is_actuated());
        assert!(close(
            f.transform(9.0).transform_point3(DVec3::ZERO),
            DVec3::ONE
        ));
    }

    #[test]
    fn bad_joints_are_refused() {
        let make = |kind, axis, xyz, limits| Joint::new("j", kind, axis, xyz, [0.0; 3], limits);
        let r = JointKind::Revolute;
        assert!(matches!(
            make(r, [0.0; 3], [0.0; 3], None),
            Err(GuardError::BadAxis { .. })
        ));
        assert!(matches!(
            make(r, [f64::NAN, 0.0, 1.0], [0.0; 3], None),
            Err(GuardError::BadAxis { .. })
        ));
        assert!(matches!(
            make(r, [1.0, 0.0, 0.0], [f64::INFINITY, 0.0, 0.0], None),
            Err(GuardError::NonFinite { .. })
        ));
        assert!(matches!(
            make(r, [1.0, 0.0, 0.0], [0.0; 3], Some([1.0, -1.0])),
            Err(GuardError::BadLimits { .. })
        ));
        assert!(matches!(
            make(JointKind::Fixed, [0.0; 3], [0.0; 3], Some([0.0, 1.0])),
            Err(GuardError::FixedWithLimits(_))
        ));
        assert!(make(r, [1e-300, 0.0, 0.0], [0.0; 3], None).is_ok());
        assert!(make(r, [1e300, 1e300, 0.0], [0.0; 3], None).is_ok());
        assert!(matches!(
            Joint::new("", r, [1.0, 0.0, 0.0], [0.0; 3], [0.0; 3], None),
            Err(GuardError::EmptyName { .. })
        ));
    }
}
