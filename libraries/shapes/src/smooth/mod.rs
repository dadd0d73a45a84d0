//! Least-squares fitting by G1 smooth spline functions (Marsala et al., paper
//! 004, Section 6): the biquintic multipatch over a quad-mesh domain whose
//! coefficients minimise eq. (26), the squared distances to the data plus
//! lambda times the thin-plate energy (27), assembled patch by patch and solved
//! with a sparse Cholesky factorisation; the error measures (28); and the
//! location of points in a planar quad-mesh domain.

// Bernstein tensors are clearer with explicit (i, j) indices.
#![allow(clippy::needless_range_loop)]

mod bernstein;
mod error;
mod fit;
mod fit_as;
mod foot_point;
mod locate;
mod parametric;
mod parametrisation;
mod sample;
mod sphere;
mod surface_locator;
mod tessellate;
mod thin_plate;
mod wire;

#[cfg(test)]
mod parametric_tests;
#[cfg(test)]
mod tests;

pub use bernstein::{bernstein5, bernstein5_derivative, bernstein5_jet};
pub use error::SmoothError;
pub use fit::{FitErrors, SmoothFitter, SmoothSurface};
pub use fit_as::{FitRounds, DEFAULT_CORRECTIONS};
pub use foot_point::{foot_point, BilinearPatches, PatchAdjacency, PatchSurface};
pub use locate::{is_planar, PlanarLocator};
pub use parametric::{correct_parameters, ParametricFit};
pub use parametrisation::Parametrisation;
pub use sample::Sample;
pub use sphere::{cube_sphere, SphereLocator};
pub use surface_locator::SurfaceLocator;
pub use thin_plate::thin_plate_gram;
pub use wire::{patches_message, sample_patches_message, SmoothFitReport};
