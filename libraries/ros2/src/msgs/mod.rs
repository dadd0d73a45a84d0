//! ROS 2 Jazzy messages as plain structs, one file per ROS package, fields
//! named and ordered as in the package's `.msg` definitions.

#[macro_use]
mod message;
mod builtin_interfaces;
mod diagnostic_msgs;
mod geometry_msgs;
mod sensor_msgs;
mod std_msgs;
mod tf2_msgs;
mod type_name;
mod visualization_msgs;

pub use builtin_interfaces::{Duration, Time};
pub use diagnostic_msgs::{DiagnosticStatus, KeyValue};
pub use geometry_msgs::{Point, Pose, Quaternion, Transform, TransformStamped, Vector3};
pub use message::RosMessage;
pub use sensor_msgs::{CompressedImage, JointState, PointCloud2, PointField};
pub use std_msgs::{ColorRGBA, Float64, Header};
pub use tf2_msgs::TFMessage;
pub use type_name::{dds_type_name, TypeNameError};
pub use visualization_msgs::{Marker, MarkerArray, MeshFile, UVCoordinate};
