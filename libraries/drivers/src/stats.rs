//! Counters a decoder keeps: what it accepted and, per [`ErrorKind`], what it
//! rejected. Cheap to copy, so a reader can snapshot and publish them.

use super::error::{ErrorKind, IngestError};
use std::fmt;

/// Counts of one decoder (or the sum of several, see [`DecoderStats::merge`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DecoderStats {
    /// Input bytes (serial, SLCAN) or frames (CAN) offered to the decoder.
    pub input: u64,
    /// Frames (serial frames, CAN frames, SLCAN/candump lines) accepted.
    pub frames: u64,
    /// Complete scans returned.
    pub scans: u64,
    /// Points in those scans.
    pub points: u64,
    /// Bytes thrown away while resynchronising (serial and SLCAN).
    pub skipped_bytes: u64,
    /// Valid frames thrown away because their scan was already lost.
    pub discarded_frames: u64,
    errors: [u64; ErrorKind::ALL.len()],
}

impl DecoderStats {
    /// How many errors of `kind` were counted.
    pub fn errors(&self, kind: ErrorKind) -> u64 {
        self.errors[kind.index()]
    }

    /// All errors of every kind.
    pub fn total_errors(&self) -> u64 {
        self.errors.iter().sum()
    }

    /// The non-zero error counters, in [`ErrorKind::ALL`] order.
    pub fn error_counts(&self) -> impl Iterator<Item = (ErrorKind, u64)> + '_ {
        ErrorKind::ALL
            .iter()
            .map(|&k| (k, self.errors(k)))
            .filter(|&(_, n)| n > 0)
    }

    /// Counts `error` under its kind and hands it back (for `push(Err(stats.count(e)))`).
    pub fn count(&mut self, error: IngestError) -> IngestError {
        self.errors[error.kind().index()] += 1;
        error
    }

    /// Adds another decoder's counts to these.
    pub fn merge(&mut self, other: &DecoderStats) {
        self.input += other.input;
        self.frames += other.frames;
        self.scans += other.scans;
        self.points += other.points;
        self.skipped_bytes += other.skipped_bytes;
        self.discarded_frames += other.discarded_frames;
        for (a, b) in self.errors.iter_mut().zip(other.errors) {
            *a += b;
        }
    }
}

impl fmt::Display for DecoderStats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} scans ({} points) from {} frames; skipped {} bytes, discarded {} frames",
            self.scans, self.points, self.frames, self.skipped_bytes, self.discarded_frames
        )?;
        if self.total_errors() == 0 {
            return write!(f, "; no errors");
        }
        write!(f, "; errors:")?;
        for (kind, n) in self.error_counts() {
            write!(f, " {}={}", kind.name(), n)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_by_kind_and_merges() {
        let mut a = DecoderStats::default();
        let e = a.count(IngestError::SlcanNak);
        assert_eq!(e, IngestError::SlcanNak);
        a.count(IngestError::Garbage { bytes: 3 });
        a.count(IngestError::Garbage { bytes: 1 });
        assert_eq!(a.errors(ErrorKind::Garbage), 2);
        assert_eq!(a.total_errors(), 3);
        let mut b = DecoderStats::default();
        b.merge(&a);
        b.merge(&a);
        assert_eq!(b.errors(ErrorKind::SlcanNak), 2);
        assert!(b.to_string().contains("garbage=4"), "{b}");
        assert!(DecoderStats::default().to_string().ends_with("no errors"));
    }
}
