//! The scale over time: how fast it may rise (hysteresis, so the arm does
//! not chatter), and the fastest scale the arm may still be obeying.

use std::collections::VecDeque;

/// Entries kept at most; past it the newest entry absorbs the next, which
/// only keeps a scale in force longer.
const MAX_ENTRIES: usize = 4096;

/// Published scales of one arm, on the guard's monotonic clock.
#[derive(Debug, Clone)]
pub struct ScaleGovernor {
    rise_per_second: f64,
    /// How long a published scale may still govern the arm's motion (ns).
    window_ns: u64,
    /// Decreasing scales with the time each was last published: the largest
    /// in the window is the front once older entries are dropped.
    in_window: VecDeque<(u64, f64)>,
    last: Option<(u64, f64)>,
    /// Whether the first query took full speed as in force.
    primed: bool,
}

impl ScaleGovernor {
    /// `window` (seconds): how long after its publication a verdict's scale
    /// can still drive the arm ([`super::SpeedMonitor::window`]); a window
    /// that is not a number keeps every scale for ever.
    pub fn new(rise_per_second: f64, window: f64) -> Self {
        Self {
            rise_per_second,
            window_ns: if window.is_nan() {
                u64::MAX
            } else {
                (window.max(0.0) * 1e9).ceil() as u64
            },
            in_window: VecDeque::new(),
            last: None,
            primed: false,
        }
    }

    /// The largest scale published within the window before `now_ns` (0 when
    /// none: the arm moves only on a fresh `clear`). The first query takes
    /// full speed as published then: a guard that has just started (or
    /// restarted) cannot know what an earlier one allowed.
    pub fn in_force(&mut self, now_ns: u64) -> f64 {
        if !self.primed {
            self.primed = true;
            self.in_window.push_back((now_ns, 1.0));
        }
        let since = now_ns.saturating_sub(self.window_ns);
        while self.in_window.front().is_some_and(|&(t, _)| t < since) {
            self.in_window.pop_front();
        }
        self.in_window.front().map_or(0.0, |&(_, s)| s)
    }

    /// The scale to publish for a `target` at `now_ns`: the target, or less
    /// while rising faster than allowed since the last publication. Records
    /// it as published.
    pub fn publish(&mut self, target: f64, now_ns: u64) -> f64 {
        let scale = match self.last {
            Some((t, last)) if target > last => {
                let dt = now_ns.saturating_sub(t) as f64 * 1e-9;
                target.min(last + self.rise_per_second * dt)
            }
            _ => target,
        };
        self.last = Some((now_ns, scale));
        while self.in_window.back().is_some_and(|&(_, s)| s <= scale) {
            self.in_window.pop_back();
        }
        let full = self.in_window.len() >= MAX_ENTRIES;
        match self.in_window.back_mut() {
            Some(back) if full => back.0 = now_ns,
            _ => self.in_window.push_back((now_ns, scale)),
        }
        scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: u64 = 1_000_000;

    #[test]
    fn rises_at_the_rate_and_falls_at_once() {
        let mut g = ScaleGovernor::new(1.0, 0.5);
        assert_eq!(g.publish(0.8, 0), 0.8);
        assert_eq!(g.publish(0.2, 10 * MS), 0.2);
        let up = g.publish(1.0, 110 * MS);
        assert!((up - 0.3).abs() < 1e-12, "{up}");
        assert_eq!(g.publish(0.0, 120 * MS), 0.0);
    }

    #[test]
    fn the_largest_scale_stays_in_force_for_the_window() {
        let mut g = ScaleGovernor::new(10.0, 0.5);
        // Just started: an earlier guard may have allowed full speed.
        assert_eq!(g.in_force(0), 1.0);
        assert_eq!(g.in_force(501 * MS), 0.0);
        g.publish(0.9, 600 * MS);
        g.publish(0.1, 700 * MS);
        assert_eq!(g.in_force(1000 * MS), 0.9);
        assert_eq!(g.in_force(1100 * MS), 0.9);
        assert_eq!(g.in_force(1101 * MS), 0.1);
        assert_eq!(g.in_force(1201 * MS), 0.0);
    }

    #[test]
    fn a_flood_of_decisions_keeps_memory_bounded_and_the_maximum() {
        let mut g = ScaleGovernor::new(1e9, 10.0);
        g.primed = true;
        for k in 0..3 * MAX_ENTRIES as u64 {
            g.publish(1.0 - k as f64 * 1e-5, k);
        }
        assert!(g.in_window.len() <= MAX_ENTRIES);
        assert_eq!(g.in_force(3 * MAX_ENTRIES as u64), 1.0);
    }
}
