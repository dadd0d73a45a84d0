//! Small linear-algebra helpers: the fitting frame, banded solves, the
//! Fibonacci lattice on the sphere, and a point's distance to a segment in a
//! plane.

mod banded;
mod frame;
mod plane;
mod sphere_lattice;

pub use banded::{BandedMatrix, BandedSolveError};
pub use frame::{Frame, FrameError};
pub use plane::{segment_distance, segment_distance_squared};
pub use sphere_lattice::fibonacci_sphere;
