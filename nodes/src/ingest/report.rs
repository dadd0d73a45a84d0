//! Logging of decode errors without flooding: each error at `debug`, and a
//! `warn` summary of the counters at most once per interval while errors grow.

use super::ReaderStats;
use shroud_drivers::{DecoderStats, ErrorKind, IngestError, Scan};
use std::time::{Duration, Instant};

#[derive(Debug)]
pub(crate) struct ErrorReporter {
    name: String,
    interval: Duration,
    last: Option<Instant>,
    reported_errors: u64,
}

impl ErrorReporter {
    pub fn new(name: &str) -> Self {
        Self {
            name: name.to_owned(),
            interval: Duration::from_secs(5),
            last: None,
            reported_errors: 0,
        }
    }

    /// Logs one decode error. Frames of other devices on a shared bus are
    /// expected: only at `trace`.
    pub fn error(&mut self, error: &IngestError) {
        if error.kind() == ErrorKind::UnknownId {
            tracing::trace!(source = %self.name, "{error}");
        } else {
            tracing::debug!(source = %self.name, kind = error.kind().name(), "ingest error: {error}");
        }
    }

    /// Hands a decoder's complete scans to `on_scan` and logs its errors, with
    /// the decoder's counters copied into `stats` first (every reader's loop).
    pub fn deliver(
        &mut self,
        results: Vec<Result<Scan, IngestError>>,
        decoder: &DecoderStats,
        stats: &mut ReaderStats,
        on_scan: &mut dyn FnMut(Scan, &ReaderStats),
    ) {
        stats.decoder = *decoder;
        for result in results {
            match result {
                Ok(scan) => {
                    stats.scans += 1;
                    on_scan(scan, stats);
                }
                Err(error) => self.error(&error),
            }
        }
        self.summarise(&stats.decoder);
    }

    /// Warns with the counters if errors grew and the interval has passed.
    pub fn summarise(&mut self, stats: &DecoderStats) {
        let total = stats.total_errors();
        if total == self.reported_errors {
            return;
        }
        if self.last.is_some_and(|t| t.elapsed() < self.interval) {
            return;
        }
        self.last = Some(Instant::now());
        self.reported_errors = total;
        tracing::warn!(source = %self.name, "ingest errors: {stats}");
    }
}
