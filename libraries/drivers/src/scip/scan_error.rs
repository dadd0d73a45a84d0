//! Why a scan's data was rejected ([`ScanDataError`]), by the scan data
//! decoder or the multi-echo splitter it calls; a module of its own so that
//! both build on it.

use thiserror::Error;

/// Why a scan's data was rejected; the whole scan is dropped.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ScanDataError {
    #[error("a data line has a wrong sum")]
    BadChecksum,
    #[error("the timestamp line is not 4 characters and a sum")]
    BadTimestamp,
    #[error("a data line is longer than 64 characters")]
    LongLine,
    #[error("a character is outside the SCIP encoding")]
    BadCharacter,
    #[error("{got} characters of data, expected {expected}")]
    WrongLength { expected: usize, got: usize },
    #[error("multi-echo data holds {got} steps, expected {expected}")]
    MissingSteps { expected: usize, got: usize },
    #[error("multi-echo data goes on after the {expected} steps requested")]
    ExtraData { expected: usize },
    #[error("a multi-echo marker '&' comes before the scan's first value")]
    EchoBeforeFirstValue,
    #[error("a step has more than 3 echoes")]
    TooManyEchoes,
    #[error("a multi-echo marker '&' is not followed by a whole value")]
    DanglingEchoMark,
}

impl ScanDataError {
    /// The error-counter name: a short scan is `incomplete_scan`, a wrong sum
    /// `bad_checksum`, a misplaced `&` or a fourth echo `malformed_multiecho`,
    /// anything else `malformed_reply`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::BadChecksum => "bad_checksum",
            Self::WrongLength { expected, got } if got < expected => "incomplete_scan",
            Self::MissingSteps { .. } => "incomplete_scan",
            Self::EchoBeforeFirstValue | Self::TooManyEchoes | Self::DanglingEchoMark => {
                "malformed_multiecho"
            }
            _ => "malformed_reply",
        }
    }
}
