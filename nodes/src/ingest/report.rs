//! Logging of decode errors without flooding: each error at `debug`, and a
//! `warn` summary of the counters at most once per interval while errors grow.

use shroud_core::ingest::{DecoderStats, IngestError};
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

    /// Logs one decode error.
    pub fn error(&mut self, error: &IngestError) {
        tracing::debug!(source = %self.name, kind = error.kind().name(), "ingest error: {error}");
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
