//! A ROS 2 `sensor_msgs/JointState` as one arm's joint state: its names
//! matched to the arm's actuated joints and put in the arm's chain order (a
//! ros2_control `joint_state_broadcaster` publishes every joint of the robot
//! in its own order, grippers included).

use crate::{ns_of_time, JointsInError};
use shroud_msg::JointStateMessage;
use shroud_ros2::JointState;

/// Matches joint states to the actuated joints of one arm.
#[derive(Debug, Clone, PartialEq)]
pub struct JointMatcher {
    arm: String,
    joints: Vec<String>,
}

/// A matched joint state, and the names it carried that the arm has not
/// (their values are dropped: the caller counts and names them).
#[derive(Debug, Clone, PartialEq)]
pub struct MatchedJoints {
    pub message: JointStateMessage,
    pub unknown: Vec<String>,
}

impl JointMatcher {
    /// `joints`: the arm's actuated joints in chain order.
    pub fn new(arm: &str, joints: Vec<String>) -> Self {
        Self {
            arm: arm.to_owned(),
            joints,
        }
    }

    pub fn joints(&self) -> &[String] {
        &self.joints
    }

    /// `state` as the arm's joint state number `sequence`: positions and,
    /// when the state has one per name, velocities, in chain order. Refused
    /// (a pose cannot be judged from part of it) when a joint of the arm is
    /// missing or named twice, when the counts disagree, or a value is not
    /// finite; an empty velocity list means none was measured.
    pub fn match_joints(
        &self,
        state: &JointState,
        sequence: u64,
    ) -> Result<MatchedJoints, JointsInError> {
        let names = state.name.len();
        if state.position.len() != names {
            return Err(JointsInError::PositionCount {
                names,
                positions: state.position.len(),
            });
        }
        let with_velocities = !state.velocity.is_empty();
        if with_velocities && state.velocity.len() != names {
            return Err(JointsInError::VelocityCount {
                names,
                velocities: state.velocity.len(),
            });
        }
        let stamp = &state.header.stamp;
        let stamp_ns = ns_of_time(stamp).ok_or(JointsInError::Stamp {
            sec: stamp.sec,
            nanosec: stamp.nanosec,
        })?;
        let (mut positions, mut velocities) = (Vec::new(), Vec::new());
        for joint in &self.joints {
            let index = self.index_of(state, joint)?;
            positions.push(finite(joint, "position", state.position[index])?);
            if with_velocities {
                velocities.push(finite(joint, "velocity", state.velocity[index])?);
            }
        }
        let unknown = state
            .name
            .iter()
            .filter(|n| !self.joints.contains(n))
            .cloned()
            .collect();
        let message = JointStateMessage::new(
            stamp_ns,
            sequence,
            &self.arm,
            self.joints.clone(),
            positions,
        )
        .with_velocities(velocities);
        Ok(MatchedJoints { message, unknown })
    }

    /// Where `joint` is in `state`: exactly once.
    fn index_of(&self, state: &JointState, joint: &str) -> Result<usize, JointsInError> {
        let mut found = state.name.iter().enumerate().filter(|(_, n)| *n == joint);
        let Some((index, _)) = found.next() else {
            return Err(JointsInError::Missing {
                arm: self.arm.clone(),
                joint: joint.to_owned(),
            });
        };
        if found.next().is_some() {
            return Err(JointsInError::Duplicate {
                joint: joint.to_owned(),
            });
        }
        Ok(index)
    }
}

fn finite(joint: &str, what: &'static str, value: f64) -> Result<f64, JointsInError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(JointsInError::NotFinite {
            joint: joint.to_owned(),
            what,
            value,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_ros2::{Header, Time};

    fn matcher() -> JointMatcher {
        JointMatcher::new("arm", vec!["a".into(), "b".into(), "c".into()])
    }

    fn state(names: &[&str], position: Vec<f64>, velocity: Vec<f64>) -> JointState {
        JointState {
            header: Header {
                stamp: Time {
                    sec: 1_700_000_000,
                    nanosec: 5,
                },
                frame_id: String::new(),
            },
            name: names.iter().map(|s| s.to_string()).collect(),
            position,
            velocity,
            effort: Vec::new(),
        }
    }

    #[test]
    fn names_in_any_order_come_out_in_chain_order_with_unknown_ones_listed() {
        let s = state(
            &["finger", "c", "a", "b"],
            vec![9.0, 3.0, 1.0, 2.0],
            vec![0.9, 0.3, 0.1, 0.2],
        );
        let m = matcher().match_joints(&s, 7).unwrap();
        assert_eq!(m.message.names, ["a", "b", "c"]);
        assert_eq!(m.message.positions, [1.0, 2.0, 3.0]);
        assert_eq!(m.message.velocities, [0.1, 0.2, 0.3]);
        assert_eq!(m.message.stamp_ns, 1_700_000_000_000_000_005);
        assert_eq!((m.message.sequence, m.message.arm.as_str()), (7, "arm"));
        assert_eq!(m.unknown, ["finger"]);
        // The result passes shroud's own decoder's checks.
        let bytes = m.message.to_bytes().unwrap();
        JointStateMessage::from_bytes(&bytes).unwrap();
    }

    #[test]
    fn no_velocities_means_none_measured() {
        let s = state(&["a", "b", "c"], vec![1.0, 2.0, 3.0], vec![]);
        assert!(matcher()
            .match_joints(&s, 0)
            .unwrap()
            .message
            .velocities
            .is_empty());
    }

    #[test]
    fn what_cannot_be_judged_is_refused_by_name() {
        let m = matcher();
        let missing = state(&["a", "c"], vec![1.0, 3.0], vec![]);
        assert_eq!(
            m.match_joints(&missing, 0).unwrap_err(),
            JointsInError::Missing {
                arm: "arm".into(),
                joint: "b".into()
            }
        );
        let twice = state(&["a", "b", "b", "c"], vec![0.0; 4], vec![]);
        assert!(matches!(
            m.match_joints(&twice, 0),
            Err(JointsInError::Duplicate { .. })
        ));
        let short = state(&["a", "b", "c"], vec![0.0; 2], vec![]);
        assert!(matches!(
            m.match_joints(&short, 0),
            Err(JointsInError::PositionCount { .. })
        ));
        let velocities = state(&["a", "b", "c"], vec![0.0; 3], vec![0.0]);
        assert!(matches!(
            m.match_joints(&velocities, 0),
            Err(JointsInError::VelocityCount { .. })
        ));
        let nan = state(&["a", "b", "c"], vec![0.0, f64::NAN, 0.0], vec![]);
        let e = m.match_joints(&nan, 0).unwrap_err();
        assert!(e.to_string().contains("\"b\": position NaN"), "{e}");
        let mut early = state(&["a", "b", "c"], vec![0.0; 3], vec![]);
        early.header.stamp.sec = -3;
        assert!(matches!(
            m.match_joints(&early, 0),
            Err(JointsInError::Stamp { .. })
        ));
    }
}
