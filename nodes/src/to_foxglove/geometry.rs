//! Foxglove's small geometry and time types from shroud's: stamps, points,
//! poses and colours.

use foxglove::messages::{Color, Point3, Pose, Quaternion, Timestamp, Vector3};
use glam::{DQuat, DVec3};

/// The frame every shroud position is in (clouds, surfaces and the posed arm
/// are all world coordinates).
pub const WORLD_FRAME: &str = "world";

/// Nanoseconds since the Unix epoch as a Foxglove stamp (seconds saturate at
/// the year 2106, which `u32` seconds cannot pass).
pub fn timestamp(ns: u64) -> Timestamp {
    let sec = u32::try_from(ns / 1_000_000_000).unwrap_or(u32::MAX);
    Timestamp::new(sec, (ns % 1_000_000_000) as u32)
}

pub(super) fn vector(v: DVec3) -> Vector3 {
    Vector3 {
        x: v.x,
        y: v.y,
        z: v.z,
    }
}

pub(super) fn point(p: [f32; 3]) -> Point3 {
    Point3 {
        x: p[0].into(),
        y: p[1].into(),
        z: p[2].into(),
    }
}

pub(super) fn quaternion(q: DQuat) -> Quaternion {
    Quaternion {
        x: q.x,
        y: q.y,
        z: q.z,
        w: q.w,
    }
}

pub(super) fn pose(position: DVec3, orientation: DQuat) -> Pose {
    Pose {
        position: Some(vector(position)),
        orientation: Some(quaternion(orientation)),
    }
}

/// The identity pose: data already in [`WORLD_FRAME`].
pub(super) fn identity() -> Pose {
    pose(DVec3::ZERO, DQuat::IDENTITY)
}

pub(super) fn color([r, g, b, a]: [f64; 4]) -> Color {
    Color { r, g, b, a }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stamps_split_into_seconds_and_nanoseconds() {
        let t = timestamp(1_700_000_000_123_456_789);
        assert_eq!((t.sec(), t.nsec()), (1_700_000_000, 123_456_789));
        assert_eq!(timestamp(u64::MAX).sec(), u32::MAX);
    }
}
