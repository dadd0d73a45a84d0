//! A node's counters and gauges, shared between its worker threads and the
//! status publisher.

use shroud_graph::metrics::names::{self, Counter, Gauge};
use shroud_msg::NodeStatusMessage;
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::sync::{Mutex, MutexGuard};

#[derive(Debug, Default)]
pub struct NodeMetrics {
    counters: Mutex<BTreeMap<Cow<'static, str>, u64>>,
    gauges: Mutex<BTreeMap<&'static str, f64>>,
    labels: Mutex<BTreeMap<String, String>>,
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // Counters stay meaningful even if a worker panicked mid-update.
    m.lock().unwrap_or_else(|p| p.into_inner())
}

impl NodeMetrics {
    pub fn add(&self, counter: Counter, n: u64) {
        *lock(&self.counters)
            .entry(Cow::Borrowed(counter.name))
            .or_insert(0) += n;
    }

    /// Sets a counter that another component keeps (e.g. a mailbox's drops).
    pub fn set_counter(&self, counter: Counter, value: u64) {
        lock(&self.counters).insert(Cow::Borrowed(counter.name), value);
    }

    /// [`Self::set_counter`] for a name made at run time (per sensor).
    pub fn set_named_counter(&self, counter: String, value: u64) {
        lock(&self.counters).insert(Cow::Owned(counter), value);
    }

    pub fn set(&self, gauge: Gauge, value: f64) {
        if value.is_finite() {
            lock(&self.gauges).insert(gauge.name, value);
        }
    }

    /// Sets a text fact (`device.state`, `device.model`...).
    pub fn set_label(&self, label: String, value: String) {
        lock(&self.labels).insert(label, value);
    }

    /// Removes the labels starting with `prefix`, except those in `keep`.
    pub fn remove_labels(&self, prefix: &str, keep: &[&str]) {
        lock(&self.labels).retain(|k, _| !k.starts_with(prefix) || keep.contains(&k.as_str()));
    }

    pub fn label(&self, label: &str) -> Option<String> {
        lock(&self.labels).get(label).cloned()
    }

    /// A message that could not be used: counted (`dropped_malformed`) and
    /// logged with its key.
    pub fn drop_malformed(&self, key: &str, error: &dyn std::fmt::Display) {
        self.add(names::DROPPED_MALFORMED, 1);
        tracing::warn!(key, "dropped a malformed message: {error}");
    }

    pub fn counter(&self, counter: Counter) -> u64 {
        lock(&self.counters).get(counter.name).copied().unwrap_or(0)
    }

    /// Copies the current values into a status message.
    pub fn fill(&self, msg: &mut NodeStatusMessage) {
        msg.counters = lock(&self.counters)
            .iter()
            .map(|(k, v)| (k.to_string(), *v))
            .collect();
        msg.gauges = lock(&self.gauges)
            .iter()
            .map(|(k, v)| (k.to_string(), *v))
            .collect();
        msg.labels = lock(&self.labels).clone();
    }
}
