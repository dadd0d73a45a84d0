//! How an emulated Benewake rangefinder is configured.

use crate::device::Faults;

/// Options of a [`BenewakeEmulator`](super::BenewakeEmulator).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenewakeOptions {
    /// `corrupt_every` = n: every n-th data frame carries a wrong checksum
    /// (string-format frames have none to break); `garbage_every` = n: 1–16
    /// random bytes go out before every n-th data frame, drawn from
    /// `faults.seed`.
    pub faults: Faults,
    /// Seed of the range and strength noise. Default 0.
    pub seed: u64,
    /// Standard deviation of the range noise, as a fraction of the range
    /// (of 1 m below 1 m). Default 0.01.
    pub noise: f64,
    /// Chip temperature reported in the frames, °C. Default 40.
    pub temperature_c: f64,
}

impl Default for BenewakeOptions {
    fn default() -> Self {
        Self {
            faults: Faults::default(),
            seed: 0,
            noise: 0.01,
            temperature_c: 40.0,
        }
    }
}
