//! The guard's decision, as a plain state machine: which surrogates (views) are
//! fresh on the guard's own clock, how far an obstacle may have moved since
//! each was measured, which view vouches for each shape, and what to say.
//!
//! [`CollisionGuard`] holds the latest surrogate of each view. Time is an
//! argument: nanoseconds on the caller's monotonic clock for ages, and the
//! caller's wall clock for the transit from the fit node (against the
//! publication stamp, within [`GuardPolicy::max_clock_offset_ns`]) and to spot
//! a device stamp that is far off ([`GuardPolicy::max_skew_ns`]). No decision
//! rests on a device's stamp.
//!
//! What the decision assumes (and what remains for the deployment to ensure):
//! - a view saw the space above (along its direction) every kept triangle of
//!   its domain: its sensor looked along the view's direction from outside
//!   the scene, and nothing it did not measure hides inside a kept triangle (a
//!   black object that returned no range, an occluded pocket smaller than a
//!   triangle, a thin object between rays). When the cloud states its
//!   sensor's field of view, space outside it counts as unseen
//!   (`guard::field_of_view`), so the assumption is needed only inside it;
//!   when it lists its rays without a return, their cones count as unseen
//!   (`guard::no_return`), so a black object is covered wherever its image
//!   holds a 2 x 2 block of rays. Space behind an object as seen from an
//!   oblique sensor is still taken as seen;
//! - obstacles move no faster than [`GuardConfig::max_obstacle_speed`];
//! - the consumer moves on a verdict no longer than
//!   [`GuardConfig::horizon`] after sending the joint state it answers (its
//!   deadman's deadline); with speed monitoring
//!   ([`CollisionGuard::with_speed_monitor`]) the arm's own motion until it
//!   has stopped is bounded from its `[motion]` table (`crate::separation`),
//!   and the arm obeys the scale within its reaction time; without it, that
//!   motion must be covered by the stop distance;
//! - the hosts' wall clocks agree within the policy's clock offset bound.

mod combine;
mod decider;
mod policy;
mod speed;
mod speed_control;
mod view;

#[cfg(test)]
mod tests;

pub use decider::{CollisionGuard, Decision, SurrogateRecord};
pub use policy::{GuardPolicy, UnobservedPolicy};
pub use speed::JointMotionSample;
pub use view::{SurrogateInput, SurrogateRejected};
