//! The guard's verdict as ROS 2 messages a controller can act on: a
//! `diagnostic_msgs/DiagnosticStatus` (its level is the one field every ROS
//! safety and monitoring tool reads: OK to move, ERROR to halt, with the
//! reason and the clearances as key-value pairs) and the speed scale as a
//! `std_msgs/Float64` in [0, 1] (0 for every verdict but `clear`), the form a
//! speed-scaling controller multiplies its velocities by. One of each per
//! verdict, so per joint state: a ROS consumer keeps the deadman by waiting
//! for the answer to its latest joint state (`joints_stamp_ns`).

use shroud_msg::CollisionMessage;
use shroud_ros2::{DiagnosticStatus, Float64, KeyValue};

/// `DiagnosticStatus.level` values (diagnostic_msgs/msg/DiagnosticStatus.msg).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum VerdictLevel {
    /// `clear` at full speed.
    Ok = 0,
    /// `clear` at a reduced speed (speed and separation monitoring).
    Warn = 1,
    /// Every other verdict: halt.
    Error = 2,
}

/// The status of `verdict`, named `shroud/guard/<arm>`.
pub fn verdict_status(verdict: &CollisionMessage) -> DiagnosticStatus {
    let level = if verdict.stop {
        VerdictLevel::Error
    } else if verdict.speed_scale < 1.0 {
        VerdictLevel::Warn
    } else {
        VerdictLevel::Ok
    };
    let message = match verdict.reason.is_empty() {
        true => verdict.verdict.name().to_owned(),
        false => format!("{}: {}", verdict.verdict.name(), verdict.reason),
    };
    let values = [
        ("verdict", verdict.verdict.name().to_owned()),
        ("stop", verdict.stop.to_string()),
        ("speed_scale", verdict.speed_scale.to_string()),
        ("min_clearance", verdict.min_clearance.to_string()),
        ("closest_link", verdict.closest_link.clone()),
        ("limiting_link", verdict.limiting_link.clone()),
        ("stop_distance", verdict.stop_distance.to_string()),
        ("unobserved", verdict.unobserved.to_string()),
        ("views", verdict.views.to_string()),
        ("surrogate_age_ns", verdict.surrogate_age_ns.to_string()),
        ("joints_stamp_ns", verdict.joints_stamp_ns.to_string()),
        ("joints_sequence", verdict.joints_sequence.to_string()),
    ];
    DiagnosticStatus {
        level: level as u8,
        name: format!("shroud/guard/{}", verdict.arm),
        message,
        hardware_id: verdict.arm.clone(),
        values: values
            .into_iter()
            .map(|(key, value)| KeyValue {
                key: key.to_owned(),
                value,
            })
            .collect(),
    }
}

/// The speed `verdict` allows, as a fraction of the arm's limits: 0 unless
/// it is `clear`.
pub fn speed_scale_of(verdict: &CollisionMessage) -> Float64 {
    let scale = if verdict.stop {
        0.0
    } else {
        verdict.speed_scale
    };
    Float64 {
        data: scale.clamp(0.0, 1.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_msg::{sample_collision, GuardVerdict};

    fn value<'a>(s: &'a DiagnosticStatus, key: &str) -> &'a str {
        &s.values.iter().find(|kv| kv.key == key).unwrap().value
    }

    #[test]
    fn only_a_clear_verdict_lets_the_arm_move() {
        for verdict in GuardVerdict::ALL {
            let mut msg = sample_collision(verdict);
            msg.reason = "why".into();
            let status = verdict_status(&msg);
            let moving = verdict == GuardVerdict::Clear;
            assert_eq!(
                status.level == VerdictLevel::Ok as u8,
                moving,
                "{verdict:?}"
            );
            assert_eq!(speed_scale_of(&msg).data > 0.0, moving, "{verdict:?}");
            assert_eq!(value(&status, "verdict"), verdict.name());
            assert_eq!(status.message, format!("{}: why", verdict.name()));
            assert_eq!(value(&status, "joints_sequence"), "2");
            assert_eq!(status.name, "shroud/guard/arm");
        }
    }

    #[test]
    fn a_slowed_clear_is_a_warning_with_its_scale() {
        let mut msg = sample_collision(GuardVerdict::Clear);
        msg.speed_scale = 0.25;
        assert_eq!(verdict_status(&msg).level, VerdictLevel::Warn as u8);
        assert_eq!(speed_scale_of(&msg).data, 0.25);
    }
}
