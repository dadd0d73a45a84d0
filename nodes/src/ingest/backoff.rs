//! Reconnection backoff: exponential waits between attempts, interruptible by
//! the stop flag.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Waits between reconnection attempts: `initial`, doubling up to `max`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BackoffConfig {
    pub initial: Duration,
    pub max: Duration,
}

impl Default for BackoffConfig {
    fn default() -> Self {
        Self {
            initial: Duration::from_millis(100),
            max: Duration::from_secs(2),
        }
    }
}

/// The current wait of a [`BackoffConfig`].
#[derive(Debug, Clone)]
pub struct Backoff {
    config: BackoffConfig,
    next: Duration,
}

impl Backoff {
    pub fn new(config: BackoffConfig) -> Self {
        Self {
            config,
            next: config.initial,
        }
    }

    /// After a success: the next failure waits `initial` again.
    pub fn reset(&mut self) {
        self.next = self.config.initial;
    }

    /// Sleeps the current wait (returning early once `stop` is set) and doubles it.
    /// Returns false if stopped.
    pub fn wait(&mut self, stop: &AtomicBool) -> bool {
        let wait = self.next;
        self.next = (self.next * 2)
            .min(self.config.max)
            .max(self.config.initial);
        sleep_unless_stopped(wait, stop)
    }
}

/// Sleeps `duration` in slices of at most 20 ms, returning false as soon as
/// `stop` is set.
pub fn sleep_unless_stopped(duration: Duration, stop: &AtomicBool) -> bool {
    let end = Instant::now() + duration;
    loop {
        if stop.load(Ordering::Relaxed) {
            return false;
        }
        let now = Instant::now();
        if now >= end {
            return true;
        }
        std::thread::sleep((end - now).min(Duration::from_millis(20)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ingest_backoff_doubles_to_its_max_and_stops_early() {
        let config = BackoffConfig {
            initial: Duration::from_millis(1),
            max: Duration::from_millis(4),
        };
        let mut b = Backoff::new(config);
        let never = AtomicBool::new(false);
        let waits: Vec<_> = (0..4)
            .map(|_| {
                let w = b.next;
                assert!(b.wait(&never));
                w.as_millis()
            })
            .collect();
        assert_eq!(waits, vec![1, 2, 4, 4]);
        b.reset();
        assert_eq!(b.next, config.initial);
        let stopped = AtomicBool::new(true);
        let start = Instant::now();
        assert!(!sleep_unless_stopped(Duration::from_secs(10), &stopped));
        assert!(start.elapsed() < Duration::from_secs(1));
    }
}
