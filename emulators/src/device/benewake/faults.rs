//! Decides which data frames the emulated rangefinder damages and where it
//! sends bursts of garbage, per [`Faults`].

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use crate::device::Faults;

/// Longest garbage burst, in bytes.
const MAX_GARBAGE: usize = 16;

pub(crate) struct FrameFaults {
    faults: Faults,
    frames: u64,
    rng: Pcg64,
}

impl FrameFaults {
    pub(crate) fn new(faults: Faults) -> Self {
        Self {
            faults,
            frames: 0,
            rng: Pcg64::seed_from_u64(faults.seed),
        }
    }

    /// Counts one more data frame (the first is frame 1); returns the
    /// garbage to send before it (empty when none) and whether to break its
    /// checksum. Frame n gets garbage when n is a multiple of
    /// `garbage_every`, a broken checksum when a multiple of `corrupt_every`.
    pub(crate) fn next_frame(&mut self) -> (Vec<u8>, bool) {
        self.frames = self.frames.wrapping_add(1);
        let garbage = if nth(self.frames, self.faults.garbage_every) {
            let len = self.rng.random_range(1..=MAX_GARBAGE);
            (0..len).map(|_| self.rng.random::<u8>()).collect()
        } else {
            Vec::new()
        };
        (garbage, nth(self.frames, self.faults.corrupt_every))
    }
}

fn nth(count: u64, every: u64) -> bool {
    every != 0 && count.is_multiple_of(every)
}
