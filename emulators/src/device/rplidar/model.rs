//! The emulated RPLIDAR models and what each one reports about itself:
//! GET_INFO identity, rates, motor drive and scan-mode table.

use super::protocol::answer;

/// An emulated RPLIDAR model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RplidarModel {
    /// RPLIDAR A1 (A1M8): 115200 baud, ~5.5 Hz, motor gated by the host's
    /// DTR line.
    A1,
    /// RPLIDAR A2 (A2M8): 115200 baud, 10 Hz, motor driven by SET_MOTOR_PWM
    /// through the accessory board.
    A2,
}

impl RplidarModel {
    /// Every model, in name order.
    pub const ALL: [RplidarModel; 2] = [RplidarModel::A1, RplidarModel::A2];

    /// The model's name: `rplidar-a1` or `rplidar-a2`.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// The model called `name` (as [`RplidarModel::name`] spells it).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|model| model.name() == name)
    }

    pub(crate) fn spec(self) -> &'static ModelSpec {
        match self {
            RplidarModel::A1 => &A1,
            RplidarModel::A2 => &A2,
        }
    }
}

/// How the host drives a model's motor (`sl_lidar_driver.cpp`,
/// `setMotorSpeed()` and `checkMotorCtrlSupport()`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MotorDrive {
    /// DTR asserted stops the motor, released runs it at its nominal speed.
    Dtr,
    /// SET_MOTOR_PWM sets the duty; GET_ACC_BOARD_FLAG reports bit 0.
    Pwm,
}

/// How the samples of a scan mode travel on the wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum StreamFormat {
    /// 5-byte nodes, answer type 0x81.
    Standard,
    /// Legacy express capsules: 84 bytes, 32 samples, answer type 0x82.
    Capsule,
    /// Dense capsules: 84 bytes, 40 distances, answer type 0x85.
    DenseCapsule,
}

impl StreamFormat {
    /// The answer type byte of the descriptor.
    pub(crate) fn answer_type(self) -> u8 {
        match self {
            StreamFormat::Standard => answer::MEASUREMENT,
            StreamFormat::Capsule => answer::MEASUREMENT_CAPSULED,
            StreamFormat::DenseCapsule => answer::MEASUREMENT_DENSE_CAPSULED,
        }
    }

    /// Bytes per answer packet (`sizeof` of the SDK's packet structs).
    pub(crate) fn packet_len(self) -> u32 {
        match self {
            StreamFormat::Standard => 5,
            StreamFormat::Capsule | StreamFormat::DenseCapsule => 84,
        }
    }

    /// Samples per answer packet.
    pub(crate) fn samples_per_packet(self) -> usize {
        match self {
            StreamFormat::Standard => 1,
            StreamFormat::Capsule => 32,
            StreamFormat::DenseCapsule => 40,
        }
    }
}

/// One entry of the scan-mode table GET_LIDAR_CONF enumerates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ScanModeSpec {
    pub name: &'static str,
    pub format: StreamFormat,
    pub us_per_sample: u32,
    pub max_distance_m: u32,
}

/// Everything model-specific.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ModelSpec {
    pub name: &'static str,
    /// GET_INFO model byte: major series in the high nibble, sub-model in the
    /// low one (the SDK prints it as `A<major>M<minor>`).
    pub model_id: u8,
    pub firmware_major: u8,
    pub firmware_minor: u8,
    pub hardware: u8,
    pub baud: u32,
    /// Rotation at nominal drive (DTR released, or PWM [`NOMINAL_PWM`]).
    pub rotation_hz: f64,
    pub motor: MotorDrive,
    /// GET_SAMPLERATE: standard and legacy-express sample durations.
    pub standard_us: u16,
    pub express_us: u16,
    pub min_range_m: f64,
    pub max_range_m: f64,
    pub modes: &'static [ScanModeSpec],
    pub typical_mode: u16,
}

/// The PWM duty at which an A2 turns at its nominal 10 Hz; also its
/// power-up duty. rplidar_sdk 1.x (`rplidar_cmd.h`, `DEFAULT_MOTOR_PWM`) and
/// rplidar_ros drive the A2 at 660 for its nominal rate; SDK 2.x falls back to
/// 600 when the device reports no desired speed.
pub(crate) const NOMINAL_PWM: u16 = 660;
/// The largest duty the accessory board accepts; larger requests saturate.
pub(crate) const MAX_PWM: u16 = 1023;

const STANDARD_MODE: ScanModeSpec = ScanModeSpec {
    name: "Standard",
    format: StreamFormat::Standard,
    us_per_sample: 500,
    max_distance_m: 12,
};

const EXPRESS_MODE: ScanModeSpec = ScanModeSpec {
    name: "Express",
    format: StreamFormat::Capsule,
    us_per_sample: 250,
    max_distance_m: 12,
};

/// Dense modes run at 200 µs a sample: 125 capsules × 84 bytes a second fill
/// 91 % of a 115200-baud line (8N1, 10 bits a byte).
const fn dense_mode(name: &'static str) -> ScanModeSpec {
    ScanModeSpec {
        name,
        format: StreamFormat::DenseCapsule,
        us_per_sample: 200,
        max_distance_m: 12,
    }
}

const A1_MODES: [ScanModeSpec; 2] = [STANDARD_MODE, EXPRESS_MODE];
/// Mode ids follow the A-series order users report (0 Standard, 1 Express,
/// 2 Boost, 3 Sensitivity; rplidar_ros issue logs).
const A2_MODES: [ScanModeSpec; 4] = [
    STANDARD_MODE,
    EXPRESS_MODE,
    dense_mode("Boost"),
    dense_mode("Sensitivity"),
];

/// A1M8 as reported by a firmware 1.29 unit: model 24 (0x18), hardware 7
/// (Adafruit_CircuitPython_RPLIDAR issue #15).
const A1: ModelSpec = ModelSpec {
    name: "rplidar-a1",
    model_id: 0x18,
    firmware_major: 1,
    firmware_minor: 29,
    hardware: 7,
    baud: 115_200,
    rotation_hz: 5.5,
    motor: MotorDrive::Dtr,
    standard_us: 500,
    express_us: 250,
    min_range_m: 0.15,
    max_range_m: 12.0,
    modes: &A1_MODES,
    typical_mode: 1,
};

/// A2M8: model 0x28, hardware 5 (a logged GET_INFO answer `28 19 01 05 …`).
const A2: ModelSpec = ModelSpec {
    name: "rplidar-a2",
    model_id: 0x28,
    firmware_major: 1,
    firmware_minor: 29,
    hardware: 5,
    baud: 115_200,
    rotation_hz: 10.0,
    motor: MotorDrive::Pwm,
    standard_us: 500,
    express_us: 250,
    min_range_m: 0.15,
    max_range_m: 12.0,
    modes: &A2_MODES,
    typical_mode: 3,
};
