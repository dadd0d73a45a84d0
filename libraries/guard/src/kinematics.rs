//! Forward kinematics: joint values to the world pose of every link, and the
//! link shapes moved into the world. Joint limits are not enforced here (a
//! simulated or measured arm is where it is); [`ArmModel::check_limits`] tells.

use super::arm::ArmModel;
use super::error::GuardError;
use super::shape::WorldShape;
use glam::DAffine3;

/// Where the arm is: the world pose of each link and every collision shape in
/// world coordinates (links in chain order, each link's shapes in its order).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ArmPose {
    pub links: Vec<DAffine3>,
    pub shapes: Vec<WorldShape>,
}

impl ArmPose {
    pub fn link_count(&self) -> usize {
        self.links.len()
    }
}

impl ArmModel {
    /// The pose at joint values `q` (one per actuated joint, radians or metres).
    pub fn forward(&self, q: &[f64]) -> Result<ArmPose, GuardError> {
        let mut pose = ArmPose::default();
        self.forward_into(q, &mut pose)?;
        Ok(pose)
    }

    /// [`Self::forward`] reusing the vectors of `pose` (no allocation once they
    /// have grown). On error `pose` holds no shapes.
    pub fn forward_into(&self, q: &[f64], pose: &mut ArmPose) -> Result<(), GuardError> {
        pose.links.clear();
        pose.shapes.clear();
        if q.len() != self.dof() {
            return Err(GuardError::JointCount {
                expected: self.dof(),
                got: q.len(),
            });
        }
        if let Some((index, &value)) = q.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(GuardError::NonFiniteJoint { index, value });
        }
        let mut values = q.iter();
        let mut current = *self.base();
        pose.links.push(current);
        for joint in self.joints() {
            let value = if joint.is_actuated() {
                values.next().copied().unwrap_or(0.0)
            } else {
                0.0
            };
            current *= joint.transform(value);
            pose.links.push(current);
        }
        for (link, (model, world)) in self.links().iter().zip(&pose.links).enumerate() {
            for shape in &model.shapes {
                pose.shapes.push(WorldShape {
                    link,
                    shape: shape.transformed(world),
                });
            }
        }
        if let Some(index) = pose.shapes.iter().position(|s| !s.shape.is_valid()) {
            let link = pose.shapes[index].link;
            pose.shapes.clear();
            return Err(GuardError::BadShape { index, link });
        }
        Ok(())
    }

    /// The first actuated joint whose value is outside its limits, as an error.
    pub fn check_limits(&self, q: &[f64]) -> Result<(), GuardError> {
        if q.len() != self.dof() {
            return Err(GuardError::JointCount {
                expected: self.dof(),
                got: q.len(),
            });
        }
        for (joint, (&value, j)) in q.iter().zip(self.actuated_joints()).enumerate() {
            if let Some(l) = j.limits().filter(|l| !l.contains(value)) {
                return Err(GuardError::OutsideLimits {
                    index: 0,
                    joint,
                    value,
                    lower: l.lower,
                    upper: l.upper,
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arm::Link;
    use crate::joint::{Joint, JointKind};
    use crate::shape::Shape;
    use glam::DVec3;
    use std::f64::consts::FRAC_PI_2;

    /// A planar two-link arm in the xz plane: base at z = 1, links 1 m long.
    fn planar() -> ArmModel {
        let link = |name: &str, shapes| Link {
            name: name.into(),
            shapes,
        };
        let tip = |len: f64| vec![Shape::sphere(DVec3::new(0.0, 0.0, len), 0.1)];
        ArmModel::new(
            "planar",
            DAffine3::from_translation(DVec3::Z),
            vec![
                link("base", vec![]),
                link("upper", tip(1.0)),
                link("flange", vec![]),
                link("fore", tip(1.0)),
            ],
            vec![
                Joint::new(
                    "shoulder",
                    JointKind::Revolute,
                    [0.0, 1.0, 0.0],
                    [0.0; 3],
                    [0.0; 3],
                    Some([-2.0, 2.0]),
                )
                .unwrap(),
                Joint::new(
                    "elbow",
                    JointKind::Revolute,
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                    [0.0; 3],
                    None,
                )
                .unwrap(),
                Joint::new("tool", JointKind::Fixed, [0.0; 3], [0.0; 3], [0.0; 3], None).unwrap(),
            ],
        )
        .unwrap()
    }

    fn centre(s: &WorldShape) -> DVec3 {
        match s.shape {
            Shape::Sphere(s) => s.centre,
            Shape::Capsule(c) => c.a,
        }
    }

    #[test]
    fn planar_arm_positions() {
        let arm = planar();
        assert_eq!(arm.dof(), 2);
        let pose = arm.forward(&[0.0, 0.0]).unwrap();
        assert_eq!(pose.link_count(), 4);
        assert_eq!(pose.shapes.len(), 2);
        assert_eq!((pose.shapes[0].link, pose.shapes[1].link), (1, 3));
        assert!((centre(&pose.shapes[1]) - DVec3::new(0.0, 0.0, 3.0)).length() < 1e-12);
        // Shoulder a quarter turn about +y: z goes to +x.
        let pose = arm.forward(&[FRAC_PI_2, 0.0]).unwrap();
        assert!((centre(&pose.shapes[0]) - DVec3::new(1.0, 0.0, 1.0)).length() < 1e-12);
        assert!((centre(&pose.shapes[1]) - DVec3::new(2.0, 0.0, 1.0)).length() < 1e-12);
        let pose = arm.forward(&[FRAC_PI_2, -FRAC_PI_2]).unwrap();
        assert!((centre(&pose.shapes[1]) - DVec3::new(1.0, 0.0, 2.0)).length() < 1e-12);
    }

    #[test]
    fn bad_joint_values_are_refused() {
        let arm = planar();
        let mut pose = arm.forward(&[0.0, 0.0]).unwrap();
        assert_eq!(
            arm.forward(&[0.0]),
            Err(GuardError::JointCount {
                expected: 2,
                got: 1
            })
        );
        assert!(matches!(
            arm.forward_into(&[0.0, f64::NAN], &mut pose),
            Err(GuardError::NonFiniteJoint { index: 1, .. })
        ));
        assert!(pose.shapes.is_empty());
        assert!(arm.check_limits(&[1.0, 9.0]).is_ok());
        assert!(matches!(
            arm.check_limits(&[2.5, 0.0]),
            Err(GuardError::OutsideLimits { joint: 0, .. })
        ));
    }

    #[test]
    fn overflowing_prismatic_joints_are_refused() {
        let arm = ArmModel::new(
            "slider",
            DAffine3::IDENTITY,
            vec![
                Link {
                    name: "a".into(),
                    shapes: vec![],
                },
                Link {
                    name: "b".into(),
                    shapes: vec![Shape::sphere(DVec3::X * 1e308, 1.0)],
                },
            ],
            vec![Joint::new(
                "s",
                JointKind::Prismatic,
                [1.0, 0.0, 0.0],
                [0.0; 3],
                [0.0; 3],
                None,
            )
            .unwrap()],
        )
        .unwrap();
        assert!(matches!(
            arm.forward(&[1e308]),
            Err(GuardError::BadShape { .. })
        ));
    }
}
