//! What the guard tolerates: surrogate age and stamp skew, and what to do
//! about space no surrogate covers. (The obstacle speed bound is part of
//! [`GuardConfig`](crate::GuardConfig), so that arm files can set it.)

use crate::GuardError;
use serde::{Deserialize, Serialize};

/// What to do when a link reaches outside every fresh surrogate's domain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum UnobservedPolicy {
    /// Stop (verdict `unobserved`): space the sensors never saw may hold
    /// anything, so it counts as occupied.
    #[default]
    Stop,
    /// Judge by the occupied space seen alone, as if the sensors had seen
    /// everything (only for scenes known to be empty where they did not
    /// look, and only with whole views of one cloud: never with sectors,
    /// which say nothing outside their cones); still flagged per link.
    Ignore,
}

/// The guard's tolerances. Ages are the pipeline delay carried in the
/// messages, the transit to the guard (wall clocks, within the clock offset
/// bound), and the time since arrival on the guard's monotonic clock.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuardPolicy {
    /// A surrogate older than this vouches for nothing.
    pub max_age_ns: u64,
    /// A surrogate whose source stamp is further than this from the guard's
    /// wall clock is refused as a fault (`u64::MAX`: no check).
    pub max_skew_ns: u64,
    /// Bound on how far the fit node's wall clock and the guard's may
    /// disagree: added to every measured transit, and a surrogate that seems
    /// to come from further in the future is refused. On one host the clocks
    /// are one; across hosts, the synchronisation's bound (PTP, NTP).
    pub max_clock_offset_ns: u64,
    pub unobserved: UnobservedPolicy,
}

impl Default for GuardPolicy {
    fn default() -> Self {
        Self {
            max_age_ns: 1_000_000_000,
            max_skew_ns: shroud_msg::DEFAULT_MAX_SKEW_NS,
            max_clock_offset_ns: shroud_msg::DEFAULT_MAX_CLOCK_OFFSET_NS,
            unobserved: UnobservedPolicy::Stop,
        }
    }
}

impl GuardPolicy {
    pub fn validate(&self) -> Result<(), GuardError> {
        if self.max_age_ns == 0 {
            return Err(GuardError::BadConfig("max_age must be positive".into()));
        }
        Ok(())
    }
}
