//! A queued typed input: zenoh's callback hands each sample to a bounded
//! drop-oldest mailbox, and the node's worker takes, decodes and uses them
//! one at a time, with what it receives, drops for backlog and refuses as
//! malformed counted and logged here.

use super::arrival::{refused, Arrival};
use super::metrics::NodeMetrics;
use crate::transport::{monotonic_ns, WaitQueue};
use anyhow::Result;
use shroud_graph::backlog::DropOldest;
use shroud_graph::metrics::names as metric;
use shroud_msg::Message;
use std::cell::Cell;
use std::marker::PhantomData;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;
use zenoh::Wait;

/// How long a worker waits for a sample before it looks at the stop flag.
const POLL: Duration = Duration::from_millis(100);

/// Samples of messages `M` from `shroud/<ns>/<M::KIND>/<name>`.
pub struct Input<M: Message> {
    metrics: Arc<NodeMetrics>,
    /// The node's stop flag.
    stop: Arc<AtomicBool>,
    mailbox: Arc<WaitQueue<DropOldest<Arrival>>>,
    /// The queue's drops already added to the node's `dropped_backlog`
    /// (added, not set: a node may have several inputs).
    dropped_counted: Cell<u64>,
    key: String,
    _subscriber: zenoh::pubsub::Subscriber<()>,
    _message: PhantomData<fn() -> M>,
}

impl<M: Message> Input<M> {
    /// Subscribes with a queue of `capacity` samples: when the worker falls
    /// behind, the oldest is dropped (counted as `dropped_backlog`).
    pub(super) fn new(
        session: &zenoh::Session,
        key: String,
        capacity: usize,
        metrics: Arc<NodeMetrics>,
        stop: Arc<AtomicBool>,
    ) -> Result<Self> {
        anyhow::ensure!(capacity > 0, "an input queue holds at least one sample");
        let mailbox = Arc::new(WaitQueue::new(DropOldest::new(capacity)));
        let inbox = mailbox.clone();
        let counted = metrics.clone();
        let subscriber = session
            .declare_subscriber(key.clone())
            .callback(move |sample| {
                if let Some(reason) = refused(&sample) {
                    return counted.drop_malformed(sample.key_expr().as_str(), &reason);
                }
                inbox.push(|backlog| backlog.push(Arrival::of(&sample)));
            })
            .wait()
            .map_err(|e| anyhow::anyhow!("subscribe {key}: {e}"))?;
        Ok(Self {
            metrics,
            stop,
            mailbox,
            dropped_counted: Cell::new(0),
            key,
            _subscriber: subscriber,
            _message: PhantomData,
        })
    }

    /// The key expression subscribed to.
    pub fn key(&self) -> &str {
        &self.key
    }

    /// The oldest queued sample, waiting at most `timeout`; `None` on timeout
    /// or once the node stops. Counts it (`received`) and refreshes the
    /// backlog count.
    pub fn recv_timeout(&self, timeout: Duration) -> Option<Arrival> {
        self.count_backlog();
        if self.stopping() {
            return None;
        }
        let mut arrival = self.mailbox.take(timeout)?;
        arrival.taken_ns = monotonic_ns();
        self.metrics.add(metric::RECEIVED, 1);
        Some(arrival)
    }

    /// Decodes `arrival` and hands the message to `use_it`; a payload that
    /// does not decode is counted (`dropped_malformed`), logged, and gives `None`.
    pub fn decoded<R>(
        &self,
        arrival: &Arrival,
        use_it: impl FnOnce(M::View<'_>) -> R,
    ) -> Option<R> {
        let bytes = arrival.payload.to_bytes();
        let used = match M::decode(&bytes) {
            Ok(message) => Some(use_it(message)),
            Err(e) => {
                self.metrics.drop_malformed(&arrival.key, &e);
                None
            }
        };
        used
    }

    /// Adds the drops since the last call to the node's `dropped_backlog`.
    fn count_backlog(&self) {
        let dropped = self.mailbox.read(|backlog| backlog.dropped());
        let new = dropped.saturating_sub(self.dropped_counted.replace(dropped));
        // Added even when 0, so that the count is in the status from the start.
        self.metrics.add(metric::DROPPED_BACKLOG, new);
    }

    fn stopping(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    /// Takes, decodes and hands over every sample until the node stops.
    pub fn for_each(&self, mut handle: impl FnMut(&Arrival, M::View<'_>)) {
        while !self.stopping() {
            if let Some(arrival) = self.recv_timeout(POLL) {
                self.decoded(&arrival, |message| handle(&arrival, message));
            }
        }
    }
}

impl<M: Message> Drop for Input<M> {
    fn drop(&mut self) {
        // Wakes a worker still waiting and refuses what zenoh delivers until
        // the subscriber is undeclared.
        self.mailbox.close();
        self.count_backlog();
    }
}
