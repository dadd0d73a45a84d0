//! Why a reader or source stopped or could not start. (Display and Error are
//! written out: shroud-nodes does not depend on thiserror.)

use std::{fmt, io};

/// What a [`CanSource`](super::CanSource) reports besides frames.
#[derive(Debug)]
pub enum SourceError {
    /// The device went away (unplugged, interface down, port closed). The reader
    /// counts it and reopens the source with backoff.
    Disconnected {
        source_name: String,
        error: io::Error,
    },
    /// The source could not be opened; the reader retries with backoff.
    Open {
        source_name: String,
        error: io::Error,
    },
    /// The source has no more frames, ever (end of a log, bus senders gone).
    Finished(String),
    /// Retrying cannot help (e.g. a log file that does not exist).
    Fatal(String),
}

impl fmt::Display for SourceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Disconnected { source_name, error } => {
                write!(f, "{source_name} disconnected: {error}")
            }
            Self::Open { source_name, error } => write!(f, "cannot open {source_name}: {error}"),
            Self::Finished(name) => write!(f, "{name} has ended"),
            Self::Fatal(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for SourceError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Disconnected { error, .. } | Self::Open { error, .. } => Some(error),
            _ => None,
        }
    }
}

/// Why a reader returned an error instead of its statistics.
#[derive(Debug)]
pub enum ReaderError {
    /// A setting is unusable (zero baud rate, empty path, ...).
    Config(String),
    /// The source failed in a way retrying cannot fix.
    Source(SourceError),
}

impl fmt::Display for ReaderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Config(message) => write!(f, "invalid reader configuration: {message}"),
            Self::Source(error) => error.fmt(f),
        }
    }
}

impl std::error::Error for ReaderError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Config(_) => None,
            Self::Source(error) => Some(error),
        }
    }
}

impl From<SourceError> for ReaderError {
    fn from(error: SourceError) -> Self {
        Self::Source(error)
    }
}
