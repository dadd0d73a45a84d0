//! The guard's decision, as a plain state machine: which surrogates (views) are
//! fresh on the guard's own clock, how far an obstacle may have moved since
//! each was measured, which view vouches for each shape, and what to say.
//!
//! [`CollisionGuard`] holds the latest surrogate of each view. Time is an
//! argument: nanoseconds on the caller's monotonic clock for ages, and the
//! caller's wall clock only to spot a device stamp that is far off
//! ([`GuardPolicy::max_skew_ns`]). No decision rests on a device's stamp.

mod combine;
mod decider;
mod policy;
mod view;

#[cfg(test)]
mod tests;

pub use decider::{CollisionGuard, Decision, SurrogateRecord};
pub use policy::{GuardPolicy, UnobservedPolicy};
pub use view::{SurrogateInput, SurrogateRejected};
