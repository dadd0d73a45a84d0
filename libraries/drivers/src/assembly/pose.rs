//! A rigid pose of a sensor (or of its turning unit) in the robot's frame:
//! position in metres and orientation from roll, pitch, yaw.

use super::error::{parse_numbers, AssemblyError};
use glam::{DQuat, DVec3, EulerRot};
use std::str::FromStr;

/// Where a frame sits in its parent: `parent_point = rotation * point +
/// translation`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MountPose {
    pub translation: DVec3,
    pub rotation: DQuat,
}

impl Default for MountPose {
    fn default() -> Self {
        Self {
            translation: DVec3::ZERO,
            rotation: DQuat::IDENTITY,
        }
    }
}

impl MountPose {
    /// From a position (metres) and roll, pitch, yaw (radians) about the
    /// parent's fixed x, y, z axes, applied in that order (REP-103's RPY:
    /// `R = Rz(yaw) Ry(pitch) Rx(roll)`).
    pub fn from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Self {
        Self {
            translation: DVec3::from_array(xyz),
            rotation: DQuat::from_euler(EulerRot::ZYX, rpy[2], rpy[1], rpy[0]),
        }
    }

    /// A point of this frame in the parent's.
    pub fn apply(&self, point: DVec3) -> DVec3 {
        self.rotation * point + self.translation
    }

    /// This frame's pose followed by `inner` (inner's points into this frame's parent).
    pub fn then(&self, inner: &MountPose) -> MountPose {
        MountPose {
            translation: self.apply(inner.translation),
            rotation: self.rotation * inner.rotation,
        }
    }
}

impl FromStr for MountPose {
    type Err = AssemblyError;

    /// `x,y,z,roll,pitch,yaw`: metres, then degrees.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let v = parse_numbers(
            "mount pose (x,y,z,roll,pitch,yaw in m and degrees)",
            text,
            6,
        )?;
        Ok(Self::from_xyz_rpy(
            [v[0], v[1], v[2]],
            [v[3].to_radians(), v[4].to_radians(), v[5].to_radians()],
        ))
    }
}
