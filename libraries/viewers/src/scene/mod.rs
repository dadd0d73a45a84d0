//! What viewers draw of the graph's messages (the web dashboard, the Foxglove
//! bridge, recordings): clouds thinned to a point budget, surrogates as their
//! trimmed triangle meshes, smooth fits tessellated, the arm posed at its joint
//! state (the one a verdict answered), each link's clearance band, and the arm's speed as its verdict
//! allows (the speed scale and the link that limits it). Pure functions of
//! decoded messages; every viewer encodes the results in its own format.

mod arm_pose;
mod arm_speed;
mod clearance_band;
mod decimate;
mod error;
mod recent_joints;
mod smooth_mesh;
mod surface_mesh;

pub use arm_pose::{pose_arm, PosedArm, PosedLink};
pub use arm_speed::{ArmSpeed, SpeedState};
pub use clearance_band::{link_bands, ClearanceBand, NO_VERDICT_RGBA};
pub use decimate::Decimation;
pub use error::SceneError;
pub use recent_joints::RecentJoints;
pub use smooth_mesh::smooth_mesh;
pub use surface_mesh::{surface_rgba, surrogate_meshes, SurfaceMesh};
