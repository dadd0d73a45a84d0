//! Wire constants of the RPLIDAR serial protocol: request and answer sync
//! bytes, command opcodes, answer types and configuration keys.
//!
//! Source: Slamtec `rplidar_sdk` @99478e5, `sdk/include/sl_lidar_protocol.h`
//! and `sdk/include/sl_lidar_cmd.h`; "RPLIDAR Interface Protocol and
//! Application Notes" §2 (packet formats) and §4 (requests).

/// First byte of every request (`SL_LIDAR_CMD_SYNC_BYTE`).
pub const REQUEST_SYNC: u8 = 0xA5;
/// Command bit saying a size byte, a payload and a checksum follow
/// (`SL_LIDAR_CMDFLAG_HAS_PAYLOAD`).
pub const HAS_PAYLOAD: u8 = 0x80;
/// First two bytes of every response descriptor (`SL_LIDAR_ANS_SYNC_BYTE1/2`).
pub const ANSWER_SYNC: [u8; 2] = [0xA5, 0x5A];
/// Send mode of a descriptor whose answer repeats until the next request
/// (`SL_LIDAR_ANS_PKTFLAG_LOOP`, bits 30..31 of the size word).
pub const SEND_MODE_LOOP: u32 = 0x1;

/// Request opcodes (`SL_LIDAR_CMD_*`).
pub mod cmd {
    pub const STOP: u8 = 0x25;
    pub const SCAN: u8 = 0x20;
    pub const FORCE_SCAN: u8 = 0x21;
    pub const RESET: u8 = 0x40;
    pub const GET_INFO: u8 = 0x50;
    pub const GET_HEALTH: u8 = 0x52;
    pub const GET_SAMPLERATE: u8 = 0x59;
    pub const EXPRESS_SCAN: u8 = 0x82;
    pub const GET_LIDAR_CONF: u8 = 0x84;
    pub const SET_MOTOR_PWM: u8 = 0xF0;
    pub const GET_ACC_BOARD_FLAG: u8 = 0xFF;
}

/// Answer types, the last byte of a descriptor (`SL_LIDAR_ANS_TYPE_*`).
pub mod answer {
    pub const DEVINFO: u8 = 0x04;
    pub const DEVHEALTH: u8 = 0x06;
    pub const SAMPLE_RATE: u8 = 0x15;
    pub const GET_LIDAR_CONF: u8 = 0x20;
    pub const MEASUREMENT: u8 = 0x81;
    pub const MEASUREMENT_CAPSULED: u8 = 0x82;
    pub const MEASUREMENT_DENSE_CAPSULED: u8 = 0x85;
    pub const ACC_BOARD_FLAG: u8 = 0xFF;
}

/// GET_LIDAR_CONF keys (`SL_LIDAR_CONF_*`); the per-mode keys take a u16
/// scan-mode id after the key in the request payload
/// (`sl_lidar_driver.cpp`, `getLidarSampleDuration()` and siblings).
pub mod conf {
    pub const SCAN_MODE_COUNT: u32 = 0x70;
    pub const SCAN_MODE_US_PER_SAMPLE: u32 = 0x71;
    pub const SCAN_MODE_MAX_DISTANCE: u32 = 0x74;
    pub const SCAN_MODE_ANS_TYPE: u32 = 0x75;
    pub const SCAN_MODE_TYPICAL: u32 = 0x7C;
    pub const SCAN_MODE_NAME: u32 = 0x7F;
}

/// Bit 0 of the GET_ACC_BOARD_FLAG answer: the board drives the motor by
/// PWM (`SL_LIDAR_RESP_ACC_BOARD_FLAG_MOTOR_CTRL_SUPPORT_MASK`).
pub const ACC_BOARD_MOTOR_CTRL: u32 = 0x1;

/// One full turn in q6 degrees (angles on the wire are degrees × 64).
pub const FULL_TURN_Q6: i64 = 360 << 6;
