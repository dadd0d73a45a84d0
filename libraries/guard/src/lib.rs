//! Conservative collision envelopes for a manipulator against a surrogate sandwich.
//!
//! - [`ArmModel`]: a serial chain of links with sphere and capsule collision
//!   shapes, parsed from TOML ([`ArmModel::from_toml_str`], schema in `schema`)
//!   and validated; [`ArmModel::forward`] gives every link's world pose and the
//!   shapes in the world ([`ArmPose`]).
//! - URDF import of serial arms ([`ArmModel::from_urdf_str`]): collision
//!   spheres, cylinders (as capsules) and boxes (as spheres).
//! - [`Trajectory`]: joint-space waypoints with cosine-eased moves, for a
//!   simulated arm.
//! - [`Envelope`]: built once per surrogate; per kept cell a padded box that
//!   holds every certified point of the cell (sandwich, upper-only: everything
//!   below, lower-only: everything above), plus the Bézier patches refinement
//!   subdivides.
//! - [`check_arm`] / [`check_shapes`]: per shape a *lower bound* on the distance
//!   to the cloud (0 when they may touch), per link the minimum, and `stop`
//!   below [`GuardConfig::stop_distance`].
//!
//! - [`CollisionGuard`]: the decision as a state machine over several views
//!   (surrogate streams): freshness on the guard's own clock, stamp skew,
//!   motion allowance, unobserved space ([`GuardPolicy`]).
//! - [`Deadman`]: a verdict consumer's rule for when it may move, and
//!   [`ResumeAfter`]: its wait-and-resume after a halt.
//! - [`VerdictWatch`]: what a display shows: the latest verdict while fresh,
//!   `no-verdict` once the guard is silent.
//!
//! A surrogate vouches only for what its sensor saw: space outside its domain
//! and over trimmed-away triangles (which hold no points) counts as possibly
//! occupied at every height ([`ShapeClearance::unseen`]), and so does space
//! outside the cloud's stated field of view and along its stated rays without
//! a return ([`Envelope::with_field_of_view`], [`Envelope::with_no_return`]);
//! a shape whose bound is set by such space in every view is
//! [`ShapeClearance::unobserved`].
// `!(x > 0.0)` deliberately rejects NaN as well, which `x <= 0.0` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod arm;
mod clearance;
mod config;
mod dark_groups;
mod deadman;
mod decision;
mod envelope;
mod error;
mod field_of_view;
mod joint;
mod kinematics;
mod no_return;
mod probe;
mod report;
mod resume;
mod schema;
mod separation;
mod shape;
mod trajectory;
mod trimmed;
mod unseen;
mod urdf;
mod verdict_watch;
mod xml;

#[cfg(test)]
mod tests;

pub use arm::{ArmModel, Link};
pub use config::{GuardConfig, MAX_HORIZON, MAX_REFINE_DEPTH};
pub use deadman::{Deadman, Motion, VerdictUse};
pub use decision::{
    CollisionGuard, Decision, GuardPolicy, JointMotionSample, SurrogateInput, SurrogateRecord,
    SurrogateRejected, UnobservedPolicy,
};
pub use envelope::{CellBox, Envelope};
pub use error::GuardError;
pub use field_of_view::depth_inside;
pub use joint::{origin_from_xyz_rpy, Joint, JointKind, Limits};
pub use kinematics::ArmPose;
pub use report::{check_arm, check_shapes, GuardReport, ShapeClearance};
pub use resume::ResumeAfter;
pub use schema::ArmFile;
pub use separation::{
    protective, ArmMotion, JointMotion, LeverArms, MotionNow, OverLimit, Protective, ScaleGovernor,
    SpeedMonitor, SpeedScale, Stop, StopSample, StoppingModel, Timing, OVER_LIMIT_TOLERANCE,
};
pub use shape::{Capsule, Shape, Sphere, WorldShape};
pub use trajectory::{Trajectory, Waypoint};
pub use verdict_watch::{ShownVerdict, VerdictWatch};
