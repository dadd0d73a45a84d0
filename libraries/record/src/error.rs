//! Why a recording or replay option cannot be used.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum RecordError {
    #[error("--topics: {pattern:?}: {reason}")]
    Filter { pattern: String, reason: String },
    #[error("{option}: {reason}")]
    Option {
        option: &'static str,
        reason: String,
    },
    #[error("channel {topic:?}: {reason}")]
    Channel { topic: String, reason: String },
}
