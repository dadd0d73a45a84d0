//! What the recorder's subscribers, its writer thread and its node body
//! share: the counts (taken, written, dropped by topic and cause, also kept in
//! the node's status counters) and whether the writer still takes messages.

use crate::runtime::NodeMetrics;
use shroud_graph::metrics::names::{self as metric, Counter};
use shroud_record::{DropCause, DropCounts};
use std::sync::{Arc, Mutex, MutexGuard};

pub struct Recording {
    metrics: Arc<NodeMetrics>,
    drops: Mutex<DropCounts>,
    /// Set once the writer stopped (disk full, write error), with why.
    refused: Mutex<Option<(DropCause, String)>>,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // Counts stay meaningful even if a thread panicked mid-update.
    m.lock().unwrap_or_else(|p| p.into_inner())
}

impl Recording {
    pub fn new(metrics: Arc<NodeMetrics>) -> Self {
        for cause in DropCause::ALL {
            metrics.set_counter(Counter::of(cause.counter()), 0);
        }
        metrics.set_counter(metric::VIEWS_WRITTEN, 0);
        metrics.set_counter(metric::VIEWS_FAILED, 0);
        metrics.set_counter(metric::VIEWS_PACED, 0);
        Self {
            metrics,
            drops: Mutex::default(),
            refused: Mutex::default(),
        }
    }

    /// A message of a recorded topic arrived.
    pub fn received(&self) {
        self.metrics.add(metric::RECEIVED, 1);
    }

    pub fn written(&self, bytes: u64) {
        self.metrics.add(metric::WRITTEN, 1);
        self.metrics.add(metric::BYTES_WRITTEN, bytes);
    }

    /// Foxglove views written (`--foxglove`), and the messages of heavy
    /// streams left without a view by `--foxglove-rate` so far.
    pub fn views_written(&self, n: u64, paced: u64) {
        self.metrics.add(metric::VIEWS_WRITTEN, n);
        self.metrics.set_counter(metric::VIEWS_PACED, paced);
    }

    /// A recorded message whose Foxglove view could not be made (the raw
    /// message is recorded all the same).
    pub fn view_failed(&self, reason: &str) {
        self.metrics.add(metric::VIEWS_FAILED, 1);
        tracing::warn!("no Foxglove view: {reason}");
    }

    /// A recorded message whose ROS 2 message could not be made (`--ros2`;
    /// counted with the views that failed; the raw message is recorded all
    /// the same).
    pub fn ros2_failed(&self, reason: &str) {
        self.metrics.add(metric::VIEWS_FAILED, 1);
        tracing::warn!("no ROS 2 message: {reason}");
    }

    pub fn dropped(&self, topic: &str, cause: DropCause) {
        lock(&self.drops).add(topic, cause);
        self.metrics.add(Counter::of(cause.counter()), 1);
    }

    pub fn queue_bytes(&self, bytes: usize) {
        self.metrics.set(metric::QUEUE_MB, bytes as f64 / 1e6);
    }

    /// Stops taking messages (the first cause is kept).
    pub fn refuse(&self, cause: DropCause, reason: String) {
        lock(&self.refused).get_or_insert((cause, reason));
    }

    /// Why messages are no longer taken, if they are not.
    pub fn refusing(&self) -> Option<DropCause> {
        lock(&self.refused).as_ref().map(|(c, _)| *c)
    }

    pub fn refusal(&self) -> Option<(DropCause, String)> {
        lock(&self.refused).clone()
    }

    pub fn drops(&self) -> DropCounts {
        lock(&self.drops).clone()
    }

    pub fn counter(&self, counter: Counter) -> u64 {
        self.metrics.counter(counter)
    }
}
