//! The `[motion]` table of an arm file: per joint by name a velocity limit
//! and a stopping model, the reaction time, the position uncertainty and the
//! scale's rise limit.
//!
//! ```toml
//! [motion]
//! reaction_time = 0.1               # s, T_r: decision until the arm obeys
//! position_uncertainty = 0.005      # m, Z_r (default 0)
//! scale_rise_per_second = 1.0       # default 1: from 0 to full speed in 1 s
//! joints = [
//!   { name = "shoulder_pan", max_velocity = 1.5, deceleration = 6.0 },
//!   # or measured stops: [fraction of max_velocity, distance, seconds]
//!   { name = "elbow", max_velocity = 2.0, stopping = [[0.33, 0.05, 0.1], [1.0, 0.31, 0.244]] },
//! ]
//! ```

use super::motion::{ArmMotion, JointMotion};
use super::stopping::{StopSample, StoppingModel};
use crate::{ArmModel, GuardError};
use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMotion {
    reaction_time: f64,
    #[serde(default)]
    position_uncertainty: f64,
    #[serde(default = "default_rise")]
    scale_rise_per_second: f64,
    joints: Vec<RawJointMotion>,
}

fn default_rise() -> f64 {
    1.0
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawJointMotion {
    name: String,
    max_velocity: f64,
    deceleration: Option<f64>,
    stopping: Option<Vec<[f64; 3]>>,
}

impl RawMotion {
    /// Orders the entries as the arm's actuated joints and validates them:
    /// every actuated joint exactly once, no other name, one stopping model each.
    pub(crate) fn for_arm(self, arm: &ArmModel) -> Result<ArmMotion, GuardError> {
        let bad = |m: String| GuardError::BadConfig(format!("[motion]: {m}"));
        if let Some(unknown) = self
            .joints
            .iter()
            .find(|j| !arm.actuated_joints().any(|a| a.name() == j.name))
        {
            return Err(bad(format!(
                "'{}' is not an actuated joint of the arm",
                unknown.name
            )));
        }
        let mut joints = Vec::with_capacity(arm.dof());
        for joint in arm.actuated_joints() {
            let mut entries = self.joints.iter().filter(|j| j.name == joint.name());
            let entry = entries
                .next()
                .ok_or_else(|| bad(format!("joint '{}' has no entry", joint.name())))?;
            if entries.next().is_some() {
                return Err(bad(format!("joint '{}' is given twice", joint.name())));
            }
            let stopping = match (entry.deceleration, &entry.stopping) {
                (Some(a), None) => StoppingModel::Deceleration(a),
                (None, Some(table)) => StoppingModel::Measured(
                    table
                        .iter()
                        .map(|&[fraction, distance, time]| StopSample {
                            fraction,
                            distance,
                            time,
                        })
                        .collect(),
                ),
                _ => {
                    return Err(bad(format!(
                        "joint '{}' needs exactly one of deceleration and stopping",
                        joint.name()
                    )))
                }
            };
            joints.push(JointMotion {
                max_velocity: entry.max_velocity,
                stopping,
            });
        }
        let motion = ArmMotion {
            reaction_time: self.reaction_time,
            position_uncertainty: self.position_uncertainty,
            scale_rise_per_second: self.scale_rise_per_second,
            joints,
        };
        motion.validate(arm)?;
        Ok(motion)
    }
}
