//! Why a blend cannot be made: every failure on input-derived data is one of these.

use shroud_geometry::cloud::BoundaryFailure;
use thiserror::Error;

/// Errors of the blending pipeline (placement, regions, RBF, sampling, merge).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BlendError {
    #[error("the {what} cloud has {count} points; at least {min} are needed")]
    TooFewPoints {
        what: &'static str,
        count: usize,
        min: usize,
    },
    #[error("the {what} cloud has a non-finite coordinate at point {index}")]
    NonFinite { what: &'static str, index: usize },
    #[error("the points of the {what} cloud (almost) all coincide: no sampling spacing")]
    Coincident { what: &'static str },
    /// No rim to take as the polygon of interest; `reason` says why and what to do.
    #[error("the {what} cloud has no usable rim for the polygon of interest: {reason}")]
    NoBoundaryLoop {
        what: &'static str,
        reason: BoundaryFailure,
    },
    #[error("degenerate polygon of interest: {reason}")]
    DegeneratePolygon { reason: String },
    #[error("blending region {region} has {count} points; at least {min} are needed (move the child or widen the region)")]
    EmptyRegion {
        region: &'static str,
        count: usize,
        min: usize,
    },
    #[error("invalid parameter {name} = {value}: {reason}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        reason: &'static str,
    },
    #[error("the RBF system is singular or ill-conditioned (relative residual {residual:e})")]
    SingularSystem { residual: f64 },
    #[error("the RBF needs at least {min} distinct centres, got {count}")]
    TooFewCentres { count: usize, min: usize },
    #[error("the transition surface needs more than {limit} grid cells; raise the cell size")]
    SamplingLimit { limit: usize },
    #[error("the transition surface was not found near the blending regions")]
    NoTransitionSurface,
    #[error("the cursor path never reaches the parent's surface")]
    NotOnSurface,
    #[error("degenerate camera: {reason}")]
    DegenerateCamera { reason: &'static str },
    #[error("too few surface samples around the target to fit its normal")]
    NoTargetNormal,
    #[error("no child is dropped yet: drop it before adjusting or committing")]
    NothingDropped,
}
