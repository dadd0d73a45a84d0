//! The optimal safe surface in the spline space (the `--tight` mode) and the
//! tightness measure the modes are compared by.
//!
//! The optimum is a linear program: minimise `∫_kept f` subject to `f` lying on
//! the safe side of every constraint point ([`lp`], [`objective`]). The fit solves
//! it over the candidates with a banded primal-dual interior-point method
//! ([`ipm`]); [`lp_reference`] solves it over every point with clarabel and
//! cutting planes; [`excess`] measures how far a surface stands off the data.

pub mod banded_cholesky;
pub mod bounds;
mod cells;
mod cloud_side;
mod error;
pub mod excess;
#[cfg(test)]
mod fixture;
pub mod ipm;
pub mod lp;
pub mod lp_reference;
pub mod objective;
mod optimum;
pub mod quadrature;

pub use cloud_side::CloudSide;
pub use error::LpError;
pub use excess::{excess_volume, Envelope, DEFAULT_RASTER};
pub use ipm::{IpmSettings, IpmSolution};
pub use lp::SplineLp;
pub use lp_reference::{optimal_surface, ReferenceOptimum};
pub use objective::objective_weights;
pub use optimum::{lower_to_optimum, optimum_of_candidates};
