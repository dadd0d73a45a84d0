//! Why a surrogate cannot be fitted, or cannot be trusted once read.

use shroud_geometry::cloud::CloudError;
use shroud_geometry::math::FrameError;
use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum FitError {
    #[error(transparent)]
    Cloud(#[from] CloudError),
    #[error(transparent)]
    Direction(#[from] FrameError),
    #[error("the grid must be at least 2 x 2 control points, got {cols} x {rows}")]
    GridTooSmall { cols: usize, rows: usize },
    #[error("the grid {cols} x {rows} is too large (at most {max} control points per side)")]
    GridTooLarge {
        cols: usize,
        rows: usize,
        max: usize,
    },
    #[error(
        "the cloud is degenerate seen along the fitting direction: its projection spans \
         {extent_u:e} x {extent_v:e} (all points identical or collinear); a surface needs a 2D footprint"
    )]
    Degenerate { extent_u: f64, extent_v: f64 },
    #[error(
        "the cloud is degenerate seen along the fitting direction: its projection lies within \
         {width:e} of a line of length {length:e} (collinear points); a surface needs a 2D footprint"
    )]
    Collinear { width: f64, length: f64 },
    #[error("no samples to fit a curve to")]
    NoSamples,
    #[error("a curve needs at least 2 control points, got {0}")]
    CurveTooShort(usize),
    #[error("sample {index} has a non-finite coordinate")]
    NonFiniteSample { index: usize },
    #[error("the certificate could not be established: {0} points remain on the wrong side")]
    Uncertifiable(usize),
}

/// A structurally readable surrogate that breaks an invariant every published
/// surrogate holds (see `docs/formats.md`).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SurrogateDefect {
    #[error("it has neither an upper nor a lower surface")]
    NoSurface,
    #[error("the grid {cols} x {rows} is outside 2 ..= {max} control points per side")]
    GridSize {
        cols: usize,
        rows: usize,
        max: usize,
    },
    #[error("domain {field} is {value}, must be finite{positive}", positive = if *.must_be_positive { " and > 0" } else { "" })]
    Domain {
        field: &'static str,
        value: f64,
        must_be_positive: bool,
    },
    #[error("frame axis {axis} is {reason}")]
    Frame {
        axis: &'static str,
        reason: &'static str,
    },
    #[error(
        "trim mask has {cells_s} x {cells_t} cells, the grid needs {expected_s} x {expected_t}"
    )]
    TrimShape {
        cells_s: usize,
        cells_t: usize,
        expected_s: usize,
        expected_t: usize,
    },
    #[error("trim mask has {got} cell bytes, expected {expected}")]
    TrimLength { expected: usize, got: usize },
    #[error("trim cell {cell} has bits {bits:#04x}: only the 4 triangle bits 0x0f may be set")]
    TrimBits { cell: usize, bits: u8 },
    #[error("the {slot} slot holds a surface marked {found}")]
    SideMismatch {
        slot: &'static str,
        found: &'static str,
    },
    #[error("{side} surface is {cols} x {rows}, the domain is {domain_cols} x {domain_rows}")]
    SurfaceShape {
        side: &'static str,
        cols: usize,
        rows: usize,
        domain_cols: usize,
        domain_rows: usize,
    },
    #[error("{side} surface has {got} coefficients, expected cols * rows = {expected}")]
    CoefficientCount {
        side: &'static str,
        expected: usize,
        got: usize,
    },
    #[error("{side} surface coefficient {index} is {value}, must be finite")]
    NonFiniteCoefficient {
        side: &'static str,
        index: usize,
        value: f64,
    },
    #[error("{side} surface certificate {reason}")]
    Certificate { side: &'static str, reason: String },
}
