//! Why a dashboard frame or a browser command was refused.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum DashboardError {
    #[error(
        "frame is truncated: {what} needs {needed} bytes at offset {offset}, the frame has {len}"
    )]
    Truncated {
        what: String,
        needed: usize,
        offset: usize,
        len: usize,
    },
    #[error("frame header is not a JSON object with a type and arrays: {0}")]
    Header(String),
    #[error("frame has {0} bytes after its last array")]
    TrailingBytes(usize),
    #[error("browser command is {len} bytes, more than {max}")]
    CommandTooLong { len: usize, max: usize },
    #[error("browser command is not valid JSON of a known shape: {0}")]
    Command(String),
    #[error("browser command field {field}: {reason}")]
    CommandField { field: &'static str, reason: String },
}
