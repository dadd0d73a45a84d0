//! The latest status of every node of a namespace, kept up to date by a
//! subscriber of `status/*`, for tests that watch counters move: what a node
//! says now, and waits (bounded) for a status that satisfies a condition.
//! Payloads that do not decode are ignored here (a test may be flooding the
//! topic with them).

use shroud_msg::NodeStatusMessage;
use std::collections::HashMap;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};
use zenoh::Wait;

type Latest = Arc<(Mutex<HashMap<String, NodeStatusMessage>>, Condvar)>;

pub struct StatusBoard {
    latest: Latest,
    _subscriber: zenoh::pubsub::Subscriber<()>,
}

fn lock(latest: &Latest) -> MutexGuard<'_, HashMap<String, NodeStatusMessage>> {
    latest.0.lock().unwrap_or_else(|p| p.into_inner())
}

impl StatusBoard {
    pub fn new(session: &zenoh::Session, namespace: &str) -> StatusBoard {
        let latest: Latest = Arc::default();
        let sink = latest.clone();
        let subscriber = session
            .declare_subscriber(format!("shroud/{namespace}/status/*"))
            .callback(move |sample| {
                let bytes = sample.payload().to_bytes();
                if let Ok(status) = NodeStatusMessage::from_bytes(&bytes) {
                    lock(&sink).insert(status.node.clone(), status);
                    sink.1.notify_all();
                }
            })
            .wait()
            .expect("status subscriber");
        StatusBoard {
            latest,
            _subscriber: subscriber,
        }
    }

    /// The latest status of `node`, if any came.
    pub fn latest(&self, node: &str) -> Option<NodeStatusMessage> {
        lock(&self.latest).get(node).cloned()
    }

    /// The first status of `node` (the latest one included) that satisfies
    /// `done`; panics naming `what` and the last status seen if none does
    /// within `timeout`.
    pub fn wait_for(
        &self,
        node: &str,
        what: &str,
        timeout: Duration,
        done: impl Fn(&NodeStatusMessage) -> bool,
    ) -> NodeStatusMessage {
        let found = self.try_wait_for(node, timeout, done);
        found.unwrap_or_else(|| {
            panic!(
                "no status of {node} with {what} within {timeout:?}; last: {:?}",
                self.latest(node)
            )
        })
    }

    /// The first status of `node` (the latest one included) that satisfies
    /// `done`, if one comes within `timeout`.
    pub fn try_wait_for(
        &self,
        node: &str,
        timeout: Duration,
        done: impl Fn(&NodeStatusMessage) -> bool,
    ) -> Option<NodeStatusMessage> {
        let deadline = Instant::now() + timeout;
        let mut latest = lock(&self.latest);
        loop {
            if let Some(status) = latest.get(node).filter(|s| done(s)) {
                return Some(status.clone());
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return None;
            }
            latest = (self.latest.1.wait_timeout(latest, left))
                .unwrap_or_else(|p| p.into_inner())
                .0;
        }
    }

    /// A status of `node` published at or after `after_ns` (Unix ns).
    pub fn published_after(&self, node: &str, after_ns: u64) -> NodeStatusMessage {
        self.wait_for(node, "a fresh stamp", Duration::from_secs(30), |s| {
            s.stamp_ns >= after_ns
        })
    }
}
