//! ROS 2 sensor_msgs/JointState payloads (shroud-ros2): round trips of what
//! decodes, named errors for the rest.

use super::ros2_messages::check;
use shroud_ros2::{Header, JointState, RosMessage};

pub fn run(data: &[u8]) {
    check::<JointState>(data);
}

/// A joint state without velocities, and one with velocities and efforts.
pub fn seeds() -> Vec<Vec<u8>> {
    let still = JointState {
        header: Header::default(),
        name: vec!["shoulder".into(), "elbow".into()],
        position: vec![0.5, -1.25],
        ..JointState::default()
    };
    let moving = JointState {
        velocity: vec![0.75, -0.2],
        effort: vec![1.0, 2.0],
        ..still.clone()
    };
    vec![still.encode(), moving.encode()]
}
