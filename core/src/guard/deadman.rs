//! The deadman of a verdict consumer (a robot driver, the simulated arm): it may
//! move only while a `clear` verdict for one of its own recent joint states is
//! younger than a deadline, so a guard that crashes, restarts, drops a message
//! or is cut off by a partition halts the robot instead of leaving it on its
//! last "clear".
//!
//! Time is an argument (nanoseconds on the consumer's own monotonic clock), so
//! the deadline covers the whole round trip: joint state out, check, verdict
//! back. A `stop` halts at once, whatever joint state it answers; a `clear`
//! counts only for a joint state sent after the last stop's.

use crate::message::GuardVerdict;
use std::collections::VecDeque;

/// Joint states remembered: more than any deadline spans at 1 kHz / 3 periods.
const REMEMBERED: usize = 256;

/// What the consumer may do now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    Move,
    /// Halted, with the verdict that halted it: the guard's (`stop`, `stale`,
    /// ...) or [`GuardVerdict::NoVerdict`] when no fresh clear has arrived.
    Halt(GuardVerdict),
}

/// How a verdict was taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VerdictUse {
    /// It answers one of the recent joint states and was applied.
    Applied,
    /// A `clear` for a joint state this deadman does not remember (too old, or
    /// another consumer's): ignored.
    Unknown,
    /// A `clear` older than a stop already received: ignored.
    Superseded,
}

/// See the module documentation.
#[derive(Debug, Clone)]
pub struct Deadman {
    deadline_ns: u64,
    /// (sequence, sent at), oldest first.
    sent: VecDeque<(u64, u64)>,
    /// The newest clear applied: its joint state's sequence and send time.
    clear: Option<(u64, u64)>,
    /// The newest stop: the sequence it answers (or the newest one sent when
    /// it answers none we know) and its verdict.
    stop: Option<(u64, GuardVerdict)>,
}

impl Deadman {
    /// A deadman that allows motion for `deadline_ns` after sending a joint
    /// state that was then cleared. The usual deadline is three joint periods.
    pub fn new(deadline_ns: u64) -> Self {
        Self {
            deadline_ns,
            sent: VecDeque::with_capacity(REMEMBERED),
            clear: None,
            stop: None,
        }
    }

    pub fn deadline_ns(&self) -> u64 {
        self.deadline_ns
    }

    /// The consumer published joint state `sequence` at `now_ns`. Sequences
    /// must increase.
    pub fn sent(&mut self, sequence: u64, now_ns: u64) {
        if self.sent.len() == REMEMBERED {
            self.sent.pop_front();
        }
        self.sent.push_back((sequence, now_ns));
    }

    /// A verdict arrived for joint state `sequence`.
    pub fn verdict(&mut self, sequence: u64, verdict: GuardVerdict) -> VerdictUse {
        let known = self.sent.iter().find(|(s, _)| *s == sequence).copied();
        if verdict != GuardVerdict::Clear {
            // A stop is never ignored: one we cannot place answers, at worst,
            // the newest joint state, so that only later ones can clear it.
            let newest = self.sent.back().map_or(0, |(s, _)| *s);
            let at = known.map_or(newest, |(s, _)| s);
            if self.stop.is_none_or(|(s, _)| at >= s) {
                self.stop = Some((at, verdict));
            }
            return VerdictUse::Applied;
        }
        let Some((seq, sent_at)) = known else {
            return VerdictUse::Unknown;
        };
        if self.stop.is_some_and(|(s, _)| seq <= s) {
            return VerdictUse::Superseded;
        }
        if self.clear.is_none_or(|(s, _)| seq > s) {
            self.clear = Some((seq, sent_at));
        }
        VerdictUse::Applied
    }

    /// What the consumer may do at `now_ns`.
    pub fn motion(&self, now_ns: u64) -> Motion {
        match (self.clear, self.stop) {
            (_, Some((stop_seq, v))) if self.clear.is_none_or(|(s, _)| s <= stop_seq) => {
                Motion::Halt(v)
            }
            (Some((_, sent_at)), _) if now_ns.saturating_sub(sent_at) <= self.deadline_ns => {
                Motion::Move
            }
            _ => Motion::Halt(GuardVerdict::NoVerdict),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: u64 = 1_000_000;

    /// A consumer at 50 Hz (20 ms) with a 60 ms deadline.
    fn deadman() -> Deadman {
        Deadman::new(60 * MS)
    }

    #[test]
    fn halted_until_the_first_clear() {
        let mut d = deadman();
        assert_eq!(d.motion(0), Motion::Halt(GuardVerdict::NoVerdict));
        d.sent(0, 0);
        assert_eq!(d.motion(5 * MS), Motion::Halt(GuardVerdict::NoVerdict));
        assert_eq!(d.verdict(0, GuardVerdict::Clear), VerdictUse::Applied);
        assert_eq!(d.motion(5 * MS), Motion::Move);
    }

    #[test]
    fn silence_halts_after_the_deadline_of_the_last_cleared_joint_state() {
        let mut d = deadman();
        d.sent(0, 0);
        d.verdict(0, GuardVerdict::Clear);
        d.sent(1, 20 * MS);
        d.sent(2, 40 * MS);
        // No answer to 1 or 2: the clear of 0 (sent at 0) lasts 60 ms.
        assert_eq!(d.motion(60 * MS), Motion::Move);
        assert_eq!(d.motion(60 * MS + 1), Motion::Halt(GuardVerdict::NoVerdict));
        // A late clear for 2 buys time from 2's send time, not from its arrival.
        d.verdict(2, GuardVerdict::Clear);
        assert_eq!(d.motion(100 * MS), Motion::Move);
        assert_eq!(
            d.motion(100 * MS + 1),
            Motion::Halt(GuardVerdict::NoVerdict)
        );
    }

    #[test]
    fn a_stop_halts_at_once_and_only_a_later_clear_releases_it() {
        let mut d = deadman();
        for s in 0..4 {
            d.sent(s, s * 20 * MS);
        }
        d.verdict(1, GuardVerdict::Clear);
        d.verdict(2, GuardVerdict::Stop);
        assert_eq!(d.motion(61 * MS), Motion::Halt(GuardVerdict::Stop));
        // A clear for an earlier joint state, arriving late, changes nothing.
        d.verdict(1, GuardVerdict::Clear);
        assert_eq!(d.verdict(2, GuardVerdict::Clear), VerdictUse::Superseded);
        assert_eq!(d.motion(61 * MS), Motion::Halt(GuardVerdict::Stop));
        d.verdict(3, GuardVerdict::Clear);
        assert_eq!(d.motion(61 * MS), Motion::Move);
    }

    #[test]
    fn a_stop_for_an_unknown_joint_state_holds_until_a_newer_clear() {
        let mut d = deadman();
        d.sent(7, 0);
        d.verdict(7, GuardVerdict::Clear);
        // The guard could not decode a joint state: it answers sequence 0.
        assert_eq!(d.verdict(0, GuardVerdict::Stop), VerdictUse::Applied);
        assert_eq!(d.motion(MS), Motion::Halt(GuardVerdict::Stop));
        d.sent(8, 20 * MS);
        d.verdict(8, GuardVerdict::Clear);
        assert_eq!(d.motion(21 * MS), Motion::Move);
    }

    #[test]
    fn clears_of_strangers_and_forgotten_states_are_ignored() {
        let mut d = deadman();
        assert_eq!(d.verdict(3, GuardVerdict::Clear), VerdictUse::Unknown);
        for s in 0..(REMEMBERED as u64 + 10) {
            d.sent(s, s * MS);
        }
        assert_eq!(d.verdict(0, GuardVerdict::Clear), VerdictUse::Unknown);
        assert_eq!(d.motion(300 * MS), Motion::Halt(GuardVerdict::NoVerdict));
    }

    #[test]
    fn every_non_clear_verdict_halts_with_its_own_name() {
        for v in [
            GuardVerdict::Stop,
            GuardVerdict::Stale,
            GuardVerdict::NoSurrogate,
            GuardVerdict::Unobserved,
        ] {
            let mut d = deadman();
            d.sent(0, 0);
            d.sent(1, MS);
            d.verdict(0, GuardVerdict::Clear);
            d.verdict(1, v);
            assert_eq!(d.motion(2 * MS), Motion::Halt(v));
        }
    }

    /// Exhaustive over short histories: motion is allowed only if some clear
    /// answers a joint state sent within the deadline and no stop answers that
    /// one or a later one.
    #[test]
    fn never_moves_without_a_fresh_unsuperseded_clear() {
        let events = [0u8, 1, 2, 3]; // 0 send, 1 clear newest, 2 stop newest, 3 clear oldest
        let mut histories = vec![vec![]];
        for _ in 0..6 {
            histories = histories
                .into_iter()
                .flat_map(|h: Vec<u8>| {
                    events.iter().map(move |&e| {
                        let mut h = h.clone();
                        h.push(e);
                        h
                    })
                })
                .collect();
        }
        for h in histories {
            let mut d = deadman();
            let (mut next, mut sent): (u64, Vec<(u64, u64)>) = (0, vec![]);
            let mut answers: Vec<(u64, bool)> = vec![]; // (seq, clear)
            for (t, &e) in h.iter().enumerate() {
                let now = t as u64 * 20 * MS;
                match e {
                    0 => {
                        d.sent(next, now);
                        sent.push((next, now));
                        next += 1;
                    }
                    _ => {
                        let Some(&(seq, _)) = (if e == 3 { sent.first() } else { sent.last() })
                        else {
                            continue;
                        };
                        let clear = e != 2;
                        let v = if clear {
                            GuardVerdict::Clear
                        } else {
                            GuardVerdict::Stop
                        };
                        d.verdict(seq, v);
                        answers.push((seq, clear));
                    }
                }
                if d.motion(now) == Motion::Move {
                    let newest_stop = answers.iter().filter(|a| !a.1).map(|a| a.0).max();
                    let ok = answers.iter().any(|&(seq, clear)| {
                        let sent_at = sent.iter().find(|s| s.0 == seq).unwrap().1;
                        clear
                            && now - sent_at <= d.deadline_ns()
                            && newest_stop.is_none_or(|s| seq > s)
                    });
                    assert!(ok, "moved without a fresh clear: {h:?} at step {t}");
                }
            }
        }
    }
}
