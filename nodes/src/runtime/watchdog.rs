//! The hard deadline of a node's shutdown.

use crate::transport::last_words_and_exit;
use std::sync::{Arc, Mutex, Once};
use std::time::Duration;

/// After a stop request the process exits by this deadline, whatever is stuck.
pub(super) const HARD_DEADLINE: Duration = Duration::from_secs(10);

/// The hard deadline of a node's shutdown: once armed, exits the process after
/// [`HARD_DEADLINE`] with an error naming the stage that did not finish, so that
/// nothing (a looping body, a hung session close) keeps a node alive.
pub(super) struct Watchdog {
    name: String,
    stage: Arc<Mutex<&'static str>>,
    armed: Once,
}

impl Watchdog {
    pub(super) fn new(name: &str) -> Self {
        Watchdog {
            name: name.to_string(),
            stage: Arc::new(Mutex::new("the node body")),
            armed: Once::new(),
        }
    }

    /// Names what the shutdown waits for now.
    pub(super) fn stage(&self, stage: &'static str) {
        *self.stage.lock().unwrap_or_else(|p| p.into_inner()) = stage;
    }

    pub(super) fn arm(&self) {
        self.armed.call_once(|| {
            let (name, stage) = (self.name.clone(), self.stage.clone());
            let expire = move || {
                std::thread::sleep(HARD_DEADLINE);
                let stage = *stage.lock().unwrap_or_else(|p| p.into_inner());
                // Not through tracing: its writer's lock may be held by a
                // thread blocked on a full pipe.
                last_words_and_exit(
                    &format!("error: node {name}: {stage} did not stop within {HARD_DEADLINE:?} of the stop request; exiting\n"),
                    2,
                );
            };
            let spawned = std::thread::Builder::new()
                .name("stop-deadline".into())
                .spawn(expire);
            if let Err(e) = spawned {
                tracing::error!("no shutdown deadline (cannot start its thread): {e}");
            }
        });
    }
}
