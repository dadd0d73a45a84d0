//! geometry_msgs (common_interfaces, Jazzy): Point, Vector3, Quaternion, Pose,
//! Transform and TransformStamped, all float64.

use super::std_msgs::Header;

ros_message! {
    /// A position (geometry_msgs/msg/Point).
    "geometry_msgs/msg/Point",
    "RIHS01_6963084842a9b04494d6b2941d11444708d892da2f4b09843b9c43f42a7f6881";
    pub struct Point {
        pub x: f64,
        pub y: f64,
        pub z: f64,
    }
}

ros_message! {
    /// A direction or a scale (geometry_msgs/msg/Vector3).
    "geometry_msgs/msg/Vector3",
    "RIHS01_cc12fe83e4c02719f1ce8070bfd14aecd40f75a96696a67a2a1f37f7dbb0765d";
    pub struct Vector3 {
        pub x: f64,
        pub y: f64,
        pub z: f64,
    }
}

ros_message! {
    /// A rotation (geometry_msgs/msg/Quaternion; the .msg defaults w to 1,
    /// [`Quaternion::IDENTITY`] here, `Default` is all zero).
    "geometry_msgs/msg/Quaternion",
    "RIHS01_8a765f66778c8ff7c8ab94afcc590a2ed5325a1d9a076ffff38fbce36f458684";
    pub struct Quaternion {
        pub x: f64,
        pub y: f64,
        pub z: f64,
        pub w: f64,
    }
}

impl Quaternion {
    /// No rotation.
    pub const IDENTITY: Self = Self {
        x: 0.0,
        y: 0.0,
        z: 0.0,
        w: 1.0,
    };
}

ros_message! {
    /// A position and an orientation (geometry_msgs/msg/Pose).
    "geometry_msgs/msg/Pose",
    "RIHS01_d501954e9476cea2996984e812054b68026ae0bfae789d9a10b23daf35cc90fa";
    pub struct Pose {
        pub position: Point,
        pub orientation: Quaternion,
    }
}

ros_message! {
    /// A frame's placement in its parent (geometry_msgs/msg/Transform).
    "geometry_msgs/msg/Transform",
    "RIHS01_beb83fbe698636351461f6f35d1abb20010c43d55374d81bd041f1ba2581fddc";
    pub struct Transform {
        pub translation: Vector3,
        pub rotation: Quaternion,
    }
}

ros_message! {
    /// `child_frame_id` placed in `header.frame_id` at `header.stamp`
    /// (geometry_msgs/msg/TransformStamped).
    "geometry_msgs/msg/TransformStamped",
    "RIHS01_0a241f87d04668d94099cbb5ba11691d5ad32c2f29682e4eb5653424bd275206";
    pub struct TransformStamped {
        pub header: Header,
        pub child_frame_id: String,
        pub transform: Transform,
    }
}
