//! Request framing: the bytes the host writes for each command.
//!
//! Protocol PDF §"Request packets' format" and the SDK's
//! `RPLidarProtocolCodec::onEncodeData` (`sdk/src/sl_lidarprotocol_codec.cpp`):
//! a command without payload is `A5 cmd`; a command whose opcode has bit 7
//! set is `A5 cmd size payload… checksum`, where the checksum is the XOR of
//! every preceding byte, `A5` included.

use super::protocol::{cmd, HAS_PAYLOAD, REQUEST_SYNC};

/// The bytes of one request. For an opcode without [`HAS_PAYLOAD`] the payload
/// is not sent (the protocol has no room for it); a payload longer than 255
/// bytes is cut to 255 (the size field is one byte). Our own payloads are at
/// most 6 bytes.
pub fn encode(opcode: u8, payload: &[u8]) -> Vec<u8> {
    if opcode & HAS_PAYLOAD == 0 {
        return vec![REQUEST_SYNC, opcode];
    }
    let payload = payload.get(..255).unwrap_or(payload);
    let mut frame = Vec::with_capacity(payload.len() + 4);
    frame.extend_from_slice(&[REQUEST_SYNC, opcode, payload.len() as u8]);
    frame.extend_from_slice(payload);
    let checksum = frame.iter().fold(0u8, |acc, b| acc ^ b);
    frame.push(checksum);
    frame
}

/// `EXPRESS_SCAN` with `working_mode`, no flags: payload
/// `working_mode u8, working_flags u16 LE, param u16 LE`
/// (`sl_lidar_payload_express_scan_t`). Mode 0 is the legacy express scan.
pub fn express_scan(working_mode: u8) -> Vec<u8> {
    encode(cmd::EXPRESS_SCAN, &[working_mode, 0, 0, 0, 0])
}

/// `GET_LIDAR_CONF` for `key`, with the scan mode id appended when the key is
/// per mode (`getLidarConf` in `sl_lidar_driver.cpp`: `type u32 LE` then the
/// optional `u16 LE` mode id).
pub fn lidar_conf(key: u32, mode: Option<u16>) -> Vec<u8> {
    let mut payload = key.to_le_bytes().to_vec();
    if let Some(mode) = mode {
        payload.extend_from_slice(&mode.to_le_bytes());
    }
    encode(cmd::GET_LIDAR_CONF, &payload)
}

/// `GET_ACC_BOARD_FLAG` with its reserved `u32` of zero
/// (`sl_lidar_payload_acc_board_flag_t`).
pub fn acc_board_flag() -> Vec<u8> {
    encode(cmd::GET_ACC_BOARD_FLAG, &[0, 0, 0, 0])
}

/// A motor command with its `u16 LE` value: `SET_MOTOR_PWM` (duty) or
/// `SET_MOTOR_RPM` (speed), as `setMotorSpeed` in `sl_lidar_driver.cpp` sends.
pub fn motor(opcode: u8, value: u16) -> Vec<u8> {
    encode(opcode, &value.to_le_bytes())
}
