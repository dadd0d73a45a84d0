//! Speed and separation monitoring (ISO/TS 15066, 5.5.4): instead of only
//! halting, the guard scales the arm's speed so that every link's certified
//! clearance stays at least the protective separation distance `S_p` at that
//! speed.
//!
//! - [`StoppingModel`]: how far and how long a joint takes to stop;
//! - [`ArmMotion`]: velocity limits, stopping models, reaction time and
//!   position uncertainty (an arm file's `[motion]` table);
//! - [`LeverArms`]: how fast each link can move per unit of each joint's
//!   speed, in any pose;
//! - [`protective`]: `S_p - C` of one link at one scale, term by term;
//! - [`SpeedMonitor`]: the largest scale every link allows;
//! - [`ScaleGovernor`]: the published scale over time (rise limit, and the
//!   scale the arm may still be obeying).

mod file;
mod governor;
mod lever;
mod monitor;
mod motion;
mod protective;
mod stopping;

#[cfg(test)]
mod tests;

pub(crate) use file::RawMotion;
pub use governor::ScaleGovernor;
pub use lever::LeverArms;
pub use monitor::{OverLimit, SpeedMonitor, SpeedScale, OVER_LIMIT_TOLERANCE};
pub use motion::{ArmMotion, JointMotion};
pub use protective::{protective, MotionNow, Protective, Timing};
pub use stopping::{Stop, StopSample, StoppingModel};
