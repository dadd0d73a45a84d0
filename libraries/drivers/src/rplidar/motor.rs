//! Motor control: which of the three mechanisms a device uses, and the
//! outputs that start and stop it (`setMotorSpeed` and
//! `checkMotorCtrlSupport` in `sl_lidar_driver.cpp`).

use super::config::MotorControl;
use super::device::DriverOutput;
use super::protocol::cmd;
use super::replies::DeviceInfo;
use super::request;

/// PWM duty for an A2 accessory board (`DEFAULT_MOTOR_PWM` in the 1.x SDK's
/// `rplidar_cmd.h`; the maximum is 1023).
pub const DEFAULT_PWM: u16 = 660;
/// Speed for built-in motor control when the device is not asked for its
/// preferred one (the SDK's fallback in `setMotorSpeed`).
pub const DEFAULT_RPM: u16 = 600;

/// The mechanism in use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotorDrive {
    Dtr,
    Pwm(u16),
    Rpm(u16),
}

impl MotorDrive {
    /// The mechanism a configuration names outright (`None` for `Auto`).
    pub fn configured(control: MotorControl) -> Option<Self> {
        match control {
            MotorControl::Auto => None,
            MotorControl::Dtr => Some(Self::Dtr),
            MotorControl::Pwm(v) => Some(Self::Pwm(v)),
            MotorControl::Rpm(v) => Some(Self::Rpm(v)),
        }
    }

    /// `Auto`'s choice: built-in control by model, else the accessory
    /// board's PWM flag (`board_pwm`, `None` if unanswered), else DTR.
    pub fn detect(info: &DeviceInfo, board_pwm: Option<bool>) -> Self {
        if info.has_builtin_motor_control() {
            Self::Rpm(DEFAULT_RPM)
        } else if board_pwm == Some(true) {
            Self::Pwm(DEFAULT_PWM)
        } else {
            Self::Dtr
        }
    }

    /// Whether `Auto` must ask `GET_ACC_BOARD_FLAG` for this device.
    pub fn needs_board_query(control: MotorControl, info: &DeviceInfo) -> bool {
        control == MotorControl::Auto && !info.has_builtin_motor_control()
    }

    /// What runs the motor. With DTR: deassert (the SDK's `setDTR(false)`).
    pub fn start(self) -> DriverOutput {
        match self {
            Self::Dtr => DriverOutput::SetDtr(false),
            Self::Pwm(v) => DriverOutput::Write(request::motor(cmd::SET_MOTOR_PWM, v)),
            Self::Rpm(v) => DriverOutput::Write(request::motor(cmd::SET_MOTOR_RPM, v)),
        }
    }

    /// What stops it. With DTR: assert (`setDTR(true)` for speed 0).
    pub fn stop(self) -> DriverOutput {
        match self {
            Self::Dtr => DriverOutput::SetDtr(true),
            Self::Pwm(_) => DriverOutput::Write(request::motor(cmd::SET_MOTOR_PWM, 0)),
            Self::Rpm(_) => DriverOutput::Write(request::motor(cmd::SET_MOTOR_RPM, 0)),
        }
    }

    pub fn describe(self) -> String {
        match self {
            Self::Dtr => "dtr".to_string(),
            Self::Pwm(v) => format!("pwm {v}"),
            Self::Rpm(v) => format!("rpm {v}"),
        }
    }
}
