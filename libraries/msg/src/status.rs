//! Node status messages: counters and gauges a node publishes about itself
//! once a second, for `shroud node list`, dashboards and the launcher's summary.

use super::blob::{decode, encode};
use super::error::MessageError;
use super::{check_finite, check_version, SCHEMA_VERSION};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A node's self-report. Counter names are stable (`received`, `published`,
/// `dropped_backlog`, `dropped_malformed`, `errors`...); gauges are the latest
/// value of a measurement (`rate_hz`, `fit_ms`, `latency_ms`...).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodeStatusMessage {
    pub version: u16,
    pub stamp_ns: u64,
    /// The node's instance name (unique in its namespace).
    pub node: String,
    /// Which node program it runs (`scanner`, `fit`, `guard`, `arm`...).
    pub kind: String,
    pub pid: u32,
    pub uptime_s: f64,
    pub counters: BTreeMap<String, u64>,
    pub gauges: BTreeMap<String, f64>,
    /// Text facts about the node (a device's `device.state`, `device.model`,
    /// `device.health`...); absent in messages that have none.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub labels: BTreeMap<String, String>,
}

impl NodeStatusMessage {
    pub fn new(node: &str, kind: &str, pid: u32) -> Self {
        Self {
            version: SCHEMA_VERSION,
            stamp_ns: 0,
            node: node.to_owned(),
            kind: kind.to_owned(),
            pid,
            uptime_s: 0.0,
            counters: BTreeMap::new(),
            gauges: BTreeMap::new(),
            labels: BTreeMap::new(),
        }
    }

    pub fn counter(&self, name: &str) -> u64 {
        self.counters.get(name).copied().unwrap_or(0)
    }

    pub fn gauge(&self, name: &str) -> Option<f64> {
        self.gauges.get(name).copied()
    }

    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: Self = decode(bytes)?;
        check_version("node status", msg.version, SCHEMA_VERSION)?;
        let gauges: Vec<f64> = msg.gauges.values().copied().collect();
        check_finite("gauges", &gauges)?;
        check_finite("uptime_s", &[msg.uptime_s])?;
        Ok(msg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_rejects_nan_gauges() {
        let mut msg = NodeStatusMessage::new("fit", "fit", 42);
        msg.counters.insert("received".into(), 10);
        msg.gauges.insert("rate_hz".into(), 29.5);
        msg.labels.insert("device.state".into(), "streaming".into());
        let back = NodeStatusMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap();
        assert_eq!(back, msg);
        assert_eq!(back.counter("received"), 10);
        assert_eq!(back.counter("missing"), 0);
        msg.gauges.insert("bad".into(), f64::NAN);
        assert!(NodeStatusMessage::from_bytes(&msg.to_bytes().unwrap()).is_err());
    }
}
