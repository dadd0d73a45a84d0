//! What the arm targets check of a decoded arm: it poses at the middle of its
//! joint limits (0 for unlimited joints) without a panic, one value per
//! actuated joint.

use crate::check::named;
use shroud_guard::{ArmModel, GuardError};

pub fn poses(arm: &ArmModel) {
    let q: Vec<f64> = arm
        .actuated_joints()
        .map(|j| j.limits().map_or(0.0, |l| l.lower / 2.0 + l.upper / 2.0))
        .collect();
    match arm.forward(&q) {
        Ok(pose) => assert_eq!(pose.links.len(), arm.links().len(), "one pose per link"),
        Err(e @ GuardError::JointCount { .. }) => panic!("posing with one value per joint: {e}"),
        Err(e) => named(&e),
    }
}
