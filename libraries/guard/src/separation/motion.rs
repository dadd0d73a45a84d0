//! What the guard must know of the arm's own motion to bound it: per joint a
//! velocity limit and a stopping model, the reaction time and the arm's
//! position uncertainty (the `[motion]` table of an arm file).

use super::stopping::StoppingModel;
use crate::{ArmModel, GuardError, Trajectory};

/// One actuated joint's motion limits.
#[derive(Debug, Clone, PartialEq)]
pub struct JointMotion {
    /// The speed the joint never exceeds at scale 1 (rad/s or m/s, `> 0`).
    pub max_velocity: f64,
    pub stopping: StoppingModel,
}

/// The arm's motion limits, per actuated joint in joint-value order.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmMotion {
    /// `T_r` (seconds, `>= 0`): from the guard's decision until the arm obeys
    /// it, the whole chain (transport, the controller's cycle and ramp).
    pub reaction_time: f64,
    /// `Z_r` (metres, `>= 0`): how far the arm may be from where its joint
    /// state puts it (encoder resolution, compliance).
    pub position_uncertainty: f64,
    /// How fast the published scale may rise (per second, `> 0`); it falls at
    /// once. A rise limit only delays speeding up, never slowing down.
    pub scale_rise_per_second: f64,
    pub joints: Vec<JointMotion>,
}

impl ArmMotion {
    /// Checks the numbers and that there is one joint entry per actuated
    /// joint of `arm`.
    pub fn validate(&self, arm: &ArmModel) -> Result<(), GuardError> {
        let bad = |m: String| Err(GuardError::BadConfig(format!("[motion]: {m}")));
        let checks = [
            ("reaction_time", self.reaction_time, 0.0, false),
            (
                "position_uncertainty",
                self.position_uncertainty,
                0.0,
                false,
            ),
            (
                "scale_rise_per_second",
                self.scale_rise_per_second,
                0.0,
                true,
            ),
        ];
        for (name, value, floor, strict) in checks {
            let above = if strict {
                value > floor
            } else {
                value >= floor
            };
            if !(value.is_finite() && above) {
                let sign = if strict { ">" } else { ">=" };
                return bad(format!(
                    "{name} must be finite and {sign} {floor}, got {value}"
                ));
            }
        }
        if self.joints.len() != arm.dof() {
            return bad(format!(
                "{} joint entries for {} actuated joints",
                self.joints.len(),
                arm.dof()
            ));
        }
        for (joint, motion) in arm.actuated_joints().zip(&self.joints) {
            if !(motion.max_velocity.is_finite() && motion.max_velocity > 0.0) {
                return bad(format!(
                    "joint '{}': max_velocity must be finite and > 0, got {}",
                    joint.name(),
                    motion.max_velocity
                ));
            }
            motion.stopping.validate(joint.name())?;
        }
        Ok(())
    }

    /// Refuses a trajectory that moves a joint faster than its limit: at
    /// scale 1 it must keep the limits the bound assumes.
    pub fn check_trajectory(
        &self,
        arm: &ArmModel,
        trajectory: &Trajectory,
    ) -> Result<(), GuardError> {
        let peaks = trajectory.peak_velocities();
        for ((joint, motion), peak) in arm.actuated_joints().zip(&self.joints).zip(peaks) {
            if peak > motion.max_velocity {
                return Err(GuardError::BadConfig(format!(
                    "[trajectory] moves joint '{}' at up to {peak:.3}, over its [motion] max_velocity {}",
                    joint.name(),
                    motion.max_velocity
                )));
            }
        }
        Ok(())
    }

    /// The longest any joint takes to stop from `factor` times its velocity
    /// limit.
    pub fn longest_stop(&self, factor: f64) -> f64 {
        self.joints
            .iter()
            .map(|j| {
                j.stopping
                    .stop(factor * j.max_velocity, j.max_velocity)
                    .time
            })
            .fold(0.0, f64::max)
    }
}
