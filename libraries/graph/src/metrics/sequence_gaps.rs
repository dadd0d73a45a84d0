//! Messages a subscriber never saw: each publisher numbers its messages, so a
//! jump in a source's sequence counts the messages missing between (dropped
//! on the way, or by the subscriber's own backlog policy before it decoded
//! them). A sequence that goes back is a new publisher (a restart), not a gap.

use std::collections::BTreeMap;

/// Most sources tracked; beyond it the oldest-named is forgotten (a stream
/// has one publisher, a few over restarts: the bound only stops a flood of
/// forged source names from growing the map).
const MAX_SOURCES: usize = 64;

#[derive(Debug, Clone, Default)]
pub struct SequenceGaps {
    last: BTreeMap<String, u64>,
    missing: u64,
}

impl SequenceGaps {
    /// Message `sequence` of `source` arrived; returns how many before it were
    /// never seen.
    pub fn observe(&mut self, source: &str, sequence: u64) -> u64 {
        let gap = match self.last.get(source) {
            Some(&last) if sequence > last => sequence - last - 1,
            _ => 0,
        };
        if !self.last.contains_key(source) && self.last.len() >= MAX_SOURCES {
            self.last.pop_first();
        }
        self.last.insert(source.to_string(), sequence);
        self.missing += gap;
        gap
    }

    /// Messages missing since creation.
    pub fn missing(&self) -> u64 {
        self.missing
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jumps_count_what_is_missing_and_restarts_do_not() {
        let mut g = SequenceGaps::default();
        assert_eq!(g.observe("a", 0), 0);
        assert_eq!(g.observe("a", 1), 0);
        assert_eq!(g.observe("a", 4), 2);
        assert_eq!(g.observe("b", 10), 0);
        assert_eq!(g.observe("a", 0), 0); // a restarted publisher
        assert_eq!(g.observe("a", 2), 1);
        assert_eq!(g.observe("a", 2), 0); // a repeat is no gap
        assert_eq!(g.missing(), 3);
        for i in 0..200 {
            g.observe(&format!("s{i}"), 5);
        }
        assert!(g.last.len() <= MAX_SOURCES);
    }
}
