//! Why an arm, a trajectory, a guard configuration or an envelope was refused.
//! Every input may come from a file or the network, so nothing is assumed.

use shroud_surrogate::query::QueryError;
use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum GuardError {
    #[error("arm file: {0}")]
    Toml(String),
    #[error("{0}")]
    FieldOfView(String),
    #[error("{0}")]
    NoReturn(String),
    #[error("URDF: {0}")]
    Urdf(String),
    #[error("{what} must be finite, got {value}")]
    NonFinite { what: String, value: f64 },
    #[error("{what}: the radius must be finite and > 0, got {radius}")]
    BadRadius { what: String, radius: f64 },
    #[error("joint '{joint}': the axis must be finite and non-zero, got {axis:?}")]
    BadAxis { joint: String, axis: [f64; 3] },
    #[error("joint '{joint}': limits must be finite with lower <= upper, got [{lower}, {upper}]")]
    BadLimits {
        joint: String,
        lower: f64,
        upper: f64,
    },
    #[error("joint '{0}': a fixed joint takes no limits")]
    FixedWithLimits(String),
    #[error("two {kind}s are named '{name}'")]
    DuplicateName { kind: &'static str, name: String },
    #[error("{kind} name must not be empty")]
    EmptyName { kind: &'static str },
    #[error("a serial chain of {joints} joints needs {} links, got {links}", joints + 1)]
    LinkCount { links: usize, joints: usize },
    #[error("joint '{joint}' names {role} '{found}' but the chain has '{expected}' there")]
    ChainMismatch {
        joint: String,
        role: &'static str,
        expected: String,
        found: String,
    },
    #[error("expected {expected} joint values (one per non-fixed joint), got {got}")]
    JointCount { expected: usize, got: usize },
    #[error("joint value {index} must be finite, got {value}")]
    NonFiniteJoint { index: usize, value: f64 },
    #[error("a trajectory needs at least one waypoint")]
    EmptyTrajectory,
    #[error("waypoint {index}: the duration must be finite and > 0, got {duration}")]
    BadDuration { index: usize, duration: f64 },
    #[error("waypoint {index} has {got} joint values, expected {expected}")]
    WaypointLength {
        index: usize,
        expected: usize,
        got: usize,
    },
    #[error("waypoint {index}: joint {joint} = {value} is outside its limits [{lower}, {upper}]")]
    OutsideLimits {
        index: usize,
        joint: usize,
        value: f64,
        lower: f64,
        upper: f64,
    },
    /// A verdict consumer asked to move longer on a verdict than the guard
    /// accounts for.
    #[error("a deadline of {deadline} s exceeds the guard's horizon of {horizon} s")]
    DeadlineBeyondHorizon { deadline: f64, horizon: f64 },
    /// A deadline of 0 (a horizon of 0, say): the consumer could never move.
    #[error(
        "a deadline of {deadline} s (under 1 ns) leaves no time to move on a clear verdict \
         (the guard's horizon, the arm file's [guard] horizon, is {horizon} s)"
    )]
    NoTimeToMove { deadline: f64, horizon: f64 },
    #[error("the time must be finite, got {0}")]
    BadTime(f64),
    #[error("guard config: {0}")]
    BadConfig(String),
    #[error("shape {index} (link {link}) has a non-finite coordinate or a bad radius")]
    BadShape { index: usize, link: usize },
    #[error("shape {index} names link {link} but the arm has {links} links")]
    ShapeLink {
        index: usize,
        link: usize,
        links: usize,
    },
    #[error("surrogate: {0}")]
    Surrogate(#[from] QueryError),
    /// Speed monitoring needs the joint state's age, and it cannot be told.
    #[error("joint state timing: {0}")]
    JointStateTiming(String),
}
