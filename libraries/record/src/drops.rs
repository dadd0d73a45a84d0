//! What a recorder drops and why: per topic and cause counts, and the
//! free-space reserve below which it stops writing (a full disk must end the
//! file cleanly, never leave it half-written).

use std::collections::BTreeMap;
use std::fmt;

/// Why a message was not written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum DropCause {
    /// The writer's queue was full (a slow disk): the newest message is dropped.
    QueueFull,
    /// Free space fell below the reserve: the file was finished and nothing
    /// more is written.
    DiskFull,
    /// Writing failed (an I/O error): the recording stopped.
    WriteError,
}

impl DropCause {
    pub const ALL: [DropCause; 3] = [Self::QueueFull, Self::DiskFull, Self::WriteError];

    /// The status counter's name: `dropped_queue_full`...
    pub fn counter(self) -> &'static str {
        match self {
            Self::QueueFull => "dropped_queue_full",
            Self::DiskFull => "dropped_disk_full",
            Self::WriteError => "dropped_write_error",
        }
    }
}

impl fmt::Display for DropCause {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::QueueFull => "queue full",
            Self::DiskFull => "disk full",
            Self::WriteError => "write error",
        })
    }
}

/// Drops by topic and cause.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct DropCounts {
    counts: BTreeMap<(String, DropCause), u64>,
}

impl DropCounts {
    pub fn add(&mut self, topic: &str, cause: DropCause) {
        *self.counts.entry((topic.to_owned(), cause)).or_insert(0) += 1;
    }

    pub fn total(&self) -> u64 {
        self.counts.values().sum()
    }

    pub fn of_cause(&self, cause: DropCause) -> u64 {
        self.counts
            .iter()
            .filter(|((_, c), _)| *c == cause)
            .map(|(_, n)| n)
            .sum()
    }

    /// `(topic, cause, count)`, by topic then cause.
    pub fn iter(&self) -> impl Iterator<Item = (&str, DropCause, u64)> {
        self.counts.iter().map(|((t, c), n)| (t.as_str(), *c, *n))
    }
}

/// The free space a recorder leaves on its disk: it starts a chunk only when
/// the disk has room for the chunk and the reserve (which also holds the
/// file's summary and footer, written when it ends).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DiskReserve {
    pub reserve_bytes: u64,
}

impl DiskReserve {
    /// Whether a chunk of up to `chunk_bytes` may be started with
    /// `free_bytes` available.
    pub fn admits(&self, free_bytes: u64, chunk_bytes: u64) -> bool {
        self.reserve_bytes
            .checked_add(chunk_bytes)
            .is_some_and(|needed| free_bytes >= needed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_by_topic_and_cause() {
        let mut d = DropCounts::default();
        d.add("shroud/demo/cloud/a", DropCause::QueueFull);
        d.add("shroud/demo/cloud/a", DropCause::QueueFull);
        d.add("shroud/demo/status/fit", DropCause::DiskFull);
        assert_eq!(d.total(), 3);
        assert_eq!(d.of_cause(DropCause::QueueFull), 2);
        assert_eq!(d.of_cause(DropCause::WriteError), 0);
        let rows: Vec<_> = d.iter().collect();
        assert_eq!(rows[0], ("shroud/demo/cloud/a", DropCause::QueueFull, 2));
    }

    #[test]
    fn the_reserve_and_the_chunk_must_fit() {
        let r = DiskReserve { reserve_bytes: 100 };
        assert!(r.admits(150, 50));
        assert!(!r.admits(149, 50));
        assert!(!r.admits(0, 0));
        let none = DiskReserve { reserve_bytes: 0 };
        assert!(none.admits(0, 0));
        assert!(!DiskReserve {
            reserve_bytes: u64::MAX
        }
        .admits(u64::MAX, 1));
    }
}
