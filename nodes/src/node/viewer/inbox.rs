//! What a viewer node hears from the graph: every sample lands, from zenoh's
//! callback, in one slot per key (a newer sample of a key replaces the one the
//! viewer has not taken yet) and in the per-topic traffic counts. The
//! callback never decodes nor waits: a 300K-point cloud at 30 Hz costs it a
//! slot swap.

use crate::transport::{monotonic_ns, WaitQueue};
use shroud_graph::backlog::LatestByKey;
use shroud_graph::metrics::RateMeter;
use shroud_msg::{TopicKey, TopicKind};
use shroud_viewers::dashboard::TopicRate;
use std::collections::BTreeMap;
use std::sync::{Mutex, MutexGuard};
use std::time::Duration;
use zenoh::bytes::ZBytes;

/// The window over which topic rates are measured.
const RATE_WINDOW_NS: u64 = 2_000_000_000;

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // Every critical section is a single counter update.
    m.lock().unwrap_or_else(|p| p.into_inner())
}

struct Traffic {
    kind: TopicKind,
    meter: RateMeter,
    messages: u64,
    bytes: u64,
    /// `bytes` and the time at the previous report, for bytes per second.
    reported: (u64, u64),
}

/// A received sample, kept until the viewer takes it.
#[derive(Clone)]
pub struct Arrival {
    pub payload: ZBytes,
    /// This host's monotonic clock at receipt.
    pub received_ns: u64,
}

/// See the module documentation.
pub struct Inbox {
    pending: WaitQueue<LatestByKey<TopicKey, Arrival>>,
    traffic: Mutex<BTreeMap<String, Traffic>>,
}

impl Inbox {
    pub fn new() -> Self {
        Self {
            pending: WaitQueue::new(LatestByKey::default()),
            traffic: Mutex::new(BTreeMap::new()),
        }
    }

    /// A sample arrived on `key` (zenoh's callback thread).
    pub fn push(&self, key: &str, payload: ZBytes) {
        let now = monotonic_ns();
        let Some(topic) = TopicKey::parse(key) else {
            return; // not a shroud topic: nothing a viewer can show
        };
        self.count(&topic, payload.len() as u64, now);
        let arrival = Arrival {
            payload,
            received_ns: now,
        };
        self.pending.push(|pending| pending.put(topic, arrival));
    }

    fn count(&self, topic: &TopicKey, bytes: u64, now: u64) {
        let mut traffic = lock(&self.traffic);
        let name = format!("{}/{}", topic.kind, topic.name);
        let entry = traffic.entry(name).or_insert_with(|| Traffic {
            kind: topic.kind,
            meter: RateMeter::new(RATE_WINDOW_NS),
            messages: 0,
            bytes: 0,
            reported: (0, now),
        });
        entry.meter.tick(now);
        entry.messages += 1;
        entry.bytes += bytes;
    }

    /// The oldest pending sample, waiting up to `timeout` for one.
    pub fn take(&self, timeout: Duration) -> Option<(TopicKey, Arrival)> {
        self.pending.take(timeout)
    }

    /// Samples replaced before the viewer took them.
    pub fn superseded(&self) -> u64 {
        self.pending.read(|pending| pending.superseded())
    }

    /// Each topic's rate, message count and bytes per second since the last call.
    pub fn rates(&self, now: u64) -> Vec<TopicRate> {
        lock(&self.traffic)
            .iter_mut()
            .map(|(topic, t)| {
                let (bytes_then, then) = t.reported;
                let seconds = now.saturating_sub(then) as f64 / 1e9;
                let bytes_per_s = if seconds > 0.0 {
                    (t.bytes - bytes_then) as f64 / seconds
                } else {
                    0.0
                };
                t.reported = (t.bytes, now);
                TopicRate {
                    topic: topic.clone(),
                    kind: t.kind.to_string(),
                    rate_hz: t.meter.rate_hz(now),
                    messages: t.messages,
                    bytes_per_s,
                }
            })
            .collect()
    }
}
