//! Decides which answer packets the emulated RPLIDAR damages and where it
//! sends bursts of garbage, per [`Faults`].

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use crate::device::Faults;

/// Longest garbage burst, in bytes.
const MAX_GARBAGE: usize = 16;

/// What to do to the next answer packet.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub(crate) struct PacketFaults {
    /// Random bytes to send before the packet (empty = none).
    pub garbage: Vec<u8>,
    /// Damage the packet's checksum or check bit.
    pub corrupt: bool,
}

pub(crate) struct FaultInjector {
    faults: Faults,
    packets: u64,
    rng: Pcg64,
}

impl FaultInjector {
    pub(crate) fn new(faults: Faults) -> Self {
        Self {
            faults,
            packets: 0,
            rng: Pcg64::seed_from_u64(faults.seed),
        }
    }

    /// Counts one more answer packet (the first is packet 1) and says what
    /// happens to it: packet n is corrupted when n is a multiple of
    /// `corrupt_every`, preceded by garbage when a multiple of
    /// `garbage_every`.
    pub(crate) fn next_packet(&mut self) -> PacketFaults {
        self.packets = self.packets.wrapping_add(1);
        let garbage = if is_nth(self.packets, self.faults.garbage_every) {
            let len = self.rng.random_range(1..=MAX_GARBAGE);
            (0..len).map(|_| self.rng.random::<u8>()).collect()
        } else {
            Vec::new()
        };
        PacketFaults {
            garbage,
            corrupt: is_nth(self.packets, self.faults.corrupt_every),
        }
    }
}

fn is_nth(count: u64, every: u64) -> bool {
    every != 0 && count.is_multiple_of(every)
}
