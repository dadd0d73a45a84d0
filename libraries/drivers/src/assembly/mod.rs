//! From range scans to 3D clouds. A planar lidar or a single-beam rangefinder
//! measures rays in its own plane ([`RangeScan`](super::device::RangeScan));
//! this module places every ray in the robot's frame through the sensor's
//! mount (fixed, or turning about one axis: a tilting or rotating unit whose
//! angle comes from a configured sweep profile or from joint-state samples),
//! each ray at its own time, and gathers the points into one cloud per sweep,
//! per N scans or per time window. A reading whose time the device did not
//! send is placed at the best estimate of it, and carries a bound on its
//! position error ([`lateness`]).
//!
//! Frames follow REP-103 (x forward, y left, z up, angles counter-clockwise).

mod assembler;
mod error;
mod joint_track;
pub mod lateness;
mod motion;
mod pose;
mod profile;
mod window;

#[cfg(test)]
mod tests;

pub use assembler::{
    AssembledCloud, AssemblyConfig, AssemblyStats, CloudAssembler, DEFAULT_MAX_POSITION_ERROR_M,
};
pub use error::AssemblyError;
pub use joint_track::JointTrack;
pub use motion::{MountMotion, MovingMount};
pub use pose::MountPose;
pub use profile::SweepProfile;
pub use window::CloudWindow;
