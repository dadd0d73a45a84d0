//! Counting what nodes did with the messages they were sent: their counters
//! once idle, and the change of each since then.

use crate::common::status_board::StatusBoard;
use crate::common::unix_ns;
use crate::RECOVERY;
use shroud_msg::NodeStatusMessage;
use std::collections::HashMap;
use std::time::Instant;

/// The counters that account for the messages a node was sent.
pub const ACCOUNTS: [&str; 3] = ["received", "dropped_backlog", "dropped_malformed"];

/// Statuses of `nodes` once their [`ACCOUNTS`] stopped moving: each published
/// at least 0.3 s after the previous one with the same values.
pub fn settled(board: &StatusBoard, nodes: &[&str]) -> HashMap<String, NodeStatusMessage> {
    let values = |s: &NodeStatusMessage| ACCOUNTS.map(|c| s.counter(c));
    nodes
        .iter()
        .map(|&node| {
            let deadline = Instant::now() + RECOVERY;
            let mut last = board.published_after(node, unix_ns());
            loop {
                let next = board.published_after(node, last.stamp_ns + 300_000_000);
                if values(&next) == values(&last) {
                    return (node.to_string(), next);
                }
                assert!(Instant::now() < deadline, "{node} never settled: {next:?}");
                last = next;
            }
        })
        .collect()
}

/// Counters of a node since `before`.
pub struct Delta<'a> {
    pub before: &'a NodeStatusMessage,
    pub now: NodeStatusMessage,
}

impl Delta<'_> {
    pub fn of(&self, counter: &str) -> u64 {
        self.now.counter(counter) - self.before.counter(counter)
    }

    pub fn sum(&self, counters: &[&str]) -> u64 {
        counters.iter().map(|c| self.of(c)).sum()
    }
}

/// Waits until the counters of `node` since `before` satisfy `done`.
pub fn wait_delta<'a>(
    board: &StatusBoard,
    node: &str,
    before: &'a NodeStatusMessage,
    what: &str,
    done: impl Fn(&Delta) -> bool,
) -> Delta<'a> {
    let now = board.wait_for(node, what, RECOVERY, |s| {
        done(&Delta {
            before,
            now: s.clone(),
        })
    });
    Delta { before, now }
}
