//! The arm model: a serial chain `link 0 -joint 0- link 1 -joint 1- ... link n`,
//! a world pose of link 0 (the base), and collision shapes per link. Built by
//! [`ArmModel::new`] (which validates) or parsed from TOML (see `schema`).

use super::error::GuardError;
use super::joint::Joint;
use super::shape::Shape;
use glam::DAffine3;
use std::collections::HashSet;

/// A rigid body of the chain and its collision shapes in its own frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    pub name: String,
    pub shapes: Vec<Shape>,
}

/// A validated serial arm.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmModel {
    name: String,
    base: DAffine3,
    links: Vec<Link>,
    joints: Vec<Joint>,
}

impl ArmModel {
    /// Checks the chain: `links.len() == joints.len() + 1` (joint `i` moves link
    /// `i + 1` relative to link `i`), unique non-empty names per kind, a finite
    /// base pose and valid shapes (finite, radius `> 0`).
    pub fn new(
        name: &str,
        base: DAffine3,
        links: Vec<Link>,
        joints: Vec<Joint>,
    ) -> Result<Self, GuardError> {
        if !base.is_finite() {
            return Err(GuardError::NonFinite {
                what: "base pose".into(),
                value: f64::NAN,
            });
        }
        if links.len() != joints.len() + 1 {
            return Err(GuardError::LinkCount {
                links: links.len(),
                joints: joints.len(),
            });
        }
        unique("link", links.iter().map(|l| l.name.as_str()))?;
        unique("joint", joints.iter().map(|j| j.name()))?;
        for link in &links {
            for (i, shape) in link.shapes.iter().enumerate() {
                if !shape.is_valid() {
                    return Err(GuardError::BadRadius {
                        what: format!(
                            "link '{}' shape {i} (coordinates must be finite too)",
                            link.name
                        ),
                        radius: shape.radius(),
                    });
                }
            }
        }
        Ok(Self {
            name: name.to_string(),
            base,
            links,
            joints,
        })
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// World pose of link 0.
    pub fn base(&self) -> &DAffine3 {
        &self.base
    }

    pub fn links(&self) -> &[Link] {
        &self.links
    }

    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Number of joint values forward kinematics takes: the non-fixed joints, in
    /// chain order.
    pub fn dof(&self) -> usize {
        self.joints.iter().filter(|j| j.is_actuated()).count()
    }

    /// The actuated joints in the order of the joint values.
    pub fn actuated_joints(&self) -> impl Iterator<Item = &Joint> {
        self.joints.iter().filter(|j| j.is_actuated())
    }

    /// Total number of collision shapes over all links.
    pub fn shape_count(&self) -> usize {
        self.links.iter().map(|l| l.shapes.len()).sum()
    }

    /// Index of the link called `name`.
    pub fn link_index(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }
}

fn unique<'a>(kind: &'static str, names: impl Iterator<Item = &'a str>) -> Result<(), GuardError> {
    let mut seen = HashSet::new();
    for name in names {
        if name.is_empty() {
            return Err(GuardError::EmptyName { kind });
        }
        if !seen.insert(name) {
            return Err(GuardError::DuplicateName {
                kind,
                name: name.to_string(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::joint::JointKind;
    use glam::DVec3;

    fn link(name: &str) -> Link {
        Link {
            name: name.into(),
            shapes: vec![Shape::sphere(DVec3::ZERO, 0.1)],
        }
    }

    fn joint(name: &str, kind: JointKind) -> Joint {
        Joint::new(name, kind, [0.0, 0.0, 1.0], [0.0; 3], [0.0; 3], None).unwrap()
    }

    #[test]
    fn counts_and_lookup() {
        let arm = ArmModel::new(
            "a",
            DAffine3::IDENTITY,
            vec![link("l0"), link("l1"), link("l2")],
            vec![
                joint("j0", JointKind::Revolute),
                joint("j1", JointKind::Fixed),
            ],
        )
        .unwrap();
        assert_eq!((arm.dof(), arm.shape_count()), (1, 3));
        assert_eq!(arm.link_index("l2"), Some(2));
        assert_eq!(arm.actuated_joints().next().map(|j| j.name()), Some("j0"));
    }

    #[test]
    fn bad_chains_are_refused() {
        let j = || vec![joint("j0", JointKind::Revolute)];
        assert!(matches!(
            ArmModel::new("a", DAffine3::IDENTITY, vec![link("l0")], j()),
            Err(GuardError::LinkCount {
                links: 1,
                joints: 1
            })
        ));
        assert!(matches!(
            ArmModel::new("a", DAffine3::IDENTITY, vec![link("l"), link("l")], j()),
            Err(GuardError::DuplicateName { kind: "link", .. })
        ));
        let bad_shape = Link {
            name: "l1".into(),
            shapes: vec![Shape::sphere(DVec3::ZERO, -1.0)],
        };
        assert!(matches!(
            ArmModel::new("a", DAffine3::IDENTITY, vec![link("l0"), bad_shape], j()),
            Err(GuardError::BadRadius { .. })
        ));
        let nan_base = DAffine3::from_translation(DVec3::new(f64::NAN, 0.0, 0.0));
        assert!(ArmModel::new("a", nan_base, vec![link("l0"), link("l1")], j()).is_err());
        let two = vec![
            joint("j", JointKind::Revolute),
            joint("j", JointKind::Fixed),
        ];
        assert!(matches!(
            ArmModel::new(
                "a",
                DAffine3::IDENTITY,
                vec![link("l0"), link("l1"), link("l2")],
                two
            ),
            Err(GuardError::DuplicateName { kind: "joint", .. })
        ));
    }
}
