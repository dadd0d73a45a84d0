//! Whether each node of a graph is alive, from the two signs a node gives: its
//! liveliness token (withdrawn by zenoh the moment its session ends, however
//! the process died) and its periodic status messages (which stop when a node
//! hangs with its session still open). Time is an argument (monotonic ns).

use shroud_msg::NodeStatusMessage;
use std::collections::BTreeMap;

/// A node is silent after this many of its status periods without a status.
const SILENT_AFTER_PERIODS: f64 = 2.5;
/// Status period assumed until two statuses have shown the node's own.
const DEFAULT_PERIOD_NS: u64 = 1_000_000_000;

/// What a viewer should say about a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeState {
    /// Its token is present, no status has arrived yet.
    Starting,
    /// A status arrived within [`SILENT_AFTER_PERIODS`] periods and its token
    /// (if the graph announces tokens) is present.
    Alive,
    /// No status for longer than that: hung, or cut off.
    Silent,
    /// Its token was withdrawn: the process ended or lost its session.
    Gone,
}

impl NodeState {
    pub fn name(self) -> &'static str {
        match self {
            Self::Starting => "starting",
            Self::Alive => "alive",
            Self::Silent => "silent",
            Self::Gone => "gone",
        }
    }
}

/// One node's row.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeRow<'a> {
    pub name: &'a str,
    pub state: NodeState,
    /// The latest status, if any arrived (a gone node keeps its last one).
    pub status: Option<&'a NodeStatusMessage>,
    /// Nanoseconds since that status arrived.
    pub status_age_ns: Option<u64>,
}

#[derive(Debug, Clone, Default)]
struct Entry {
    /// `Some(true)` token present, `Some(false)` withdrawn, `None` never seen.
    token: Option<bool>,
    status: Option<NodeStatusMessage>,
    status_at_ns: Option<u64>,
    period_ns: Option<u64>,
}

/// The table of every node heard of in a namespace.
#[derive(Debug, Clone, Default)]
pub struct NodeHealth {
    nodes: BTreeMap<String, Entry>,
}

impl NodeHealth {
    /// A liveliness token of node `name` appeared (`present`) or was withdrawn.
    pub fn on_token(&mut self, name: &str, present: bool) {
        let entry = self.nodes.entry(name.to_string()).or_default();
        if present && entry.token == Some(false) {
            // A new process under the same name: its statuses start afresh.
            *entry = Entry::default();
        }
        entry.token = Some(present);
    }

    /// A status message arrived at `now_ns`. A gone node's statuses (its final
    /// one lands around its token's withdrawal) update its counters but do not
    /// bring it back: only a new token does.
    pub fn on_status(&mut self, msg: NodeStatusMessage, now_ns: u64) {
        let entry = self.nodes.entry(msg.node.clone()).or_default();
        if let Some(previous) = entry.status_at_ns {
            let gap = now_ns.saturating_sub(previous);
            // The node's period is the shortest gap seen: a late status never
            // stretches it (nodes publish on a fixed tick).
            if gap > 0 {
                entry.period_ns = Some(entry.period_ns.map_or(gap, |p| p.min(gap)));
            }
        }
        entry.status = Some(msg);
        entry.status_at_ns = Some(now_ns);
    }

    /// The state of node `name` at `now_ns`, `None` if never heard of.
    pub fn state(&self, name: &str, now_ns: u64) -> Option<NodeState> {
        self.nodes.get(name).map(|e| Self::state_of(e, now_ns))
    }

    fn state_of(entry: &Entry, now_ns: u64) -> NodeState {
        if entry.token == Some(false) {
            return NodeState::Gone;
        }
        let Some(at) = entry.status_at_ns else {
            return NodeState::Starting;
        };
        let period = entry.period_ns.unwrap_or(DEFAULT_PERIOD_NS) as f64;
        if now_ns.saturating_sub(at) as f64 > SILENT_AFTER_PERIODS * period {
            NodeState::Silent
        } else {
            NodeState::Alive
        }
    }

    /// Every node by name.
    pub fn rows(&self, now_ns: u64) -> Vec<NodeRow<'_>> {
        self.nodes
            .iter()
            .map(|(name, e)| NodeRow {
                name,
                state: Self::state_of(e, now_ns),
                status: e.status.as_ref(),
                status_age_ns: e.status_at_ns.map(|at| now_ns.saturating_sub(at)),
            })
            .collect()
    }

    /// The latest status of node `name`.
    pub fn status(&self, name: &str) -> Option<&NodeStatusMessage> {
        self.nodes.get(name)?.status.as_ref()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const S: u64 = 1_000_000_000;

    fn status(node: &str) -> NodeStatusMessage {
        NodeStatusMessage::new(node, "fit", 7)
    }

    #[test]
    fn a_node_starts_lives_and_goes_with_its_token() {
        let mut h = NodeHealth::default();
        h.on_token("fit", true);
        assert_eq!(h.state("fit", 0), Some(NodeState::Starting));
        h.on_status(status("fit"), S);
        assert_eq!(h.state("fit", S), Some(NodeState::Alive));
        h.on_token("fit", false);
        assert_eq!(h.state("fit", S), Some(NodeState::Gone));
        // Its final status does not revive it.
        h.on_status(status("fit"), S + 1);
        assert_eq!(h.state("fit", S + 2), Some(NodeState::Gone));
        assert!(h.status("fit").is_some());
        // A restart declares a new token.
        h.on_token("fit", true);
        assert_eq!(h.state("fit", S + 3), Some(NodeState::Starting));
        assert_eq!(h.state("nobody", 0), None);
    }

    #[test]
    fn a_node_that_stops_reporting_turns_silent_after_its_own_periods() {
        let mut h = NodeHealth::default();
        h.on_token("fit", true);
        for k in 0..4 {
            h.on_status(status("fit"), k * S / 2);
        }
        // Period 0.5 s: silent after 1.25 s without a status.
        let last = 3 * S / 2;
        assert_eq!(h.state("fit", last + S), Some(NodeState::Alive));
        assert_eq!(h.state("fit", last + 13 * S / 10), Some(NodeState::Silent));
        // Statuses without any token (a graph without liveliness) still count.
        h.on_status(status("solo"), 0);
        assert_eq!(h.state("solo", S), Some(NodeState::Alive));
        assert_eq!(h.state("solo", 3 * S), Some(NodeState::Silent));
        let rows = h.rows(3 * S);
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[1].name, "solo");
        assert_eq!(rows[1].status_age_ns, Some(3 * S));
    }
}
