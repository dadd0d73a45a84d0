//! Why a smooth fit cannot be made.

use crate::mesh::MeshError;
use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum SmoothError {
    #[error(transparent)]
    Mesh(#[from] MeshError),
    #[error("sample {index} has a non-finite value or parameter")]
    NonFinite { index: usize },
    #[error("sample {index} lies on face {face}, but the domain has {faces} faces")]
    NoSuchFace {
        index: usize,
        face: usize,
        faces: usize,
    },
    #[error("sample {index} has parameters ({u}, {v}) outside [0, 1]^2")]
    OutsidePatch { index: usize, u: f64, v: f64 },
    #[error("{values} values for {samples} samples of dimension {dim}")]
    ValueCount {
        values: usize,
        samples: usize,
        dim: usize,
    },
    #[error("the least-squares system is singular: {points} points do not determine {functions} functions (add points or a smoothing weight lambda > 0)")]
    Underdetermined { points: usize, functions: usize },
    #[error("parameter correction applies to parametric fits (a domain mesh in space); a {kind} fit has exact parameters")]
    ExactParameters { kind: &'static str },
    #[error("invalid smoothing weight lambda = {0}: it must be finite and >= 0")]
    Lambda(f64),
    #[error("point {index} ({x}, {y}) is outside the planar domain")]
    OutsideDomain { index: usize, x: f64, y: f64 },
    #[error("point {index} has a non-finite coordinate (NaN or infinite)")]
    NonFinitePoint { index: usize },
    #[error("point {index} gives no direction from the centre (zero or not finite)")]
    NoDirection { index: usize },
    #[error("the domain mesh is not planar in z = 0 (vertex {vertex} has z = {z})")]
    NotPlanar { vertex: usize, z: f64 },
}
