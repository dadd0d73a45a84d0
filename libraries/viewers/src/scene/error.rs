//! Why a message cannot be drawn.

use shroud_guard::GuardError;
use shroud_shapes::mesh::MeshError;
use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum SceneError {
    #[error("joint state of arm {arm:?} names joints {found:?}, the arm's are {expected:?}")]
    JointNames {
        arm: String,
        found: Vec<String>,
        expected: Vec<String>,
    },
    #[error("cannot pose the arm: {0}")]
    Pose(#[from] GuardError),
    #[error("cannot tessellate the smooth fit: {0}")]
    SmoothMesh(String),
    #[error("smooth fit domain: {0}")]
    Domain(#[from] MeshError),
}
