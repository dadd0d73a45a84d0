//! Encodes the RPLIDAR's single answers and response descriptors: GET_INFO,
//! GET_HEALTH, GET_SAMPLERATE, GET_LIDAR_CONF, GET_ACC_BOARD_FLAG and the
//! ASCII banner printed after a reset.

use super::model::{ModelSpec, ScanModeSpec};
use super::options::RplidarHealth;
use super::protocol::{answer, conf, ACC_BOARD_MOTOR_CTRL, ANSWER_SYNC, SEND_MODE_LOOP};

/// A response descriptor: `A5 5A`, a u32 LE holding the answer length in
/// bits 0..29 and the send mode in bits 30..31, then the answer type
/// (`sl_lidar_ans_header_t`; protocol PDF §2 "Response Descriptor").
pub(crate) fn descriptor(len: u32, looping: bool, answer_type: u8) -> [u8; 7] {
    let mode = if looping { SEND_MODE_LOOP } else { 0 };
    let word = (len & 0x3FFF_FFFF) | (mode << 30);
    let [w0, w1, w2, w3] = word.to_le_bytes();
    [ANSWER_SYNC[0], ANSWER_SYNC[1], w0, w1, w2, w3, answer_type]
}

/// A single answer: its descriptor, then its payload.
fn single(answer_type: u8, payload: &[u8]) -> Vec<u8> {
    let len = u32::try_from(payload.len()).unwrap_or(u32::MAX);
    let mut out = descriptor(len, false, answer_type).to_vec();
    out.extend_from_slice(payload);
    out
}

/// GET_INFO: model, firmware minor, firmware major, hardware, 16-byte serial
/// (`sl_lidar_response_device_info_t`; the u16 firmware is major << 8 |
/// minor, little-endian on the wire).
pub(crate) fn device_info(spec: &ModelSpec, serial: &[u8; 16]) -> Vec<u8> {
    let mut payload = vec![
        spec.model_id,
        spec.firmware_minor,
        spec.firmware_major,
        spec.hardware,
    ];
    payload.extend_from_slice(serial);
    single(answer::DEVINFO, &payload)
}

/// GET_HEALTH: status byte and u16 LE error code
/// (`sl_lidar_response_device_health_t`).
pub(crate) fn health(health: RplidarHealth) -> Vec<u8> {
    let [c0, c1] = health.error_code().to_le_bytes();
    single(answer::DEVHEALTH, &[health.status_byte(), c0, c1])
}

/// GET_SAMPLERATE: standard and express sample durations in µs, u16 LE each
/// (`sl_lidar_response_sample_rate_t`).
pub(crate) fn sample_rate(spec: &ModelSpec) -> Vec<u8> {
    let mut payload = spec.standard_us.to_le_bytes().to_vec();
    payload.extend_from_slice(&spec.express_us.to_le_bytes());
    single(answer::SAMPLE_RATE, &payload)
}

/// GET_ACC_BOARD_FLAG: u32 LE support flags, bit 0 = PWM motor control
/// (`sl_lidar_response_acc_board_flag_t`).
pub(crate) fn acc_board_flag() -> Vec<u8> {
    single(answer::ACC_BOARD_FLAG, &ACC_BOARD_MOTOR_CTRL.to_le_bytes())
}

/// GET_LIDAR_CONF for `key` (with the u16 mode id `mode` for per-mode keys):
/// the answer echoes the u32 key, then the entry's value
/// (`sl_lidar_response_get_lidar_conf_t`). Payload layouts, from the SDK's
/// readers in `sl_lidar_driver.cpp`: mode count u16, µs per sample u32 q8,
/// max distance u32 q8 metres, answer type u8, typical mode u16, name ASCII
/// (sent NUL-terminated). `None` for an unknown key or mode: the device
/// does not answer.
pub(crate) fn lidar_conf(spec: &ModelSpec, key: u32, mode: u16) -> Option<Vec<u8>> {
    let value = conf_value(spec, key, mode)?;
    let mut payload = key.to_le_bytes().to_vec();
    payload.extend_from_slice(&value);
    Some(single(answer::GET_LIDAR_CONF, &payload))
}

fn conf_value(spec: &ModelSpec, key: u32, mode: u16) -> Option<Vec<u8>> {
    match key {
        conf::SCAN_MODE_COUNT => {
            let count = u16::try_from(spec.modes.len()).unwrap_or(u16::MAX);
            Some(count.to_le_bytes().to_vec())
        }
        conf::SCAN_MODE_TYPICAL => Some(spec.typical_mode.to_le_bytes().to_vec()),
        _ => mode_value(spec.modes.get(usize::from(mode))?, key),
    }
}

fn mode_value(mode: &ScanModeSpec, key: u32) -> Option<Vec<u8>> {
    match key {
        conf::SCAN_MODE_US_PER_SAMPLE => Some((mode.us_per_sample << 8).to_le_bytes().to_vec()),
        conf::SCAN_MODE_MAX_DISTANCE => Some((mode.max_distance_m << 8).to_le_bytes().to_vec()),
        conf::SCAN_MODE_ANS_TYPE => Some(vec![mode.format.answer_type()]),
        conf::SCAN_MODE_NAME => {
            let mut name = mode.name.as_bytes().to_vec();
            name.push(0);
            Some(name)
        }
        _ => None,
    }
}

/// The ASCII banner the core prints when it boots after RESET. Its first
/// words follow the one quoted in sllidar_ros2 issue #6 ("RP LIDAR System.
/// Firmware Ver 1.27…"); the rest of the wording is this emulator's.
pub(crate) fn banner(spec: &ModelSpec) -> Vec<u8> {
    format!(
        "RP LIDAR System.\r\nFirmware Ver {}.{:02} - rtm, HW Ver {}\r\nModel: {:02X}\r\n",
        spec.firmware_major, spec.firmware_minor, spec.hardware, spec.model_id
    )
    .into_bytes()
}
