//! The deadman of a verdict consumer (a robot driver, the simulated arm): it may
//! move only while a `clear` verdict for one of its own recent joint states is
//! younger than a deadline, so a guard that crashes, restarts, drops a message
//! or is cut off by a partition halts the robot instead of leaving it on its
//! last "clear".
//!
//! Time is an argument (nanoseconds on the consumer's own monotonic clock), so
//! the deadline covers the whole round trip: joint state out, check, verdict
//! back. A verdict is matched to a joint state by sequence *and* stamp, so a
//! restarted consumer or another one on the same stream never clears this one.
//! A `stop` halts at once, whatever joint state it answers (or none), and only a
//! `clear` for a joint state sent after the stop arrived releases it: a stop
//! that arrives late, after a clear for a newer joint state, still halts.

use shroud_msg::GuardVerdict;
use std::collections::VecDeque;

/// Joint states remembered (sequence, stamp, send time): 256 is over 5 s at
/// 50 Hz and 0.25 s at 1 kHz, more than any sensible deadline.
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
    /// It was applied (every stop is; a clear that answers one of the recent
    /// joint states and is newer than the last stop).
    Applied,
    /// A `clear` for a joint state this deadman does not remember (too old,
    /// another consumer's, or a stamp that does not match): ignored.
    Unknown,
    /// A `clear` for a joint state sent before the last stop arrived: ignored.
    Superseded,
}

/// One joint state sent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Sent {
    sequence: u64,
    stamp_ns: u64,
    at_ns: u64,
}

/// See the module documentation.
#[derive(Debug, Clone)]
pub struct Deadman {
    deadline_ns: u64,
    /// Oldest first.
    sent: VecDeque<Sent>,
    /// The newest clear applied.
    clear: Option<Sent>,
    /// Its speed scale.
    clear_scale: f64,
    /// The newest stop: the newest sequence sent when it arrived (a clear must
    /// answer a later one) and its verdict.
    stop: Option<(Option<u64>, GuardVerdict)>,
}

impl Deadman {
    /// A deadman that allows motion for `deadline_ns` after sending a joint
    /// state that was then cleared. The usual deadline is three joint periods.
    pub fn new(deadline_ns: u64) -> Self {
        Self {
            deadline_ns,
            sent: VecDeque::with_capacity(REMEMBERED),
            clear: None,
            clear_scale: 0.0,
            stop: None,
        }
    }

    /// The deadline of a consumer publishing joint states every `period_s`:
    /// `requested` (seconds) or three periods, never longer than the guard's
    /// `horizon` (seconds), the time after a decision its allowance covers.
    /// A default longer than the horizon is cut to it; a requested one is
    /// refused, and so is a deadline of 0 (a horizon of 0), under which the
    /// consumer could never move.
    pub fn deadline_for(
        period_s: f64,
        requested: Option<f64>,
        horizon: f64,
    ) -> Result<f64, crate::GuardError> {
        use crate::GuardError;
        let deadline = match requested {
            Some(deadline) if deadline > horizon => {
                return Err(GuardError::DeadlineBeyondHorizon { deadline, horizon })
            }
            Some(deadline) => deadline,
            None => (3.0 * period_s).min(horizon),
        };
        // The consumer counts in nanoseconds: less than one is none.
        if deadline * 1e9 >= 1.0 {
            Ok(deadline)
        } else {
            Err(GuardError::NoTimeToMove { deadline, horizon })
        }
    }

    pub fn deadline_ns(&self) -> u64 {
        self.deadline_ns
    }

    /// The consumer published joint state (`sequence`, `stamp_ns`) at `now_ns`.
    /// Sequences must increase.
    pub fn sent(&mut self, sequence: u64, stamp_ns: u64, now_ns: u64) {
        if self.sent.len() == REMEMBERED {
            self.sent.pop_front();
        }
        self.sent.push_back(Sent {
            sequence,
            stamp_ns,
            at_ns: now_ns,
        });
    }

    /// A verdict arrived for joint state (`sequence`, `stamp_ns`), a `clear`
    /// taken at full speed: only for a guard without speed monitoring, whose
    /// clears are all at scale 1. A consumer of scaled verdicts calls
    /// [`Self::scaled_verdict`] and moves at [`Self::scale`], never at the
    /// speed [`Self::motion`] alone would suggest.
    pub fn verdict(&mut self, sequence: u64, stamp_ns: u64, verdict: GuardVerdict) -> VerdictUse {
        self.scaled_verdict(sequence, stamp_ns, verdict, 1.0)
    }

    /// A verdict with its speed scale arrived for joint state (`sequence`,
    /// `stamp_ns`): a `clear` lets the consumer move at `scale` of its
    /// nominal speed.
    pub fn scaled_verdict(
        &mut self,
        sequence: u64,
        stamp_ns: u64,
        verdict: GuardVerdict,
        scale: f64,
    ) -> VerdictUse {
        if verdict != GuardVerdict::Clear {
            // Whatever it answers, only joint states sent from now on can
            // clear it.
            let newest = self.sent.back().map(|s| s.sequence);
            let later = match self.stop {
                Some((Some(s), _)) => newest.map(|n| n.max(s)),
                _ => newest,
            };
            self.stop = Some((later, verdict));
            return VerdictUse::Applied;
        }
        let known = self
            .sent
            .iter()
            .find(|s| s.sequence == sequence && s.stamp_ns == stamp_ns)
            .copied();
        let Some(answered) = known else {
            return VerdictUse::Unknown;
        };
        if !self.after_stop(answered.sequence) {
            return VerdictUse::Superseded;
        }
        if self.clear.is_none_or(|c| answered.sequence > c.sequence) {
            self.clear = Some(answered);
            // NaN or out of range is never a reason to move faster.
            self.clear_scale = if scale >= 0.0 { scale.min(1.0) } else { 0.0 };
        }
        VerdictUse::Applied
    }

    /// Whether joint state `sequence` was sent after the last stop arrived.
    fn after_stop(&self, sequence: u64) -> bool {
        match self.stop {
            Some((Some(s), _)) => sequence > s,
            _ => true,
        }
    }

    /// The fraction of its nominal speed the consumer may move at, at
    /// `now_ns`: the newest applied clear's scale while it allows motion, 0
    /// otherwise.
    pub fn scale(&self, now_ns: u64) -> f64 {
        match self.motion(now_ns) {
            Motion::Move => self.clear_scale,
            Motion::Halt(_) => 0.0,
        }
    }

    /// What the consumer may do at `now_ns`.
    pub fn motion(&self, now_ns: u64) -> Motion {
        let clear = self.clear.filter(|c| self.after_stop(c.sequence));
        match (clear, self.stop) {
            (Some(c), _) if now_ns.saturating_sub(c.at_ns) <= self.deadline_ns => Motion::Move,
            (None, Some((_, v))) => Motion::Halt(v),
            _ => Motion::Halt(GuardVerdict::NoVerdict),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: u64 = 1_000_000;
    const CLEAR: GuardVerdict = GuardVerdict::Clear;
    const STOP: GuardVerdict = GuardVerdict::Stop;

    /// A consumer at 50 Hz (20 ms) with a 60 ms deadline; joint state `s` is
    /// stamped `1000 + s`.
    fn deadman() -> Deadman {
        Deadman::new(60 * MS)
    }

    #[test]
    fn deadlines_never_exceed_the_horizon() {
        // 50 Hz: three periods, inside a 0.1 s horizon.
        assert_eq!(Deadman::deadline_for(0.02, None, 0.1).unwrap(), 0.06);
        // 10 Hz: three periods would be 0.3 s; cut to the horizon.
        assert_eq!(Deadman::deadline_for(0.1, None, 0.1).unwrap(), 0.1);
        assert_eq!(Deadman::deadline_for(0.1, Some(0.05), 0.1).unwrap(), 0.05);
        let refused = Deadman::deadline_for(0.1, Some(0.5), 0.1).unwrap_err();
        assert!(refused.to_string().contains("horizon"), "{refused}");
        // A horizon of 0 would leave the arm halted for ever: refused by name.
        for (requested, horizon) in [(None, 0.0), (Some(0.0), 0.1), (Some(1e-12), 0.1)] {
            let refused = Deadman::deadline_for(0.02, requested, horizon).unwrap_err();
            assert!(refused.to_string().contains("no time to move"), "{refused}");
        }
    }

    fn send(d: &mut Deadman, s: u64, at: u64) {
        d.sent(s, 1000 + s, at);
    }

    fn answer(d: &mut Deadman, s: u64, v: GuardVerdict) -> VerdictUse {
        d.verdict(s, 1000 + s, v)
    }

    #[test]
    fn halted_until_the_first_clear() {
        let mut d = deadman();
        assert_eq!(d.motion(0), Motion::Halt(GuardVerdict::NoVerdict));
        send(&mut d, 0, 0);
        assert_eq!(d.motion(5 * MS), Motion::Halt(GuardVerdict::NoVerdict));
        assert_eq!(answer(&mut d, 0, CLEAR), VerdictUse::Applied);
        assert_eq!(d.motion(5 * MS), Motion::Move);
    }

    #[test]
    fn the_newest_clear_sets_the_speed_scale_and_a_halt_zeroes_it() {
        let mut d = deadman();
        send(&mut d, 0, 0);
        send(&mut d, 1, 20 * MS);
        d.scaled_verdict(1, 1001, CLEAR, 0.4);
        assert_eq!(d.scale(25 * MS), 0.4);
        // An older clear does not override the newer one's scale.
        d.scaled_verdict(0, 1000, CLEAR, 1.0);
        assert_eq!(d.scale(25 * MS), 0.4);
        // Silence past the deadline: no speed at all.
        assert_eq!(d.scale(80 * MS + 1), 0.0);
        // A scale that is no number never moves the arm.
        send(&mut d, 2, 90 * MS);
        d.scaled_verdict(2, 1002, CLEAR, f64::NAN);
        assert_eq!(d.scale(95 * MS), 0.0);
        send(&mut d, 3, 100 * MS);
        answer(&mut d, 3, STOP);
        assert_eq!(d.scale(101 * MS), 0.0);
    }

    #[test]
    fn silence_halts_after_the_deadline_of_the_last_cleared_joint_state() {
        let mut d = deadman();
        send(&mut d, 0, 0);
        answer(&mut d, 0, CLEAR);
        send(&mut d, 1, 20 * MS);
        send(&mut d, 2, 40 * MS);
        // No answer to 1 or 2: the clear of 0 (sent at 0) lasts 60 ms.
        assert_eq!(d.motion(60 * MS), Motion::Move);
        assert_eq!(d.motion(60 * MS + 1), Motion::Halt(GuardVerdict::NoVerdict));
        // A late clear for 2 buys time from 2's send time, not from its arrival.
        answer(&mut d, 2, CLEAR);
        assert_eq!(d.motion(100 * MS), Motion::Move);
        assert_eq!(
            d.motion(100 * MS + 1),
            Motion::Halt(GuardVerdict::NoVerdict)
        );
    }

    #[test]
    fn a_stop_halts_at_once_and_only_a_joint_state_sent_after_it_releases_it() {
        let mut d = deadman();
        for s in 0..4 {
            send(&mut d, s, s * 20 * MS);
        }
        answer(&mut d, 1, CLEAR);
        // The stop answers 2 but arrives after 3 was sent: 3 cannot clear it.
        answer(&mut d, 2, STOP);
        assert_eq!(d.motion(61 * MS), Motion::Halt(STOP));
        assert_eq!(answer(&mut d, 3, CLEAR), VerdictUse::Superseded);
        assert_eq!(d.motion(61 * MS), Motion::Halt(STOP));
        send(&mut d, 4, 80 * MS);
        answer(&mut d, 4, CLEAR);
        assert_eq!(d.motion(81 * MS), Motion::Move);
    }

    #[test]
    fn a_late_stop_for_an_older_joint_state_still_halts() {
        let mut d = deadman();
        for s in 0..3 {
            send(&mut d, s, s * 20 * MS);
        }
        answer(&mut d, 2, CLEAR);
        assert_eq!(d.motion(41 * MS), Motion::Move);
        // Another guard's (or a delayed) stop for joint state 1.
        answer(&mut d, 1, STOP);
        assert_eq!(d.motion(41 * MS), Motion::Halt(STOP));
    }

    #[test]
    fn a_stop_for_an_unknown_joint_state_holds_until_a_newer_clear() {
        let mut d = deadman();
        send(&mut d, 0, 0);
        answer(&mut d, 0, CLEAR);
        // The guard could not decode a joint state: it answers no sequence.
        assert_eq!(d.verdict(u64::MAX, 0, STOP), VerdictUse::Applied);
        assert_eq!(d.motion(MS), Motion::Halt(STOP));
        send(&mut d, 1, 20 * MS);
        answer(&mut d, 1, CLEAR);
        assert_eq!(d.motion(21 * MS), Motion::Move);
    }

    #[test]
    fn clears_of_strangers_and_forgotten_states_are_ignored() {
        let mut d = deadman();
        assert_eq!(answer(&mut d, 3, CLEAR), VerdictUse::Unknown);
        for s in 0..(REMEMBERED as u64 + 10) {
            send(&mut d, s, s * MS);
        }
        assert_eq!(answer(&mut d, 0, CLEAR), VerdictUse::Unknown);
        // Same sequence, another stamp: another consumer (or a restarted one).
        let newest = REMEMBERED as u64 + 9;
        assert_eq!(d.verdict(newest, 7, CLEAR), VerdictUse::Unknown);
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
            send(&mut d, 0, 0);
            send(&mut d, 1, MS);
            answer(&mut d, 0, CLEAR);
            answer(&mut d, 1, v);
            assert_eq!(d.motion(2 * MS), Motion::Halt(v));
        }
    }

    /// Exhaustive over short histories of sends, clears and stops (of the
    /// newest or the oldest joint state, or of none, in any order): the
    /// consumer moves exactly while it holds a clear for a joint state sent
    /// within the deadline and after every stop that has arrived.
    #[test]
    fn moves_exactly_while_a_fresh_clear_is_newer_than_every_stop() {
        // 0 send, 1 clear newest, 2 stop newest, 3 clear oldest, 4 stop
        // oldest, 5 stop of an undecodable joint state (no sequence)
        let mut histories = vec![vec![]];
        for _ in 0..6 {
            histories = histories
                .into_iter()
                .flat_map(|h: Vec<u8>| {
                    (0u8..6).map(move |e| {
                        let mut h = h.clone();
                        h.push(e);
                        h
                    })
                })
                .collect();
        }
        for h in histories {
            check_history(&h);
        }
    }

    fn check_history(h: &[u8]) {
        let mut d = deadman();
        let mut sent: Vec<(u64, u64)> = vec![];
        // Per stop: the newest sequence sent when it arrived.
        let mut stops: Vec<Option<u64>> = vec![];
        let mut clears: Vec<u64> = vec![];
        for (t, &e) in h.iter().enumerate() {
            let now = t as u64 * 20 * MS;
            if e == 0 {
                let s = sent.len() as u64;
                send(&mut d, s, now);
                sent.push((s, now));
            } else if e == 5 {
                d.verdict(u64::MAX, 0, STOP);
                stops.push(sent.last().map(|s| s.0));
            } else if let Some(&(seq, _)) = if e >= 3 { sent.first() } else { sent.last() } {
                if e % 2 == 1 {
                    answer(&mut d, seq, CLEAR);
                    clears.push(seq);
                } else {
                    answer(&mut d, seq, STOP);
                    stops.push(sent.last().map(|s| s.0));
                }
            }
            let ok = clears.iter().any(|&seq| {
                let sent_at = sent[seq as usize].1;
                let after_stops = stops.iter().all(|s| s.is_none_or(|s| seq > s));
                now - sent_at <= d.deadline_ns() && after_stops
            });
            assert_eq!(d.motion(now) == Motion::Move, ok, "{h:?} at step {t}");
        }
    }
}
