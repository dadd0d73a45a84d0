//! A sample as it reached this node: its key and payload, when its publisher
//! stamped it (the publisher's wall clock) and when it arrived and was taken
//! up (this node's clocks).

use crate::transport::{monotonic_ns, sample_published_ns, unix_ns};
use zenoh::bytes::ZBytes;

pub struct Arrival {
    pub key: String,
    pub payload: ZBytes,
    /// The sample's zenoh timestamp: when it was published, on the
    /// publisher's wall clock (ns since the Unix epoch); `None` when the
    /// sample carries none.
    pub published_ns: Option<u64>,
    /// This node's wall clock when the sample arrived (ns since the epoch),
    /// comparable with `published_ns` within the hosts' clock offset.
    pub received_wall_ns: u64,
    /// This node's monotonic clock ([`monotonic_ns`]) when it arrived.
    pub received_ns: u64,
    /// The monotonic clock when the node took it up (from its queue; for a
    /// callback, on arrival).
    pub taken_ns: u64,
}

/// Why a sample is refused before it is read: shroud publishes on exact
/// keys only, so a put on a wildcard key (`shroud/demo/collision/*`), which
/// zenoh delivers to every subscriber it intersects, is a forgery or a
/// mistake, never a message of the stream subscribed to.
pub(super) fn refused(sample: &zenoh::sample::Sample) -> Option<&'static str> {
    // `*`, `**` and `$*` are zenoh's wildcards; no concrete key holds a `*`.
    (sample.key_expr().as_str().contains('*'))
        .then_some("published on a wildcard key, not on the stream's own")
}

impl Arrival {
    /// Read in zenoh's callback, before anything else, so that the times are
    /// those of the arrival.
    pub(super) fn of(sample: &zenoh::sample::Sample) -> Self {
        let (received_ns, received_wall_ns) = (monotonic_ns(), unix_ns());
        Self {
            key: sample.key_expr().to_string(),
            payload: sample.payload().clone(),
            published_ns: sample_published_ns(sample),
            received_wall_ns,
            received_ns,
            taken_ns: received_ns,
        }
    }

    /// How long it has been here, on this node's monotonic clock.
    pub fn held_ns(&self) -> u64 {
        monotonic_ns().saturating_sub(self.received_ns)
    }

    /// How long it waited in the node's queue.
    pub fn queued_ns(&self) -> u64 {
        self.taken_ns.saturating_sub(self.received_ns)
    }
}
