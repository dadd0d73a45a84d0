//! What a guard keeps for speed monitoring: the arm's bound and the scales
//! it published.

use crate::{ScaleGovernor, SpeedMonitor};

/// A guard's speed monitoring: the arm's bound and its published scales.
#[derive(Debug, Clone)]
pub(super) struct SpeedControl {
    pub(super) monitor: SpeedMonitor,
    pub(super) governor: ScaleGovernor,
}
