//! Why a sensor frame, line or scan was rejected: one named error per failure, each
//! with an [`ErrorKind`] so decoders can count them.

use thiserror::Error;

/// Every way ingest can reject input. Decoders return these *and* count them by
/// [`IngestError::kind`] in their [`DecoderStats`](super::DecoderStats); none is
/// fatal to a stream.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum IngestError {
    #[error("skipped {bytes} bytes of garbage before a sync word")]
    Garbage { bytes: usize },
    #[error("frame header checksum mismatch (read {found:#06x}, computed {computed:#06x})")]
    BadHeaderCrc { found: u16, computed: u16 },
    #[error("frame checksum mismatch (read {found:#010x}, computed {computed:#010x})")]
    BadCrc { found: u32, computed: u32 },
    #[error("frame truncated: {got} of {expected} bytes before the next frame started")]
    Truncated { got: usize, expected: usize },
    #[error("protocol version {found}, this build reads version {expected}")]
    Version { found: u8, expected: u8 },
    #[error("{what} of {found} exceeds the limit of {limit}")]
    Oversize {
        what: &'static str,
        found: usize,
        limit: usize,
    },
    #[error("{field} holds a non-finite value at point {index}")]
    NonFinite { field: &'static str, index: usize },
    #[error("point {index}: {field} = {value} does not fit the wire encoding")]
    OutOfRange {
        field: &'static str,
        index: usize,
        value: f32,
    },
    #[error("malformed {what}: {reason}")]
    Malformed { what: &'static str, reason: String },
    #[error("scan {sequence}: expected frame {expected}, got frame {found} (frames missing)")]
    MissingFrame {
        sequence: u32,
        expected: u32,
        found: u32,
    },
    #[error("scan {sequence}: frame {found} arrived after frame {expected} was due (out of order or repeated)")]
    OutOfOrder {
        sequence: u32,
        expected: u32,
        found: u32,
    },
    #[error(
        "scan {sequence} dropped incomplete: {received} of {expected} frames/points, {reason}"
    )]
    IncompleteScan {
        sequence: u32,
        received: u32,
        expected: u32,
        reason: &'static str,
    },
    #[error("scan {sequence}: checksum mismatch (read {found:#010x}, computed {computed:#010x})")]
    BadChecksum {
        sequence: u32,
        found: u32,
        computed: u32,
    },
    #[error("unknown CAN id {id:#x}{}", if *.extended { " (extended)" } else { "" })]
    UnknownId { id: u32, extended: bool },
    #[error("bad SLCAN line {line:?}: {reason}")]
    BadSlcan { line: String, reason: &'static str },
    #[error("the SLCAN adapter refused a command (BEL)")]
    SlcanNak,
    #[error("bad candump line {line}: {reason}")]
    BadCandump { line: usize, reason: String },
}

/// The kind of an [`IngestError`], the key its counters are kept under.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ErrorKind {
    Garbage,
    BadHeaderCrc,
    BadCrc,
    Truncated,
    Version,
    Oversize,
    NonFinite,
    OutOfRange,
    Malformed,
    MissingFrame,
    OutOfOrder,
    IncompleteScan,
    BadChecksum,
    UnknownId,
    BadSlcan,
    SlcanNak,
    BadCandump,
}

impl ErrorKind {
    /// Every kind, in declaration order (the index of a kind in its counters).
    pub const ALL: [ErrorKind; 17] = [
        Self::Garbage,
        Self::BadHeaderCrc,
        Self::BadCrc,
        Self::Truncated,
        Self::Version,
        Self::Oversize,
        Self::NonFinite,
        Self::OutOfRange,
        Self::Malformed,
        Self::MissingFrame,
        Self::OutOfOrder,
        Self::IncompleteScan,
        Self::BadChecksum,
        Self::UnknownId,
        Self::BadSlcan,
        Self::SlcanNak,
        Self::BadCandump,
    ];

    /// A short snake_case name for logs and diagnostics.
    pub fn name(self) -> &'static str {
        match self {
            Self::Garbage => "garbage",
            Self::BadHeaderCrc => "bad_header_crc",
            Self::BadCrc => "bad_crc",
            Self::Truncated => "truncated",
            Self::Version => "version",
            Self::Oversize => "oversize",
            Self::NonFinite => "non_finite",
            Self::OutOfRange => "out_of_range",
            Self::Malformed => "malformed",
            Self::MissingFrame => "missing_frame",
            Self::OutOfOrder => "out_of_order",
            Self::IncompleteScan => "incomplete_scan",
            Self::BadChecksum => "bad_checksum",
            Self::UnknownId => "unknown_id",
            Self::BadSlcan => "bad_slcan",
            Self::SlcanNak => "slcan_nak",
            Self::BadCandump => "bad_candump",
        }
    }

    pub(crate) fn index(self) -> usize {
        self as usize
    }
}

impl IngestError {
    pub fn kind(&self) -> ErrorKind {
        match self {
            Self::Garbage { .. } => ErrorKind::Garbage,
            Self::BadHeaderCrc { .. } => ErrorKind::BadHeaderCrc,
            Self::BadCrc { .. } => ErrorKind::BadCrc,
            Self::Truncated { .. } => ErrorKind::Truncated,
            Self::Version { .. } => ErrorKind::Version,
            Self::Oversize { .. } => ErrorKind::Oversize,
            Self::NonFinite { .. } => ErrorKind::NonFinite,
            Self::OutOfRange { .. } => ErrorKind::OutOfRange,
            Self::Malformed { .. } => ErrorKind::Malformed,
            Self::MissingFrame { .. } => ErrorKind::MissingFrame,
            Self::OutOfOrder { .. } => ErrorKind::OutOfOrder,
            Self::IncompleteScan { .. } => ErrorKind::IncompleteScan,
            Self::BadChecksum { .. } => ErrorKind::BadChecksum,
            Self::UnknownId { .. } => ErrorKind::UnknownId,
            Self::BadSlcan { .. } => ErrorKind::BadSlcan,
            Self::SlcanNak => ErrorKind::SlcanNak,
            Self::BadCandump { .. } => ErrorKind::BadCandump,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_index_their_own_slot() {
        for (i, kind) in ErrorKind::ALL.iter().enumerate() {
            assert_eq!(kind.index(), i);
        }
        let names: std::collections::BTreeSet<_> =
            ErrorKind::ALL.iter().map(|k| k.name()).collect();
        assert_eq!(names.len(), ErrorKind::ALL.len());
    }
}
