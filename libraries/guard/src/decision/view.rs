//! One view: the latest surrogate of one stream, when it reached the guard, and
//! how old its data was then.

use super::policy::GuardPolicy;
use crate::Envelope;
use shroud_msg::{check_stamp_skew, ClockAhead, StampSkew};

/// A certified surrogate as the guard takes it in.
#[derive(Debug, Clone)]
pub struct SurrogateInput {
    pub envelope: Envelope,
    /// The source cloud's stamp (the device's word: checked for skew, kept
    /// for the record) and sequence.
    pub stamp_ns: u64,
    pub sequence: u64,
    /// Time the data had spent in shroud nodes before the surrogate was
    /// published, as they measured it on their own clocks (their transit
    /// between nodes included).
    pub pipeline_ns: u64,
    /// When the fit node published it, on its wall clock (nanoseconds since
    /// the Unix epoch: the zenoh timestamp of the sample). The time from there
    /// to the guard's callback, the transit and any queueing or freezing of
    /// the guard before the callback ran, counts toward the age.
    pub published_ns: u64,
    /// Bound on how far any point of the source cloud may lie from where the
    /// sensor placed it (metres, finite and `>= 0`; a panning sensor's timing
    /// uncertainty, say): every clearance shrinks by it.
    pub position_error: f64,
}

/// Why a surrogate was not taken.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SurrogateRejected {
    /// Its source stamp is further from the guard's wall clock than the
    /// policy allows.
    #[error("source {0}: not trusted")]
    ClockSkew(StampSkew),
    /// It was published later, by the guard's wall clock, than the guard
    /// received it, by more than the clock offset the policy allows: the
    /// clocks disagree more than configured, so its transit is unknown.
    #[error("{0}")]
    ClockOffset(ClockAhead),
    /// Its position error is not a finite distance `>= 0`.
    #[error("position error {0} m is not a finite distance >= 0")]
    BadPositionError(f64),
    /// No such view.
    #[error("no view {0}")]
    UnknownView(usize),
}

impl SurrogateRejected {
    /// The status counter this fault is counted under.
    pub fn counter(&self) -> &'static str {
        match self {
            Self::ClockSkew(_) => "clock_skew",
            Self::ClockOffset(_) => "clock_offset",
            Self::BadPositionError(_) => "bad_position_error",
            Self::UnknownView(_) => "unknown_view",
        }
    }
}

/// The latest surrogate of a view and its arrival on the guard's clock.
#[derive(Debug, Clone)]
pub(super) struct HeldSurrogate {
    pub input: SurrogateInput,
    /// On the guard's monotonic clock.
    pub arrived_ns: u64,
    /// Its transit to the guard as counted: measured, never below 0, plus
    /// the allowed clock offset.
    pub transit_ns: u64,
}

impl HeldSurrogate {
    /// Age of the data at `now_ns`: the upstream pipeline delay, the transit
    /// to the guard, and the time since it arrived.
    pub fn age_ns(&self, now_ns: u64) -> u64 {
        now_ns
            .saturating_sub(self.arrived_ns)
            .saturating_add(self.transit_ns)
            .saturating_add(self.input.pipeline_ns)
    }
}

/// Checks a surrogate's source stamp against the guard's wall clock.
pub(super) fn check_skew(
    stamp_ns: u64,
    wall_ns: u64,
    policy: &GuardPolicy,
) -> Result<(), SurrogateRejected> {
    check_stamp_skew(stamp_ns, wall_ns, policy.max_skew_ns).map_err(SurrogateRejected::ClockSkew)
}
