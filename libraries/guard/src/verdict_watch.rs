//! What a display of an arm's safety shows: the guard's latest verdict while it
//! is fresh, and `no-verdict` once the guard has been silent for longer than a
//! timeout, so that a display never shows "clear" from a guard that stopped
//! talking (silence is never "clear"). Time is the caller's monotonic clock.

use shroud_msg::{CollisionMessage, GuardVerdict};

/// The verdict to show at some instant.
#[derive(Debug, Clone, PartialEq)]
pub struct ShownVerdict<'a> {
    pub verdict: GuardVerdict,
    /// The guard's reason, or why there is no verdict.
    pub reason: String,
    /// The message behind the verdict, absent before the first one.
    pub message: Option<&'a CollisionMessage>,
    /// Nanoseconds since that message arrived.
    pub age_ns: Option<u64>,
}

/// Latest verdict of one arm and when it arrived.
#[derive(Debug, Clone)]
pub struct VerdictWatch {
    timeout_ns: u64,
    latest: Option<(CollisionMessage, u64)>,
}

impl VerdictWatch {
    /// A watch that declares the guard silent after `timeout_ns` without a verdict.
    pub fn new(timeout_ns: u64) -> Self {
        Self {
            timeout_ns,
            latest: None,
        }
    }

    /// A verdict arrived at `now_ns`.
    pub fn on_verdict(&mut self, msg: CollisionMessage, now_ns: u64) {
        self.latest = Some((msg, now_ns));
    }

    /// What to show at `now_ns`.
    pub fn shown(&self, now_ns: u64) -> ShownVerdict<'_> {
        let Some((msg, at)) = &self.latest else {
            return ShownVerdict {
                verdict: GuardVerdict::NoVerdict,
                reason: "no verdict from the guard yet".into(),
                message: None,
                age_ns: None,
            };
        };
        let age = now_ns.saturating_sub(*at);
        if age > self.timeout_ns {
            return ShownVerdict {
                verdict: GuardVerdict::NoVerdict,
                reason: format!(
                    "no verdict for {:.1} s: the guard is silent or cut off",
                    age as f64 / 1e9
                ),
                message: Some(msg),
                age_ns: Some(age),
            };
        }
        ShownVerdict {
            verdict: msg.verdict,
            reason: msg.reason.clone(),
            message: Some(msg),
            age_ns: Some(age),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_msg::sample_collision as verdict;

    #[test]
    fn a_clear_is_shown_only_while_fresh() {
        let mut w = VerdictWatch::new(500);
        assert_eq!(w.shown(0).verdict, GuardVerdict::NoVerdict);
        w.on_verdict(verdict(GuardVerdict::Clear), 1000);
        assert_eq!(w.shown(1500).verdict, GuardVerdict::Clear);
        let silent = w.shown(1501);
        assert_eq!(silent.verdict, GuardVerdict::NoVerdict);
        assert!(silent.reason.contains("silent"), "{}", silent.reason);
        assert_eq!(silent.age_ns, Some(501));
        w.on_verdict(verdict(GuardVerdict::Stop), 2000);
        assert_eq!(w.shown(2000).verdict, GuardVerdict::Stop);
    }
}
