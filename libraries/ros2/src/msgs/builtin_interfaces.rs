//! builtin_interfaces (rcl_interfaces, Jazzy): Time.msg and Duration.msg.

ros_message! {
    /// A point in time (builtin_interfaces/msg/Time).
    "builtin_interfaces/msg/Time",
    "RIHS01_b106235e25a4c5ed35098aa0a61a3ee9c9b18d197f398b0e4206cea9acf9c197";
    pub struct Time {
        pub sec: i32,
        /// Nanoseconds past `sec`, below 1e9 (not checked: ROS does not either).
        pub nanosec: u32,
    }
}

ros_message! {
    /// A span of time (builtin_interfaces/msg/Duration); zero means forever
    /// where a lifetime is meant (Marker.lifetime).
    "builtin_interfaces/msg/Duration",
    "RIHS01_e8d009f659816f758b75334ee1a9ca5b5c0b859843261f14c7f937349599d93b";
    pub struct Duration {
        pub sec: i32,
        pub nanosec: u32,
    }
}
