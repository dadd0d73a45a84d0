//! diagnostic_msgs (common_interfaces, Jazzy): KeyValue.msg and DiagnosticStatus.msg.

ros_message! {
    /// One named value of a status (diagnostic_msgs/msg/KeyValue).
    "diagnostic_msgs/msg/KeyValue",
    "RIHS01_d68081eaa540288c5440753baecef0c4e16e81a5f78ad68902ded5100413bb42";
    pub struct KeyValue {
        pub key: String,
        pub value: String,
    }
}

ros_message! {
    /// The state of one component (diagnostic_msgs/msg/DiagnosticStatus).
    "diagnostic_msgs/msg/DiagnosticStatus",
    "RIHS01_b0e3e692ea2d54a8af2f4ef1930e81556a2db55216b771f8a7d2724ed47bf0e4";
    pub struct DiagnosticStatus {
        /// One of the level constants; `byte` in the .msg, so one unsigned byte.
        pub level: u8,
        pub name: String,
        pub message: String,
        pub hardware_id: String,
        pub values: Vec<KeyValue>,
    }
}

impl DiagnosticStatus {
    pub const OK: u8 = 0;
    pub const WARN: u8 = 1;
    pub const ERROR: u8 = 2;
    pub const STALE: u8 = 3;
}
