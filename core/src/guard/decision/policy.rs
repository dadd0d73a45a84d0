//! What the guard tolerates: surrogate age and stamp skew, and what to do
//! about space no surrogate covers. (The obstacle speed bound is part of
//! [`GuardConfig`](crate::guard::GuardConfig), so that arm files can set it.)

use crate::guard::GuardError;
use serde::{Deserialize, Serialize};

/// What to do when a link reaches outside every fresh surrogate's domain.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum UnobservedPolicy {
    /// Stop (verdict `unobserved`): space the sensors never saw may hold anything.
    #[default]
    Stop,
    /// Judge by the observed space alone (for scenes known to be empty
    /// outside the sensors' view, such as the simulator's); still flagged per link.
    Ignore,
}

/// The guard's tolerances. Ages are on the guard's clock plus the pipeline
/// delay carried in the messages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuardPolicy {
    /// A surrogate older than this vouches for nothing.
    pub max_age_ns: u64,
    /// A surrogate whose source stamp is further than this from the guard's
    /// wall clock is refused as a fault (`u64::MAX`: no check).
    pub max_skew_ns: u64,
    pub unobserved: UnobservedPolicy,
}

impl Default for GuardPolicy {
    fn default() -> Self {
        Self {
            max_age_ns: 1_000_000_000,
            max_skew_ns: crate::message::DEFAULT_MAX_SKEW_NS,
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
