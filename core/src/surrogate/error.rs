//! Why a surrogate cannot be fitted.

use crate::cloud::CloudError;
use crate::math::FrameError;
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
