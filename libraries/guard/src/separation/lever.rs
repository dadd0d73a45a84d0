//! How fast a link's shapes can move per unit of each joint's speed, in any
//! pose: the lever arm of a revolute joint bounded by the lengths of the
//! chain between the joint's axis and the shapes.
//!
//! Why it holds. Joint `j` turns link `j + 1` about an axis through that
//! link's frame origin, so a point `p` of link `l > j` moves at
//! `|q̇_j| · dist(p, axis) <= |q̇_j| · |p - o|`, `o` the origin. The chain
//! from `o` to link `l`'s frame is the joints `j + 1 .. l - 1`, each adding
//! its origin's translation (a prismatic one also its travel, at most the
//! larger magnitude of its limits), and `p` is within the largest extent of
//! the link's shapes (centre or end point plus radius) of link `l`'s origin.
//! A prismatic joint moves every later point at exactly `|q̇_j|`. Summing
//! over the joints bounds the speed whatever the other joints do, since
//! speeds of a serial chain add (the point's velocity is the sum of each
//! joint's contribution).

use crate::{ArmModel, GuardError, JointKind, Shape};

/// Per link, per actuated joint: metres moved per radian (or per metre) of
/// the joint's travel, at most, in any pose.
#[derive(Debug, Clone, PartialEq)]
pub struct LeverArms {
    per_link: Vec<Vec<f64>>,
}

impl LeverArms {
    /// Refuses a prismatic joint without limits (its travel, and so the
    /// chain's length, is unbounded).
    pub fn new(arm: &ArmModel) -> Result<Self, GuardError> {
        let joints = arm.joints();
        let mut lengths = Vec::with_capacity(joints.len());
        for joint in joints {
            let mut length = joint.origin().translation.length();
            if joint.kind() == JointKind::Prismatic {
                let limits = joint.limits().ok_or_else(|| {
                    GuardError::BadConfig(format!(
                        "[motion]: prismatic joint '{}' needs limits to bound the arm's reach",
                        joint.name()
                    ))
                })?;
                length += limits.lower.abs().max(limits.upper.abs());
            }
            lengths.push(length);
        }
        let per_link = arm
            .links()
            .iter()
            .enumerate()
            .map(|(link, model)| {
                let extent = model.shapes.iter().map(shape_extent).fold(0.0, f64::max);
                joints
                    .iter()
                    .enumerate()
                    .filter(|(_, j)| j.is_actuated())
                    .map(|(j, joint)| {
                        if j >= link {
                            0.0
                        } else if joint.kind() == JointKind::Prismatic {
                            1.0
                        } else {
                            lengths[j + 1..link].iter().sum::<f64>() + extent
                        }
                    })
                    .collect()
            })
            .collect();
        Ok(Self { per_link })
    }

    /// Link `link`'s levers, one per actuated joint.
    pub fn of_link(&self, link: usize) -> &[f64] {
        self.per_link.get(link).map_or(&[], Vec::as_slice)
    }

    pub fn links(&self) -> usize {
        self.per_link.len()
    }
}

/// The farthest point of a shape from its link's frame origin.
fn shape_extent(shape: &Shape) -> f64 {
    match shape {
        Shape::Sphere(s) => s.centre.length() + s.radius,
        Shape::Capsule(c) => c.a.length().max(c.b.length()) + c.radius,
    }
}
