//! Pure geometry core of shroud: uniform cubic B-splines, safe spline surrogates
//! (Myles & Peters, "Fast Safe Spline Surrogates for Large Point Clouds"), their
//! certification, queries, and the file formats. No I/O, no async: every function
//! here takes values or byte slices and returns values.

pub mod backlog;
pub mod blend;
pub mod cloud;
pub mod dashboard;
pub mod format;
pub mod guard;
pub mod ingest;
pub mod launch;
pub mod math;
pub mod mesh;
pub mod message;
pub mod metrics;
pub mod pace;
pub mod query;
pub mod record;
pub mod scene;
pub mod smooth;
pub mod spline;
pub mod surrogate;
pub mod tight;

pub use cloud::{CloudError, PointCloud};
pub use math::Frame;
