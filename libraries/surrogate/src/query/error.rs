//! Why a query cannot be answered: malformed input, or a surrogate whose parts do
//! not fit together (it may come from a file, so nothing is assumed).

use crate::Side;
use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum QueryError {
    #[error("the surrogate has no {0:?} surface")]
    MissingSide(Side),
    #[error("the surrogate has neither an upper nor a lower surface")]
    NoSurface,
    #[error(
        "the {side:?} surface has a {surface_cols} x {surface_rows} grid with {coefficients} \
         coefficients but the domain is {domain_cols} x {domain_rows}"
    )]
    GridMismatch {
        side: Side,
        surface_cols: usize,
        surface_rows: usize,
        coefficients: usize,
        domain_cols: usize,
        domain_rows: usize,
    },
    #[error(
        "the trim mask covers {cells_s} x {cells_t} cells with {bits} entries but the domain \
         has {expected_s} x {expected_t} cells"
    )]
    TrimMismatch {
        cells_s: usize,
        cells_t: usize,
        bits: usize,
        expected_s: usize,
        expected_t: usize,
    },
    #[error(
        "the domain must be at least 2 x 2 with finite origin and positive finite steps, got {0:?}"
    )]
    BadDomain(crate::Domain),
    #[error("the frame has a non-finite axis")]
    BadFrame,
    #[error("the surface stored as {slot:?} says it is {stored:?}")]
    SideMismatch { slot: Side, stored: Side },
    #[error("coefficient {index} of the {side:?} surface is not finite")]
    NonFiniteCoefficient { side: Side, index: usize },
    #[error("the ray origin must be finite, got ({0}, {1}, {2})")]
    BadRayOrigin(f64, f64, f64),
    #[error("the ray direction must be finite and non-zero, got ({0}, {1}, {2})")]
    BadRayDirection(f64, f64, f64),
    #[error("the maximum ray distance must be finite and >= 0, got {0}")]
    BadMaxDistance(f64),
    #[error("the rectangle corners must be finite, got {0:?} x {1:?}")]
    NonFiniteRect([f64; 2], [f64; 2]),
    #[error("refinement depth {depth} exceeds the maximum {max} (4^depth pieces per cell)")]
    RefineTooDeep { depth: u32, max: u32 },
}
