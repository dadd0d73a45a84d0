//! Queries against a safe spline surrogate, exact about the conservative direction
//! (what a collision guard needs):
//!
//! - [`HeightQuery`]: the surface height at a place, `None` where the surrogate says
//!   nothing (outside the domain, trimmed out). Evaluation is the certificate's.
//! - [`Classify`]: a point's place relative to the surfaces. It repeats the
//!   certificate's exact operations (locator, `eval`), so every certified cloud
//!   point lands on its promised side.
//! - [`RayCast`]: the first hit of a ray. On each cell the height difference along
//!   the ray is a degree-6 polynomial (Section 1 of the paper), bounded by its
//!   Bernstein coefficients: a piece is skipped only when the convex hull proves
//!   it has no root, so hits are never missed; touches and near-zero values are
//!   reported.
//! - [`BoundQuery`]: height bounds over a rectangle from restricted Bézier control
//!   nets (convex hull property), padded by their rounding.
//!
//! The kept region of a trimmed surrogate is taken as the closed union of its
//! kept triangles (a superset of `TrimMask::contains`): a surface counts up to and
//! including its trim border.
//!
//! Queries work on validated views ([`SurrogateView`], [`SideView`]): checked once,
//! then allocation-free and panic-free.

mod bernstein;
mod bound;
mod classify;
mod error;
mod height;
mod kept;
mod ray;
mod root;
mod traversal;
mod view;

#[cfg(test)]
mod tests;

pub use bernstein::{cubic_on_interval, patch_on_rect, Bernstein6};
pub use bound::{BoundOptions, BoundQuery, CellFilter, HeightRange, ParamRect, UvRect, MAX_REFINE};
pub use classify::{Classify, PointClass};
pub use error::QueryError;
pub use height::HeightQuery;
pub use kept::{closed_triangles, kept_closed};
pub use ray::{first_hit_any, Ray, RayCast, RayHit, HIT_RESOLUTION};
pub use view::{SideView, SurrogateView};
