//! What RViz draws of shroud, as `visualization_msgs/MarkerArray`s: each
//! surrogate's certified surfaces as triangle lists over their kept cells,
//! and the arm's collision shapes coloured by the guard's clearance bands.

mod arm;
mod surrogate;

pub use arm::arm_markers;
pub use surrogate::surrogate_markers;

use crate::time_of_ns;
use glam::DVec3;
use shroud_ros2::{ColorRGBA, Header, Marker, Point, Pose, Quaternion, Vector3};

/// A marker of `kind` with everything RViz reads set: identity pose, unit
/// scale, opaque white, no lifetime (it stays until replaced or deleted).
fn marker(frame_id: &str, stamp_ns: u64, ns: &str, id: i32, kind: i32) -> Marker {
    Marker {
        header: Header {
            stamp: time_of_ns(stamp_ns),
            frame_id: frame_id.to_owned(),
        },
        ns: ns.to_owned(),
        id,
        type_: kind,
        action: Marker::ADD,
        pose: pose_at(DVec3::ZERO, glam::DQuat::IDENTITY),
        scale: Vector3 {
            x: 1.0,
            y: 1.0,
            z: 1.0,
        },
        color: rgba([1.0; 4]),
        ..Marker::default()
    }
}

fn point(p: DVec3) -> Point {
    Point {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

fn pose_at(position: DVec3, rotation: glam::DQuat) -> Pose {
    Pose {
        position: point(position),
        orientation: Quaternion {
            x: rotation.x,
            y: rotation.y,
            z: rotation.z,
            w: rotation.w,
        },
    }
}

fn rgba(c: [f64; 4]) -> ColorRGBA {
    ColorRGBA {
        r: c[0] as f32,
        g: c[1] as f32,
        b: c[2] as f32,
        a: c[3] as f32,
    }
}
