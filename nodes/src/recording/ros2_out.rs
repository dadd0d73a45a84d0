//! What `shroud record --ros2` writes beside shroud's own messages: each
//! cloud, joint state and verdict as the ROS 2 message a ROS user plays back
//! (`sensor_msgs/msg/PointCloud2` in frame `world`, `sensor_msgs/msg/JointState`,
//! `diagnostic_msgs/msg/DiagnosticStatus`), CDR-encoded, on the channel
//! `shroud-record`'s [`ros2_channel`] names.

use shroud_msg::{CloudView, CollisionMessage, JointStateMessage, TopicKey, TopicKind};
use shroud_record::ros2::{ros2_channel, RosChannel};
use shroud_ros2::{Header, JointState, RosMessage};
use shroud_ros2_bridge::{point_cloud2_of, time_of_ns, verdict_status};

/// The frame of the recorded clouds: shroud's world, as the ROS side names it.
pub const WORLD_FRAME: &str = "world";

/// The ROS 2 message of a shroud message: `None` for a kind without one, an
/// error naming the topic when the payload does not decode.
pub fn ros2_message(
    key: &TopicKey,
    payload: &[u8],
) -> Option<Result<(RosChannel, Vec<u8>), String>> {
    let channel = ros2_channel(key)?;
    let fail = |e: &dyn std::fmt::Display| format!("{}/{}: {e}", key.kind, key.name);
    let cdr = match key.kind {
        TopicKind::Cloud => CloudView::from_bytes(payload)
            .and_then(|view| point_cloud2_of(&view, WORLD_FRAME))
            .map(|cloud| cloud.encode())
            .map_err(|e| fail(&e)),
        TopicKind::Joints => JointStateMessage::from_bytes(payload)
            .map(|m| joint_state(&m).encode())
            .map_err(|e| fail(&e)),
        _ => CollisionMessage::from_bytes(payload)
            .map(|m| verdict_status(&m).encode())
            .map_err(|e| fail(&e)),
    };
    Some(cdr.map(|cdr| (channel, cdr)))
}

fn joint_state(msg: &JointStateMessage) -> JointState {
    JointState {
        header: Header {
            stamp: time_of_ns(msg.stamp_ns),
            frame_id: String::new(),
        },
        name: msg.names.clone(),
        position: msg.positions.clone(),
        velocity: msg.velocities.clone(),
        effort: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_msg::{sample_collision, CloudMessage, GuardVerdict, SensorPose};
    use shroud_ros2::{DiagnosticStatus, PointCloud2};

    fn key(text: &str) -> TopicKey {
        TopicKey::parse(text).unwrap()
    }

    #[test]
    fn clouds_joints_and_verdicts_become_ros_messages_and_junk_is_named() {
        let cloud = CloudMessage::new(5, 1, "s", SensorPose::default(), &[[1.0, 2.0, 3.0]]);
        let (channel, cdr) = ros2_message(&key("shroud/t/cloud/cam"), &cloud.to_bytes().unwrap())
            .unwrap()
            .unwrap();
        assert_eq!(channel.topic, "/shroud/cloud/cam");
        let back = PointCloud2::decode_borrowed(&cdr).unwrap();
        assert_eq!(
            (back.width, back.header.frame_id.as_str()),
            (1, WORLD_FRAME)
        );
        let joints = JointStateMessage::new(7, 2, "arm", vec!["a".into()], vec![0.5]);
        let (_, cdr) = ros2_message(&key("shroud/t/joints/arm"), &joints.to_bytes().unwrap())
            .unwrap()
            .unwrap();
        assert_eq!(JointState::decode(&cdr).unwrap().position, [0.5]);
        let verdict = sample_collision(GuardVerdict::Clear).to_bytes().unwrap();
        let (channel, cdr) = ros2_message(&key("shroud/t/collision/arm"), &verdict)
            .unwrap()
            .unwrap();
        assert_eq!(channel.topic, "/shroud/verdict/arm");
        assert_eq!(
            DiagnosticStatus::decode(&cdr).unwrap().level,
            DiagnosticStatus::OK
        );
        assert!(ros2_message(&key("shroud/t/status/x"), b"").is_none());
        let e = ros2_message(&key("shroud/t/cloud/cam"), b"junk")
            .unwrap()
            .unwrap_err();
        assert!(e.starts_with("cloud/cam"), "{e}");
    }
}
