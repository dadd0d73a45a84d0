//! Injected misbehaviour: a wrong sum on one data line of every n-th scan,
//! and a burst of random bytes before every n-th scan.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use crate::device::Faults;

/// Longest garbage burst.
const MAX_GARBAGE: usize = 32;

/// What to do to one scan message.
#[derive(Debug, Default)]
pub(crate) struct ScanFaults {
    /// Random bytes to send before the scan.
    pub(crate) garbage: Vec<u8>,
    /// The data line (0-based) whose sum to corrupt.
    pub(crate) corrupt_line: Option<usize>,
}

pub(crate) struct FaultInjector {
    faults: Faults,
    rng: Pcg64,
}

impl FaultInjector {
    pub(crate) fn new(faults: Faults) -> Self {
        FaultInjector {
            faults,
            rng: Pcg64::seed_from_u64(faults.seed),
        }
    }

    /// The faults of scan number `scan` (1-based, counting every scan sent)
    /// whose payload takes `data_lines` lines.
    pub(crate) fn for_scan(&mut self, scan: u64, data_lines: usize) -> ScanFaults {
        let due = |every: u64| every != 0 && scan.is_multiple_of(every);
        let mut faults = ScanFaults::default();
        if due(self.faults.garbage_every) {
            let len = self.rng.random_range(1..=MAX_GARBAGE);
            faults.garbage = (0..len).map(|_| self.rng.random::<u8>()).collect();
        }
        if due(self.faults.corrupt_every) && data_lines > 0 {
            faults.corrupt_line = Some(self.rng.random_range(0..data_lines));
        }
        faults
    }
}
