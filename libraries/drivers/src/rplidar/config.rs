//! What the node tells the RPLIDAR driver: link speed, scan mode, motor
//! control and timeouts.

use std::time::Duration;

/// Which scan to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ScanMode {
    /// `SCAN`: 5-byte nodes, with quality (every model).
    Standard,
    /// Legacy express capsules (answer type 0x82; A series, firmware 1.17+).
    Express,
    /// Dense capsules (answer type 0x85; S/C series "DenseBoost").
    Dense,
    /// The device's typical mode (`GET_LIDAR_CONF`, firmware 1.24+) when its
    /// answer type is one this driver decodes, else a listed express mode,
    /// else legacy express (A series, firmware 1.17+), else standard. A
    /// configured mode the device lacks falls back to this choice (counted
    /// `unsupported_scan_mode`).
    #[default]
    Auto,
}

/// How the motor is driven.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MotorControl {
    /// Models with built-in motor control (major model id >= 6) take
    /// `SET_MOTOR_RPM` 600; others are asked `GET_ACC_BOARD_FLAG`, and an
    /// accessory board with PWM support takes `SET_MOTOR_PWM` 660; otherwise
    /// (no answer, or no PWM support) the DTR line.
    #[default]
    Auto,
    /// The DTR line gates the motor (A1): deasserted runs it, asserted stops
    /// it, as the SDK's `setMotorSpeed` does.
    Dtr,
    /// `SET_MOTOR_PWM` with this duty (0..1023 on A2) to run, 0 to stop.
    Pwm(u16),
    /// `SET_MOTOR_RPM` with this speed to run, 0 to stop.
    Rpm(u16),
}

/// The RPLIDAR driver's settings.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RplidarConfig {
    /// The link's baud rate; the node opens the port at it. It also enters
    /// the timing model (the transmission time of each packet). A1 and A2M8
    /// run at 115200, A2M12/A3/S1 at 256000 (`rplidar_ros` launch files).
    pub baud: u32,
    pub scan_mode: ScanMode,
    pub motor: MotorControl,
    /// How long to wait for an answer before asking once more (then giving
    /// up and asking for a reconnect). Optional queries are not repeated.
    pub reply_timeout: Duration,
    /// How long the stream may go without a complete revolution (from its
    /// start, or the last revolution) before the driver asks for a
    /// reconnect. Covers the motor's spin-up and the discarded first
    /// revolution.
    pub stream_timeout: Duration,
    /// The most rays a revolution may have; a longer one is dropped
    /// (`oversize_scan`). The SDK buffers 8192 (`MAX_SCANNODE_CACHE_COUNT`).
    pub max_rays: usize,
}

impl Default for RplidarConfig {
    fn default() -> Self {
        Self {
            baud: 115_200,
            scan_mode: ScanMode::Auto,
            motor: MotorControl::Auto,
            reply_timeout: Duration::from_secs(1),
            stream_timeout: Duration::from_secs(3),
            max_rays: 8192,
        }
    }
}
