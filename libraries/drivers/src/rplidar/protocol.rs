//! The RPLIDAR serial protocol's vocabulary: sync bytes, command opcodes,
//! answer types, configuration keys and fixed packet sizes.
//!
//! Every value comes from Slamtec's SDK headers `sdk/include/sl_lidar_cmd.h`
//! and `sdk/include/sl_lidar_protocol.h` (rplidar_sdk @99478e5f), which match
//! the "RPLIDAR Interface Protocol and Application Notes" (A1/A2/A3).

/// First byte of every request (`SL_LIDAR_CMD_SYNC_BYTE`).
pub const REQUEST_SYNC: u8 = 0xA5;
/// Opcodes with this bit set carry `size payload checksum`
/// (`SL_LIDAR_CMDFLAG_HAS_PAYLOAD`).
pub const HAS_PAYLOAD: u8 = 0x80;
/// The two bytes that open a response descriptor (`SL_LIDAR_ANS_SYNC_BYTE1/2`).
pub const ANSWER_SYNC: [u8; 2] = [0xA5, 0x5A];
/// A response descriptor: 2 sync bytes, u32 LE size/mode, type byte.
pub const DESCRIPTOR_LEN: usize = 7;

/// Request opcodes (`SL_LIDAR_CMD_*`).
pub mod cmd {
    pub const STOP: u8 = 0x25;
    pub const SCAN: u8 = 0x20;
    pub const RESET: u8 = 0x40;
    pub const GET_INFO: u8 = 0x50;
    pub const GET_HEALTH: u8 = 0x52;
    /// Added in firmware 1.17.
    pub const GET_SAMPLERATE: u8 = 0x59;
    /// Motor speed in rpm, for models with built-in motor control.
    pub const SET_MOTOR_RPM: u8 = 0xA8;
    /// Added in firmware 1.17.
    pub const EXPRESS_SCAN: u8 = 0x82;
    /// Added in firmware 1.24.
    pub const GET_LIDAR_CONF: u8 = 0x84;
    /// A2 accessory board: motor PWM.
    pub const SET_MOTOR_PWM: u8 = 0xF0;
    /// A2 accessory board: which features the board supports.
    pub const GET_ACC_BOARD_FLAG: u8 = 0xFF;
}

/// Answer types, the descriptor's last byte (`SL_LIDAR_ANS_TYPE_*`).
pub mod answer {
    pub const DEVINFO: u8 = 0x04;
    pub const DEVHEALTH: u8 = 0x06;
    pub const SAMPLE_RATE: u8 = 0x15;
    pub const LIDAR_CONF: u8 = 0x20;
    pub const ACC_BOARD_FLAG: u8 = 0xFF;
    /// Standard scan: 5-byte nodes.
    pub const MEASUREMENT: u8 = 0x81;
    /// Legacy express scan: 84-byte capsules.
    pub const CAPSULED: u8 = 0x82;
    /// HQ nodes (not decoded here).
    pub const HQ: u8 = 0x83;
    /// Ultra capsules, 132 bytes (not decoded here).
    pub const CAPSULED_ULTRA: u8 = 0x84;
    /// Dense capsules: 84 bytes, 40 distances.
    pub const DENSE_CAPSULED: u8 = 0x85;
}

/// `GET_LIDAR_CONF` keys (`SL_LIDAR_CONF_*`).
pub mod conf {
    pub const SCAN_MODE_COUNT: u32 = 0x70;
    pub const SCAN_MODE_US_PER_SAMPLE: u32 = 0x71;
    pub const SCAN_MODE_MAX_DISTANCE: u32 = 0x74;
    pub const SCAN_MODE_ANS_TYPE: u32 = 0x75;
    pub const SCAN_MODE_TYPICAL: u32 = 0x7C;
    pub const SCAN_MODE_NAME: u32 = 0x7F;
}

/// `GET_HEALTH` status values (`SL_LIDAR_STATUS_*`).
pub mod health {
    pub const OK: u8 = 0;
    pub const WARNING: u8 = 1;
    pub const ERROR: u8 = 2;
}

/// Size of one standard-scan node (`sl_lidar_response_measurement_node_t`).
pub const NODE_LEN: usize = 5;
/// Size of a legacy express capsule and of a dense capsule
/// (`sl_lidar_response_capsule_measurement_nodes_t`,
/// `sl_lidar_response_dense_capsule_measurement_nodes_t`).
pub const CAPSULE_LEN: usize = 84;
/// Size of an ultra capsule (`sl_lidar_response_ultra_capsule_measurement_nodes_t`).
pub const ULTRA_CAPSULE_LEN: usize = 132;

/// Sample duration the SDK assumes when a device cannot say
/// (`LEGACY_SAMPLE_DURATION` in `sl_lidar_driver.cpp`), in µs.
pub const LEGACY_SAMPLE_US: u32 = 476;
