//! Why a message could not be encoded or decoded.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum MessageError {
    #[error("not a valid shroud message: {0}")]
    Malformed(String),
    /// A message of another schema version than this build reads; `message`
    /// names its kind (`"joint state"`, `"collision"`, ...).
    #[error("{message} message version {found}, this build reads version {expected}")]
    Version {
        message: &'static str,
        found: u16,
        expected: u16,
    },
    #[error("the {field} blob has {len} bytes, not a multiple of {unit}")]
    BlobLength {
        field: &'static str,
        len: usize,
        unit: usize,
    },
    #[error("the {field} blob holds {found} values, expected {expected}")]
    Count {
        field: &'static str,
        found: usize,
        expected: usize,
    },
    #[error("{field} holds a non-finite value at index {index}")]
    NonFinite { field: &'static str, index: usize },
    #[error("position_error_m is {value}: a bound on a distance must be finite and >= 0")]
    PositionError { value: f64 },
    #[error("invalid {field}: {reason}")]
    Invalid { field: &'static str, reason: String },
}
