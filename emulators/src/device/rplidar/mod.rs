//! Emulated Slamtec RPLIDAR A1 and A2 lidars on a serial line: the request
//! protocol (STOP, RESET, SCAN, FORCE_SCAN, EXPRESS_SCAN, GET_INFO,
//! GET_HEALTH, GET_SAMPLERATE, GET_LIDAR_CONF, GET_ACC_BOARD_FLAG,
//! SET_MOTOR_PWM), standard nodes, legacy and dense express capsules, the
//! motor and its DTR/PWM control.
//!
//! Written from Slamtec's protocol PDF and the `rplidar_sdk` sources (cited
//! per file), independently of the host driver.

mod capsule;
mod emulator;
mod faults;
mod measure;
mod model;
mod motor;
mod node;
mod options;
mod protocol;
mod rejects;
mod reply;
mod request;
mod stream;
mod tx;

#[cfg(test)]
mod tests;

pub use emulator::RplidarEmulator;
pub use model::RplidarModel;
pub use options::{RplidarHealth, RplidarOptions};
pub use rejects::{RejectCounts, RejectKind};
