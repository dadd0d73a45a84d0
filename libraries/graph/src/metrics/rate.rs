//! Message rate over a sliding time window.

use std::collections::VecDeque;

/// Counts events in the last `window_ns` nanoseconds.
#[derive(Debug, Clone)]
pub struct RateMeter {
    window_ns: u64,
    stamps: VecDeque<u64>,
}

impl RateMeter {
    pub fn new(window_ns: u64) -> Self {
        Self {
            window_ns: window_ns.max(1),
            stamps: VecDeque::new(),
        }
    }

    /// Records an event at `now_ns` (monotonic nanoseconds).
    pub fn tick(&mut self, now_ns: u64) {
        self.stamps.push_back(now_ns);
        self.expire(now_ns);
    }

    /// Events per second: over the span between the oldest and newest event in the
    /// window, so that a fresh meter is not biased low by the empty part of it.
    pub fn rate_hz(&mut self, now_ns: u64) -> f64 {
        self.expire(now_ns);
        match (self.stamps.front(), self.stamps.back()) {
            (Some(&first), Some(&last)) if self.stamps.len() >= 2 && last > first => {
                (self.stamps.len() - 1) as f64 * 1e9 / (last - first) as f64
            }
            _ => 0.0,
        }
    }

    fn expire(&mut self, now_ns: u64) {
        while let Some(&front) = self.stamps.front() {
            if now_ns.saturating_sub(front) > self.window_ns {
                self.stamps.pop_front();
            } else {
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steady_ten_hertz_reads_ten() {
        let mut m = RateMeter::new(2_000_000_000);
        for i in 0..50u64 {
            m.tick(i * 100_000_000);
        }
        let r = m.rate_hz(49 * 100_000_000);
        assert!((r - 10.0).abs() < 1e-9, "{r}");
        assert_eq!(m.rate_hz(100 * 1_000_000_000), 0.0);
    }
}
