//! Wait and resume: after a halt, a consumer moves again only once its
//! [`Deadman`](super::Deadman) has allowed motion for a settling time, so that
//! a clearance hovering at the stop distance (a new cloud every 100 ms, each
//! older than the last by the time the next arrives) gives one halt, not a
//! stutter of twenty.

use super::Motion;
use shroud_msg::GuardVerdict;

/// See the module documentation. Time is an argument (monotonic nanoseconds).
#[derive(Debug, Clone)]
pub struct ResumeAfter {
    settle_ns: u64,
    /// When motion was last allowed after a halt (None: halted now).
    allowed_since: Option<u64>,
    /// Whether the consumer is moving (it has settled since the last halt).
    moving: bool,
    /// The verdict of the last halt, reported while settling.
    last_halt: GuardVerdict,
}

impl ResumeAfter {
    /// Resumes after motion has been allowed for `settle_ns` without a break;
    /// starts halted.
    pub fn new(settle_ns: u64) -> Self {
        Self {
            settle_ns,
            allowed_since: None,
            moving: false,
            last_halt: GuardVerdict::NoVerdict,
        }
    }

    /// What to do at `now_ns`, given what the deadman allows.
    pub fn motion(&mut self, allowed: Motion, now_ns: u64) -> Motion {
        match allowed {
            Motion::Halt(v) => {
                self.allowed_since = None;
                self.moving = false;
                self.last_halt = v;
                Motion::Halt(v)
            }
            Motion::Move if self.moving => Motion::Move,
            Motion::Move => {
                let since = *self.allowed_since.get_or_insert(now_ns);
                self.moving = now_ns.saturating_sub(since) >= self.settle_ns;
                if self.moving {
                    Motion::Move
                } else {
                    Motion::Halt(self.last_halt)
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: u64 = 1_000_000;

    #[test]
    fn resumes_only_after_settling_and_halts_at_once() {
        let mut r = ResumeAfter::new(200 * MS);
        let stop = Motion::Halt(GuardVerdict::Stop);
        assert_eq!(
            r.motion(Motion::Move, 0),
            Motion::Halt(GuardVerdict::NoVerdict)
        );
        assert_eq!(r.motion(Motion::Move, 200 * MS), Motion::Move);
        // A halt takes effect at once.
        assert_eq!(r.motion(stop, 210 * MS), stop);
        // Allowed again, with a break in the middle: the settling restarts.
        assert_eq!(r.motion(Motion::Move, 300 * MS), stop);
        assert_eq!(r.motion(stop, 350 * MS), stop);
        assert_eq!(r.motion(Motion::Move, 400 * MS), stop);
        assert_eq!(r.motion(Motion::Move, 599 * MS), stop);
        assert_eq!(r.motion(Motion::Move, 600 * MS), Motion::Move);
        assert_eq!(r.motion(Motion::Move, 601 * MS), Motion::Move);
    }

    #[test]
    fn zero_settling_follows_the_deadman() {
        let mut r = ResumeAfter::new(0);
        let stale = Motion::Halt(GuardVerdict::Stale);
        for (allowed, t) in [(Motion::Move, 0), (stale, 1), (Motion::Move, 2)] {
            assert_eq!(r.motion(allowed, t), allowed);
        }
    }

    /// Never moves when the deadman says halt, whatever came before.
    #[test]
    fn never_moves_against_the_deadman() {
        let mut r = ResumeAfter::new(30 * MS);
        for t in 0..2000u64 {
            let allowed = if (t * 7919) % 13 < 5 {
                Motion::Halt(GuardVerdict::Stop)
            } else {
                Motion::Move
            };
            let m = r.motion(allowed, t * MS);
            if allowed != Motion::Move {
                assert_eq!(m, allowed);
            }
        }
    }
}
