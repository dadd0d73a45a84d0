//! A sensor mount that may turn about one axis: a fixed base pose, the axis,
//! the sensor's pose on the turning part, and where the angle comes from.

use super::joint_track::JointTrack;
use super::pose::MountPose;
use super::profile::SweepProfile;
use glam::{DQuat, DVec3};

/// Where a mount's angle comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum MountMotion {
    /// The mount does not move.
    Fixed,
    /// A configured sweep on the wall clock.
    Profile(SweepProfile),
    /// The named joint of a joint-state topic; samples are handed to the
    /// assembler as they arrive.
    Joint { name: String },
}

/// `robot_point = base * Rot(axis, angle(t)) * sensor * sensor_point`.
#[derive(Debug, Clone, PartialEq)]
pub struct MovingMount {
    /// The turning unit's frame in the robot's (the whole mount for a fixed one).
    pub base: MountPose,
    /// The turning axis in the base frame (unit length).
    pub axis: DVec3,
    /// The sensor's frame on the turning part.
    pub sensor: MountPose,
    pub motion: MountMotion,
}

impl MovingMount {
    /// A mount that does not move.
    pub fn fixed(pose: MountPose) -> Self {
        Self {
            base: pose,
            axis: DVec3::Y,
            sensor: MountPose::default(),
            motion: MountMotion::Fixed,
        }
    }

    /// The sensor's pose in the robot's frame with the unit at `angle`.
    pub fn pose_at_angle(&self, angle: f64) -> MountPose {
        let turn = MountPose {
            translation: DVec3::ZERO,
            rotation: DQuat::from_axis_angle(self.axis, angle),
        };
        self.base.then(&turn).then(&self.sensor)
    }

    /// The unit's angle and sweep number at `unix_ns` (`(0, 0)` for a fixed
    /// mount), or `None` when the joint samples do not cover that time.
    pub fn angle_at(&self, unix_ns: u64, track: &JointTrack) -> Option<(f64, u64)> {
        match &self.motion {
            MountMotion::Fixed => Some((0.0, 0)),
            MountMotion::Profile(p) => Some((p.angle_at(unix_ns), p.sweep_index(unix_ns))),
            MountMotion::Joint { .. } => track.at(unix_ns),
        }
    }

    /// Whether the mount has sweeps (a fixed one has none).
    pub fn sweeps(&self) -> bool {
        self.motion != MountMotion::Fixed
    }
}
