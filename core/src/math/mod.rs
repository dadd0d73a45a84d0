//! Small linear-algebra helpers: the fitting frame, banded solves, and the
//! Fibonacci lattice on the sphere.

mod banded;
mod frame;
mod sphere_lattice;

pub use banded::{BandedMatrix, BandedSolveError};
pub use frame::{Frame, FrameError};
pub use sphere_lattice::fibonacci_sphere;
