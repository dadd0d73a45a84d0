//! When `shroud replay` publishes each message: at its log time's offset from
//! the pass's first message, divided by `--speed`, or at once (`--max`); with
//! `--loop`, pass after pass, each starting one mean message interval (of the
//! pass before) after that pass's last message, so that the last and first
//! messages are not published together (a one-message recording: a second
//! apart). The schedule learns the recording as it is read, so that a replay
//! streams its file once per pass and needs no index (a truncated file has
//! none).

use super::error::RecordError;

/// How fast a replay runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pace {
    /// Real time multiplied by this factor.
    Speed(f64),
    /// As fast as the subscribers take it.
    Max,
}

/// `--speed` bounds: a thousandth to a thousand times real time.
const SPEED: std::ops::RangeInclusive<f64> = 1e-3..=1e3;

/// The gap between passes of a recording of one message (it has no mean
/// interval): a second of log time.
const ONE_MESSAGE_GAP_NS: u64 = 1_000_000_000;

impl Pace {
    pub fn speed(factor: f64) -> Result<Self, RecordError> {
        if !factor.is_finite() || !SPEED.contains(&factor) {
            return Err(RecordError::Option {
                option: "--speed",
                reason: format!("{factor} is not between 0.001 and 1000 (or use --max)"),
            });
        }
        Ok(Self::Speed(factor))
    }
}

/// Due times of a replay's messages, in ns after the replay started.
#[derive(Debug, Clone, PartialEq)]
pub struct ReplaySchedule {
    pace: Pace,
    /// When the current pass started, in replay time (ns).
    pass_start_ns: u64,
    /// Log times of the current pass's first and last messages, and its count.
    first_log_ns: Option<u64>,
    last_log_ns: u64,
    count: u64,
}

impl ReplaySchedule {
    pub fn new(pace: Pace) -> Self {
        Self {
            pace,
            pass_start_ns: 0,
            first_log_ns: None,
            last_log_ns: 0,
            count: 0,
        }
    }

    /// When the next message of the pass, logged at `log_ns`, is due.
    /// Messages logged before the pass's first (a clock step back) are due at
    /// the pass's start.
    pub fn due_ns(&mut self, log_ns: u64) -> u64 {
        let first = *self.first_log_ns.get_or_insert(log_ns);
        self.last_log_ns = self.last_log_ns.max(log_ns);
        self.count += 1;
        match self.pace {
            Pace::Max => 0,
            Pace::Speed(s) => self
                .pass_start_ns
                .saturating_add(scale(log_ns.saturating_sub(first), s)),
        }
    }

    /// Starts the next pass (after `--loop` reached the end of the file).
    pub fn next_pass(&mut self) {
        if let (Pace::Speed(s), Some(first)) = (self.pace, self.first_log_ns) {
            let span = self.last_log_ns.saturating_sub(first);
            let gap = span
                .checked_div(self.count.saturating_sub(1))
                .unwrap_or(ONE_MESSAGE_GAP_NS);
            self.pass_start_ns = self
                .pass_start_ns
                .saturating_add(scale(span.saturating_add(gap), s));
        }
        self.first_log_ns = None;
        self.last_log_ns = 0;
        self.count = 0;
    }
}

/// `ns` of log time in replay time at `speed`.
fn scale(ns: u64, speed: f64) -> u64 {
    (ns as f64 / speed) as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pass(s: &mut ReplaySchedule, logs: &[u64]) -> Vec<u64> {
        logs.iter().map(|&l| s.due_ns(l)).collect()
    }

    #[test]
    fn real_time_keeps_offsets_and_loops_one_interval_later() {
        let mut s = ReplaySchedule::new(Pace::speed(1.0).unwrap());
        let logs = [1_000, 2_000, 3_000, 5_000, 5_000];
        assert_eq!(pass(&mut s, &logs), vec![0, 1_000, 2_000, 4_000, 4_000]);
        s.next_pass();
        // span 4000 + mean interval 1000.
        assert_eq!(pass(&mut s, &logs)[..2], [5_000, 6_000]);
    }

    #[test]
    fn speed_divides_times_and_max_is_always_due() {
        let mut fast = ReplaySchedule::new(Pace::speed(4.0).unwrap());
        assert_eq!(
            pass(&mut fast, &[1_000, 5_000, 9_000]),
            vec![0, 1_000, 2_000]
        );
        fast.next_pass();
        assert_eq!(fast.due_ns(1_000), 3_000);
        let mut max = ReplaySchedule::new(Pace::Max);
        assert_eq!(pass(&mut max, &[1, 9_000]), vec![0, 0]);
        max.next_pass();
        assert_eq!(max.due_ns(9_000), 0);
    }

    #[test]
    fn clock_steps_back_are_clamped_and_one_message_loops_each_second() {
        let mut s = ReplaySchedule::new(Pace::Speed(1.0));
        assert_eq!(pass(&mut s, &[1_000, 10, 2_000]), vec![0, 0, 1_000]);
        let mut one = ReplaySchedule::new(Pace::Speed(1.0));
        assert_eq!(one.due_ns(7), 0);
        one.next_pass();
        assert_eq!(one.due_ns(7), ONE_MESSAGE_GAP_NS);
    }

    #[test]
    fn absurd_speeds_are_refused() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-9, 1e6] {
            assert!(Pace::speed(bad).is_err(), "{bad}");
        }
    }
}
