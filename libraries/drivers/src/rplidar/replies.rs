//! Decoders of the single answers the handshake reads: `GET_INFO`,
//! `GET_HEALTH`, `GET_SAMPLERATE` and `GET_ACC_BOARD_FLAG` (struct layouts
//! `sl_lidar_response_device_info_t`, `…_device_health_t`,
//! `…_sample_rate_t`, `…_acc_board_flag_t` in `sl_lidar_cmd.h`; all
//! little-endian). Longer payloads are accepted (later firmware may append
//! fields); shorter ones are rejected.

use super::protocol::health;

/// An answer payload too short for its type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("{what} answer has {got} bytes, needs {needed}")]
pub struct ShortReply {
    pub what: &'static str,
    pub needed: usize,
    pub got: usize,
}

fn take<const N: usize>(payload: &[u8], what: &'static str) -> Result<[u8; N], ShortReply> {
    payload
        .get(..N)
        .and_then(|head| <[u8; N]>::try_from(head).ok())
        .ok_or(ShortReply {
            what,
            needed: N,
            got: payload.len(),
        })
}

/// `GET_INFO`: model, firmware, hardware revision, serial number.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DeviceInfo {
    /// Model id: high nibble the major model (1 = A1, 2 = A2, 3 = A3,
    /// 4 = C series, 6.. = S series...), low nibble the sub-model.
    pub model: u8,
    pub firmware_major: u8,
    pub firmware_minor: u8,
    pub hardware: u8,
    pub serial: [u8; 16],
}

impl DeviceInfo {
    pub fn parse(payload: &[u8]) -> Result<Self, ShortReply> {
        let bytes: [u8; 20] = take(payload, "GET_INFO")?;
        let [model, minor, major, hardware, serial @ ..] = bytes;
        Ok(Self {
            model,
            firmware_major: major,
            firmware_minor: minor,
            hardware,
            serial,
        })
    }

    /// The firmware as the SDK compares it: `major << 8 | minor`.
    pub fn firmware(&self) -> u16 {
        u16::from(self.firmware_major) << 8 | u16::from(self.firmware_minor)
    }

    /// The major model id (`model >> 4`).
    pub fn model_major(&self) -> u8 {
        self.model >> 4
    }

    /// `major.minor`, the minor with two digits (as Slamtec prints it: 1.29).
    pub fn firmware_text(&self) -> String {
        format!("{}.{:02}", self.firmware_major, self.firmware_minor)
    }

    /// The serial number as 32 upper-case hex digits, in wire order (as the
    /// SDK's `ultra_simple` prints it).
    pub fn serial_hex(&self) -> String {
        self.serial.iter().map(|b| format!("{b:02X}")).collect()
    }

    /// The model's name by the SDK's rule (`GetModelNameStringByModelID` and
    /// `ParseLIDARMajorTypeByModelID` in `sl_lidar_driver.cpp`): majors 1..3
    /// are A series, 4..5 C, 6..8 S, 9..11 T, 12.. M.
    pub fn model_name(&self) -> String {
        let (major, minor) = (self.model_major(), self.model & 0x0F);
        let (series, first) = match major {
            12.. => ('M', 12),
            9.. => ('T', 9),
            6.. => ('S', 6),
            4.. => ('C', 4),
            1.. => ('A', 1),
            _ => return format!("unknown({:#04x})", self.model),
        };
        format!("{series}{}M{minor}", major - first + 1)
    }

    /// Whether the device answers `GET_LIDAR_CONF`: firmware 1.24 or later,
    /// or a "new design" model (major >= 4) (`checkSupportConfigCommands`,
    /// `_checkNDMagicNumber` in `sl_lidar_driver.cpp`).
    pub fn supports_lidar_conf(&self) -> bool {
        self.model_major() >= 4 || self.firmware() >= 0x0118
    }

    /// Whether the device answers `GET_SAMPLERATE`: A series before firmware
    /// 1.17 does not (`_getLegacySampleDuration_uS`).
    pub fn supports_sample_rate(&self) -> bool {
        self.model_major() >= 4 || self.firmware() >= 0x0111
    }

    /// Whether legacy express scan (EXPRESS_SCAN working mode 0) can be
    /// assumed without a mode list: A series, firmware 1.17+
    /// (`sl_lidar_cmd.h`: "added in fw 1.17"). Later series list their
    /// modes through `GET_LIDAR_CONF` instead.
    pub fn supports_express(&self) -> bool {
        self.model_major() < 4 && self.firmware() >= 0x0111
    }

    /// Models with motor speed control built in take `SET_MOTOR_RPM`
    /// (major >= 6, `BUILTIN_MOTORCTL_MINUM_MAJOR_ID` in
    /// `checkMotorCtrlSupport`).
    pub fn has_builtin_motor_control(&self) -> bool {
        self.model_major() >= 6
    }
}

/// The `GET_HEALTH` status byte.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HealthStatus {
    Ok,
    Warning,
    Error,
    /// A value the protocol does not define.
    Unknown(u8),
}

/// `GET_HEALTH`: status and the device's error code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Health {
    pub status: HealthStatus,
    pub error_code: u16,
}

impl Health {
    pub fn parse(payload: &[u8]) -> Result<Self, ShortReply> {
        let [status, lo, hi] = take(payload, "GET_HEALTH")?;
        let status = match status {
            health::OK => HealthStatus::Ok,
            health::WARNING => HealthStatus::Warning,
            health::ERROR => HealthStatus::Error,
            other => HealthStatus::Unknown(other),
        };
        Ok(Self {
            status,
            error_code: u16::from_le_bytes([lo, hi]),
        })
    }

    /// Human-readable status for `DriverOutput::Health`.
    pub fn detail(&self) -> String {
        let status = match self.status {
            HealthStatus::Ok => "ok".to_string(),
            HealthStatus::Warning => "warning".to_string(),
            HealthStatus::Error => "error".to_string(),
            HealthStatus::Unknown(v) => format!("unknown status {v}"),
        };
        format!("{status}, error code {:#06x}", self.error_code)
    }
}

/// `GET_SAMPLERATE`: sample durations of the standard and express scans, µs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SampleRate {
    pub standard_us: u16,
    pub express_us: u16,
}

impl SampleRate {
    pub fn parse(payload: &[u8]) -> Result<Self, ShortReply> {
        let [a, b, c, d] = take(payload, "GET_SAMPLERATE")?;
        Ok(Self {
            standard_us: u16::from_le_bytes([a, b]),
            express_us: u16::from_le_bytes([c, d]),
        })
    }
}

/// `GET_ACC_BOARD_FLAG`: whether the accessory board drives the motor by PWM
/// (bit 0, `SL_LIDAR_RESP_ACC_BOARD_FLAG_MOTOR_CTRL_SUPPORT_MASK`).
pub fn parse_acc_board_pwm(payload: &[u8]) -> Result<bool, ShortReply> {
    let flags = u32::from_le_bytes(take(payload, "GET_ACC_BOARD_FLAG")?);
    Ok(flags & 1 != 0)
}
