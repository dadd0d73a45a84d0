//! The host's time, as the node that owns a port reads it and hands it to a
//! driver: one monotonic reading for timeouts and ages, one wall-clock reading
//! for stamps, taken together.

/// Host time at one instant. Drivers never read a clock: the node passes this
/// with every call.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct HostTime {
    /// A monotonic clock (never jumps), nanoseconds from an arbitrary origin.
    /// Timeouts and ages are measured on it.
    pub monotonic_ns: u64,
    /// The wall clock, nanoseconds since the Unix epoch. Stamps are on it.
    pub unix_ns: u64,
}

impl HostTime {
    pub const fn new(monotonic_ns: u64, unix_ns: u64) -> Self {
        Self {
            monotonic_ns,
            unix_ns,
        }
    }

    /// Nanoseconds of monotonic time from `earlier` to `self` (0 if `earlier`
    /// is later).
    pub fn since(&self, earlier: HostTime) -> u64 {
        self.monotonic_ns.saturating_sub(earlier.monotonic_ns)
    }

    /// This instant moved `ns` later on both clocks (for tests and timeouts).
    pub fn plus_ns(&self, ns: u64) -> Self {
        Self::new(
            self.monotonic_ns.saturating_add(ns),
            self.unix_ns.saturating_add(ns),
        )
    }
}

/// When the bytes of one read of a port became readable on the host: what a
/// node can tell a driver about a reading's lateness when the device sends
/// no time of its own.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ReadWindow {
    /// When the port's previous read was called. That read took every byte
    /// readable then (or found none), so this read's bytes became readable
    /// later. `None` when no such read is known: the first read after the
    /// port opened, or a previous read that filled its buffer (and may have
    /// left older bytes behind).
    pub after: Option<HostTime>,
    /// When this read returned: its bytes were readable by then.
    pub returned: HostTime,
}

impl ReadWindow {
    /// A read known only by when it returned.
    pub const fn returned_at(returned: HostTime) -> Self {
        Self {
            after: None,
            returned,
        }
    }
}
