//! Frames, uniform cubic B-splines and point clouds: the geometric vocabulary
//! every other shroud library shares. Pure: no I/O, no clocks.

pub mod cloud;
pub mod math;
pub mod spline;

pub use cloud::{CloudError, PointCloud};
pub use math::Frame;
