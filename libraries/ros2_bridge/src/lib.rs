//! What ROS 2 messages mean to shroud, without I/O: a `PointCloud2` read in
//! any field layout and placed in shroud's world by its sensor's mount (its
//! rays without a return stated as unseen), a `JointState` matched to an
//! arm's joints, and shroud's clouds, surrogates, arm clearances and verdicts
//! as the ROS 2 messages a ROS user displays or acts on. The wire itself
//! (CDR, rmw_zenoh's keys, tokens and attachment) is `shroud-ros2`; zenoh and
//! clocks are the `ros2` node's (`shroud-nodes`).

mod cloud_in;
mod cloud_out;
mod error;
mod joints_in;
mod markers;
mod stamp;
mod transform;
mod verdict;

pub use cloud_in::{cloud_from_ros, CloudMount, PinholeCamera, PointLayout, RosCloud};
pub use cloud_out::point_cloud2_of;
pub use error::{CloudInError, JointsInError};
pub use joints_in::{JointMatcher, MatchedJoints};
pub use markers::{arm_markers, surrogate_markers};
pub use stamp::{ns_of_time, time_of_ns};
pub use transform::mount_transform;
pub use verdict::{speed_scale_of, verdict_status, VerdictLevel};
