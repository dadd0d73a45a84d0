//! How many scans make one cloud: a sweep of a moving mount, a number of
//! scans, or a window of time.

use super::error::AssemblyError;
use std::str::FromStr;

/// When a cloud is complete.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CloudWindow {
    /// One sweep of the mount (needs a moving mount).
    Sweep,
    /// Every `n` scans (1: each scan is its own cloud).
    Scans(u32),
    /// Rays whose time falls in the same window of this many nanoseconds
    /// (windows aligned on the Unix epoch).
    Time(u64),
}

impl FromStr for CloudWindow {
    type Err = AssemblyError;

    /// `sweep`, `scans:N` or `time:SECONDS`.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let bad = |reason: &str| AssemblyError::parse("cloud window", text, reason);
        match text.split_once(':') {
            None if text == "sweep" => Ok(Self::Sweep),
            Some(("scans", n)) => match n.parse::<u32>() {
                Ok(n) if (1..=100_000).contains(&n) => Ok(Self::Scans(n)),
                _ => Err(bad("scans:N needs N in 1..=100000")),
            },
            Some(("time", s)) => match s.parse::<f64>() {
                Ok(s) if (1e-3..=3600.0).contains(&s) => Ok(Self::Time((s * 1e9).round() as u64)),
                _ => Err(bad("time:SECONDS needs 0.001 to 3600 seconds")),
            },
            _ => Err(bad("expected sweep, scans:N or time:SECONDS")),
        }
    }
}
