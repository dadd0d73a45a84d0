//! What the launcher knows of its children (starts, restarts, pid, state) and
//! the malformed messages its summary skipped, published as its own status
//! message (`status/launcher`, kind `launch`), so that `shroud node list`,
//! dashboards and tests see restart counts.

use crate::transport::unix_ns;
use shroud_graph::metrics::{names, ZenohDrops};
use shroud_msg::{NodeStatusMessage, TopicKind, Topics};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};
use zenoh::Wait;

/// The launcher's status name; launch files may not use it for a node.
pub use shroud_graph::launch::LAUNCHER_NAME;

#[derive(Debug, Clone, Default)]
struct Child {
    starts: u64,
    pid: u32,
    state: &'static str,
}

/// Every child's record, shared by the supervising tasks, and the summary's
/// count of messages it could not decode.
#[derive(Debug, Clone)]
pub struct Roster {
    /// The launcher's status name.
    name: Arc<str>,
    children: Arc<Mutex<BTreeMap<String, Child>>>,
    dropped_malformed: Arc<AtomicU64>,
}

impl Default for Roster {
    fn default() -> Self {
        Self::named(LAUNCHER_NAME)
    }
}

impl Roster {
    /// A roster published as status `name`.
    pub fn named(name: &str) -> Self {
        Self {
            name: name.into(),
            children: Arc::default(),
            dropped_malformed: Arc::default(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, BTreeMap<String, Child>> {
        self.children.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The summary skipped a message it could not decode.
    pub fn malformed(&self) {
        self.dropped_malformed.fetch_add(1, Ordering::Relaxed);
    }

    /// Node `name` was started with `pid`.
    pub fn started(&self, name: &str, pid: u32) {
        let mut children = self.lock();
        let child = children.entry(name.to_string()).or_default();
        child.starts += 1;
        child.pid = pid;
        child.state = "running";
    }

    /// Node `name` is in `state` (`restarting`, `stopped`, `finished`, `gave-up`).
    pub fn set_state(&self, name: &str, state: &'static str) {
        self.lock().entry(name.to_string()).or_default().state = state;
    }

    /// The status message: `restarts.<node>` and `starts.<node>` counters,
    /// `pid.<node>` and `state.<node>` labels, and `dropped_malformed`.
    pub fn status(&self, started: Instant, drops: Option<ZenohDrops>) -> NodeStatusMessage {
        let mut msg = NodeStatusMessage::new(&self.name, "launch", std::process::id());
        msg.stamp_ns = unix_ns();
        msg.uptime_s = started.elapsed().as_secs_f64();
        msg.counters.insert(
            names::DROPPED_MALFORMED.name.into(),
            self.dropped_malformed.load(Ordering::Relaxed),
        );
        for (counter, value) in drops.iter().flat_map(ZenohDrops::counters) {
            msg.counters.insert(counter.name.into(), value);
        }
        for (name, child) in self.lock().iter() {
            msg.counters.insert(format!("starts.{name}"), child.starts);
            msg.counters
                .insert(format!("restarts.{name}"), child.starts.saturating_sub(1));
            msg.labels
                .insert(format!("pid.{name}"), child.pid.to_string());
            msg.labels
                .insert(format!("state.{name}"), child.state.to_string());
        }
        msg
    }
}

/// Publishes the roster every `period` until aborted.
pub async fn publish(session: zenoh::Session, topics: Topics, roster: Roster, period: Duration) {
    let Ok(key) = topics.key(TopicKind::Status, &roster.name) else {
        return;
    };
    let publisher = match crate::transport::topic_publisher(&session, key, TopicKind::Status) {
        Ok(p) => p,
        Err(e) => {
            super::output::err(format!("[launch] no launcher status: {e:#}"));
            return;
        }
    };
    let started = Instant::now();
    let mut tick = tokio::time::interval(period);
    loop {
        tick.tick().await;
        let drops = crate::transport::session_drops(&session).await;
        if let Ok(bytes) = roster.status(started, drops).to_bytes() {
            let _ = publisher.put(bytes).wait();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn restarts_count_every_start_after_the_first() {
        let roster = Roster::default();
        roster.started("fit", 10);
        roster.set_state("fit", "restarting");
        roster.started("fit", 11);
        roster.started("guard", 12);
        roster.malformed();
        let drops = ZenohDrops {
            access_control: 3,
            ..ZenohDrops::default()
        };
        let msg = roster.status(Instant::now(), Some(drops));
        assert_eq!(msg.node, LAUNCHER_NAME);
        assert_eq!(msg.kind, "launch");
        assert_eq!(msg.counter("restarts.fit"), 1);
        assert_eq!(msg.counter("starts.fit"), 2);
        assert_eq!(msg.counter("restarts.guard"), 0);
        assert_eq!(msg.labels["pid.fit"], "11");
        assert_eq!(msg.labels["state.fit"], "running");
        assert_eq!(
            msg.counter(shroud_graph::metrics::names::DROPPED_MALFORMED.name),
            1
        );
        assert_eq!(msg.counter(names::ZENOH_DROPPED_ACCESS_CONTROL.name), 3);
    }
}
