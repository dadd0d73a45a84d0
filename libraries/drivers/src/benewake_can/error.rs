//! Why a Benewake CAN driver cannot start.

use thiserror::Error;

#[derive(Debug, Clone, PartialEq, Error)]
pub enum BenewakeCanError {
    #[error("{found} Benewake CAN rangefinders configured, 1 to {limit} are supported")]
    SensorCount { found: usize, limit: usize },
    #[error("rangefinder {sensor}: id {id:#x} exceeds {max:#x}")]
    BadId { sensor: String, id: u32, max: u32 },
    #[error("rangefinders {first} and {second} share id {id:#x} (extended: {extended})")]
    DuplicateId {
        first: String,
        second: String,
        id: u32,
        extended: bool,
    },
    #[error("Benewake CAN setting {name}: {reason}")]
    BadSetting { name: &'static str, reason: String },
    #[error("no builtin DBC {0}")]
    MissingDatabase(&'static str),
    #[error("the DBC {database} has no message {message}")]
    MissingMessage {
        database: &'static str,
        message: &'static str,
    },
    #[error("the DBC message {message} has no signal {signal}")]
    MissingSignal {
        message: &'static str,
        signal: &'static str,
    },
}
