//! The arm's last few joint states by stamp, so that a verdict is drawn on
//! the pose it answered (its `joints_stamp_ns`), not on a later one.

use shroud_msg::JointStateMessage;
use std::collections::VecDeque;

/// The last `capacity` joint states, oldest first.
#[derive(Debug, Clone)]
pub struct RecentJoints {
    states: VecDeque<JointStateMessage>,
    capacity: usize,
}

impl RecentJoints {
    /// Keeps at most `capacity` (at least 1) joint states.
    pub fn new(capacity: usize) -> Self {
        let capacity = capacity.max(1);
        Self {
            states: VecDeque::with_capacity(capacity),
            capacity,
        }
    }

    /// Adds the newest joint state, forgetting the oldest when full.
    pub fn push(&mut self, joints: JointStateMessage) {
        if self.states.len() == self.capacity {
            self.states.pop_front();
        }
        self.states.push_back(joints);
    }

    /// The joint state stamped `stamp_ns`, if still kept (the newest of
    /// several with that stamp).
    pub fn stamped(&self, stamp_ns: u64) -> Option<&JointStateMessage> {
        self.states.iter().rev().find(|j| j.stamp_ns == stamp_ns)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn joints(stamp_ns: u64, q: f64) -> JointStateMessage {
        JointStateMessage::new(stamp_ns, 0, "arm", vec!["j".into()], vec![q])
    }

    #[test]
    fn a_verdict_finds_the_pose_it_answered_not_the_latest() {
        let mut recent = RecentJoints::new(3);
        recent.push(joints(10, 0.1));
        recent.push(joints(20, 0.2));
        recent.push(joints(30, 0.3));
        assert_eq!(recent.stamped(20).unwrap().positions, vec![0.2]);
        assert!(recent.stamped(25).is_none());
    }

    #[test]
    fn the_oldest_is_forgotten_when_full() {
        let mut recent = RecentJoints::new(2);
        for (stamp, q) in [(1, 0.1), (2, 0.2), (3, 0.3)] {
            recent.push(joints(stamp, q));
        }
        assert!(recent.stamped(1).is_none());
        assert_eq!(recent.stamped(3).unwrap().positions, vec![0.3]);
    }
}
