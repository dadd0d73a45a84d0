//! The TF a ROS user needs to show shroud's markers and the sensor's own
//! cloud together: the sensor frame's mount in shroud's world frame, as a
//! `geometry_msgs/TransformStamped` for `/tf_static`.

use crate::{time_of_ns, CloudMount};
use shroud_ros2::{Header, Quaternion, Transform, TransformStamped, Vector3};

/// `child` (the ROS cloud's frame) placed in `parent` (shroud's world) by
/// `mount`.
pub fn mount_transform(
    parent: &str,
    child: &str,
    mount: &CloudMount,
    stamp_ns: u64,
) -> TransformStamped {
    let [x, y, z] = mount.position;
    let q = mount.rotation();
    TransformStamped {
        header: Header {
            stamp: time_of_ns(stamp_ns),
            frame_id: parent.to_owned(),
        },
        child_frame_id: child.to_owned(),
        transform: Transform {
            translation: Vector3 { x, y, z },
            rotation: Quaternion {
                x: q.x,
                y: q.y,
                z: q.z,
                w: q.w,
            },
        },
    }
}
