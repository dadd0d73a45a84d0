//! Small linear-algebra helpers: the fitting frame and banded solves.

mod banded;
mod frame;

pub use banded::{BandedMatrix, BandedSolveError};
pub use frame::{Frame, FrameError};
