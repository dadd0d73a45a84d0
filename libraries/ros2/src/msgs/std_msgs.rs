//! std_msgs (common_interfaces, Jazzy): Header.msg, ColorRGBA.msg, Float64.msg.

use super::builtin_interfaces::Time;

ros_message! {
    /// A stamp and the frame data is expressed in (std_msgs/msg/Header).
    "std_msgs/msg/Header",
    "RIHS01_f49fb3ae2cf070f793645ff749683ac6b06203e41c891e17701b1cb597ce6a01";
    pub struct Header {
        pub stamp: Time,
        pub frame_id: String,
    }
}

ros_message! {
    /// A color, each channel in [0, 1] (std_msgs/msg/ColorRGBA).
    "std_msgs/msg/ColorRGBA",
    "RIHS01_77a7a5b9ae477306097665106e0413ba74440245b1f3d0c6d6405fe5c7813fe8";
    pub struct ColorRGBA {
        pub r: f32,
        pub g: f32,
        pub b: f32,
        pub a: f32,
    }
}

ros_message! {
    /// One float64 (std_msgs/msg/Float64).
    "std_msgs/msg/Float64",
    "RIHS01_705ba9c3d1a09df43737eb67095534de36fd426c0587779bda2bc51fe790182a";
    pub struct Float64 {
        pub data: f64,
    }
}
