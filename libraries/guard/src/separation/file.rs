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

#[cfg(test)]
mod tests {
    use crate::ArmFile;

    const ARM: &str = r#"
        [[links]]
        name = "base"
        [[links]]
        name = "upper"
        spheres = [{ centre = [0.3, 0.0, 0.0], radius = 0.05 }]
        [[links]]
        name = "tip"
        [[joints]]
        name = "turn"
        kind = "revolute"
        axis = [0.0, 0.0, 1.0]
        [[joints]]
        name = "mount"
        kind = "fixed"
    "#;

    fn with_motion(motion: &str) -> Result<ArmFile, String> {
        ArmFile::from_toml_str(&format!("{ARM}\n[motion]\n{motion}")).map_err(|e| e.to_string())
    }

    #[test]
    fn a_motion_table_is_read_per_actuated_joint() {
        let file = with_motion(
            r#"reaction_time = 0.1
            joints = [{ name = "turn", max_velocity = 2.0, stopping = [[0.5, 0.1, 0.1], [1.0, 0.3, 0.2]] }]"#,
        )
        .unwrap();
        let motion = file.motion.unwrap();
        assert_eq!(motion.joints.len(), 1);
        assert_eq!(
            (motion.position_uncertainty, motion.scale_rise_per_second),
            (0.0, 1.0)
        );
        assert!(ArmFile::from_toml_str(ARM).unwrap().motion.is_none());
    }

    #[test]
    fn bad_motion_tables_are_refused_by_name() {
        let refused = |m: &str| with_motion(m).unwrap_err();
        let joint = |j: &str| format!("reaction_time = 0.1\njoints = [{j}]");
        assert!(refused(&joint(
            r#"{ name = "mount", max_velocity = 1.0, deceleration = 1.0 }"#
        ))
        .contains("'mount' is not an actuated joint"));
        assert!(refused("reaction_time = 0.1\njoints = []").contains("'turn' has no entry"));
        assert!(refused(&joint(
            r#"{ name = "turn", max_velocity = 1.0, deceleration = 1.0 }, { name = "turn", max_velocity = 1.0, deceleration = 1.0 }"#
        ))
        .contains("given twice"));
        assert!(refused(&joint(r#"{ name = "turn", max_velocity = 1.0 }"#))
            .contains("exactly one of deceleration and stopping"));
        assert!(refused(&joint(
            r#"{ name = "turn", max_velocity = 1.0, deceleration = 1.0, stopping = [[1.0, 0.1, 0.1]] }"#
        ))
        .contains("exactly one"));
        assert!(refused(&joint(
            r#"{ name = "turn", max_velocity = -1.0, deceleration = 1.0 }"#
        ))
        .contains("max_velocity"));
        assert!(refused(&joint(
            r#"{ name = "turn", max_velocity = 1.0, deceleration = 1.0, typo = 1 }"#
        ))
        .contains("typo"));
        assert!(
            refused(r#"joints = [{ name = "turn", max_velocity = 1.0, deceleration = 1.0 }]"#)
                .contains("reaction_time")
        );
    }

    #[test]
    fn a_trajectory_faster_than_the_limits_is_refused() {
        let file = format!(
            "{ARM}\n[trajectory]\nwaypoints = [{{ positions = [0.0], duration = 1.0 }}, {{ positions = [1.0], duration = 1.0 }}]\n\
             [motion]\nreaction_time = 0.1\njoints = [{{ name = \"turn\", max_velocity = 1.0, deceleration = 4.0 }}]"
        );
        let e = ArmFile::from_toml_str(&file).unwrap_err().to_string();
        assert!(e.contains("moves joint 'turn' at up to 1.571"), "{e}");
    }
}
