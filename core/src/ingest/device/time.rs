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
