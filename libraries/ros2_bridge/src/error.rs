//! Why a ROS 2 message could not become a shroud message: each names the
//! field or joint at fault, so that a node logs and counts it by name.

use shroud_msg::MessageError;

/// A `sensor_msgs/PointCloud2` that cannot become a shroud cloud.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum CloudInError {
    #[error("no field {name:?} (fields: {found})")]
    MissingField { name: &'static str, found: String },
    #[error("field {name:?} has datatype {datatype}, not FLOAT32 (7) or FLOAT64 (8)")]
    CoordinateType { name: String, datatype: u8 },
    #[error("field {name:?} has datatype {datatype}, not a number type (1 to 8)")]
    FieldType { name: String, datatype: u8 },
    #[error(
        "field {name:?} at offset {offset} ({size} bytes) does not fit in point_step {point_step}"
    )]
    FieldOutside {
        name: String,
        offset: u32,
        size: usize,
        point_step: u32,
    },
    #[error("point_step is 0")]
    ZeroPointStep,
    #[error("width {width} x point_step {point_step} exceeds row_step {row_step}")]
    RowTooShort {
        width: u32,
        point_step: u32,
        row_step: u32,
    },
    #[error("data is {found} bytes, row_step {row_step} x height {height} says {expected}")]
    DataLength {
        found: usize,
        row_step: u32,
        height: u32,
        expected: u128,
    },
    #[error(
        "{count} points without a return in an unorganised cloud (height 1): their rays \
         cannot be placed, so the space they looked into cannot be stated as unseen"
    )]
    UnplacedEmptyRays { count: usize },
    #[error(
        "{count} points without a return in an organised {height} x {width} cloud, and \
         no camera field of view is configured to place their rays"
    )]
    EmptyRaysWithoutCamera {
        count: usize,
        height: u32,
        width: u32,
    },
    #[error(
        "pixel ({row}, {column}) returned a point {degrees:.3} deg off its pinhole ray, more \
         than the ray spacing {spread_degrees:.3} deg: the cloud is not in the camera's optical \
         frame (z forward, x right, y down), or camera_fov is not its field of view"
    )]
    CameraModel {
        row: usize,
        column: usize,
        degrees: f64,
        spread_degrees: f64,
    },
    #[error("stamp {sec} s {nanosec} ns is not a time after the Unix epoch")]
    Stamp { sec: i32, nanosec: u32 },
    #[error("mount: {0}")]
    Mount(String),
    #[error(transparent)]
    Message(#[from] MessageError),
}

/// A `sensor_msgs/JointState` that cannot become an arm's joint state.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum JointsInError {
    #[error("{names} names but {positions} positions")]
    PositionCount { names: usize, positions: usize },
    #[error("{names} names but {velocities} velocities (expected none or one per name)")]
    VelocityCount { names: usize, velocities: usize },
    #[error("joint {joint:?} of arm {arm:?} is missing")]
    Missing { arm: String, joint: String },
    #[error("joint {joint:?} is named twice")]
    Duplicate { joint: String },
    #[error("joint {joint:?}: {what} {value} is not finite")]
    NotFinite {
        joint: String,
        what: &'static str,
        value: f64,
    },
    #[error("stamp {sec} s {nanosec} ns is not a time after the Unix epoch")]
    Stamp { sec: i32, nanosec: u32 },
}
