//! Uniform cubic B-splines with integer knots and repeated end coefficients
//! (Section 2 of Myles & Peters): curves, tensor-product surfaces, their Bézier
//! form, and the matrices of equation (2).

mod basis;
mod bezier;
mod curve;
mod matrix_form;
mod surface;

pub use basis::{
    basis_derivative_weights, basis_weights, eval_eq1, knot_interval, second_difference,
};
pub use bezier::{bezier_patch, cubic_bezier_of_interval, BezierPatch};
pub use curve::UniformCubicCurve;
pub use matrix_form::{difference_matrix, evaluation_matrix};
pub use surface::UniformCubicSurface;
