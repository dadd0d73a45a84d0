//! Restart backoff: how long to wait before restarting a failed node, doubling
//! after each quick failure and forgetting failures once a run lasted long enough.

use super::file::{NodeSpec, RestartPolicy};
use std::time::Duration;

/// What the supervisor does after a child exited.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RestartDecision {
    /// Restart after this delay.
    RestartAfter(Duration),
    /// The policy says no restart (clean exit under `on-failure`, or `never`).
    Stop,
    /// The node failed more often in a row than `max_restarts` allows.
    GiveUp { failures: u32 },
}

/// Per-node restart state.
#[derive(Debug, Clone)]
pub struct Backoff {
    policy: RestartPolicy,
    initial: Duration,
    max: Duration,
    max_restarts: u32,
    stable_after: Duration,
    consecutive: u32,
}

impl Backoff {
    pub fn new(spec: &NodeSpec) -> Self {
        Self {
            policy: spec.restart,
            initial: Duration::from_millis(spec.backoff_ms),
            max: Duration::from_millis(spec.backoff_max_ms),
            max_restarts: spec.max_restarts,
            stable_after: Duration::from_millis(spec.stable_after_ms),
            consecutive: 0,
        }
    }

    /// Decides after an exit with `success` whose run lasted `ran_for`. A run
    /// longer than `stable_after` resets the count: a node that crashes once an
    /// hour is restarted promptly every time, one that crashes at start backs off.
    pub fn on_exit(&mut self, success: bool, ran_for: Duration) -> RestartDecision {
        let restart = match self.policy {
            RestartPolicy::Never => false,
            RestartPolicy::OnFailure => !success,
            RestartPolicy::Always => true,
        };
        if !restart {
            return RestartDecision::Stop;
        }
        if ran_for >= self.stable_after {
            self.consecutive = 0;
        }
        if self.consecutive >= self.max_restarts {
            return RestartDecision::GiveUp {
                failures: self.consecutive + 1,
            };
        }
        let factor = 1u32 << self.consecutive.min(20);
        self.consecutive += 1;
        RestartDecision::RestartAfter(self.initial.saturating_mul(factor).min(self.max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::launch::LaunchFile;

    fn spec(extra: &str) -> NodeSpec {
        let text = format!(
            "external = [\"cloud/c\"]\n[[node]]\nname = \"n\"\nkind = \"fit\"\n\
             inputs = {{ cloud = \"c\" }}\noutputs = {{ surrogate = \"s\" }}\n{extra}"
        );
        LaunchFile::from_toml_str(&text).unwrap().nodes.remove(0)
    }

    #[test]
    fn doubles_caps_and_gives_up() {
        let mut b = Backoff::new(&spec(
            "restart = \"on-failure\"\nbackoff_ms = 100\nbackoff_max_ms = 350\nmax_restarts = 3",
        ));
        let quick = Duration::from_millis(10);
        let ms = |d: u64| RestartDecision::RestartAfter(Duration::from_millis(d));
        assert_eq!(b.on_exit(false, quick), ms(100));
        assert_eq!(b.on_exit(false, quick), ms(200));
        assert_eq!(b.on_exit(false, quick), ms(350));
        assert_eq!(
            b.on_exit(false, quick),
            RestartDecision::GiveUp { failures: 4 }
        );
        assert_eq!(b.on_exit(true, quick), RestartDecision::Stop);
    }

    #[test]
    fn a_stable_run_resets_the_count() {
        let mut b = Backoff::new(&spec(
            "restart = \"always\"\nbackoff_ms = 100\nstable_after_ms = 1000",
        ));
        let quick = Duration::from_millis(10);
        assert_eq!(
            b.on_exit(false, quick),
            RestartDecision::RestartAfter(Duration::from_millis(100))
        );
        assert_eq!(
            b.on_exit(true, quick),
            RestartDecision::RestartAfter(Duration::from_millis(200))
        );
        assert_eq!(
            b.on_exit(false, Duration::from_secs(5)),
            RestartDecision::RestartAfter(Duration::from_millis(100))
        );
        let mut never = Backoff::new(&spec("restart = \"never\""));
        assert_eq!(never.on_exit(false, quick), RestartDecision::Stop);
    }
}
