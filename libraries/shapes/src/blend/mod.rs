//! Point-cloud blending by drag-and-drop (Zou et al., paper 001).
//!
//! * Placement (Section 3): [`Camera`], [`DepthImage`], [`BlockDepth`],
//!   [`bresenham`], [`surface_target`], [`DragSession`], [`drop_transform`],
//!   [`LocalAdjust`].
//! * Blending regions (Section 4): [`PolygonOfInterest`], [`blend_regions`].
//! * Transition surface (Section 5): [`rbf`] (triharmonic RBF, greedy centres,
//!   dense solve, split evaluation) and [`sample_zero_set`] (marching tetrahedra,
//!   surface following).
//! * Merge and compound blending: [`merge`], [`blend`], [`blend_sequence`];
//!   interactively, [`BlendSession`] (drop, adjust, clear, commit).
//! * Measures: [`seam_gap`], [`overlap_rate`]; output: [`write_ply_with_normals`].
// `!(x > 0.0)` deliberately rejects NaN as well, which `x <= 0.0` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Small fixed-size matrices and nets are clearer with explicit indices.
#![allow(clippy::needless_range_loop)]

mod camera;
mod depth;
mod drag;
mod error;
mod lattice;
mod merge;
mod pipeline;
mod polygon;
mod polygon2d;
mod prepared;
mod quality;
pub mod rbf;
mod regions;
mod session;
mod tetra;
mod transform;
mod write_ply;

pub use camera::Camera;
pub use depth::{BlockDepth, DepthImage, EMPTY_DEPTH};
pub use drag::{bresenham, last_on_surface, surface_target, DragSession};
pub use error::BlendError;
pub use merge::{keep_transition, merge, Merged, Source};
pub use pipeline::{
    blend, blend_sequence, Blend, BlendParams, BlendReport, Evaluation, StageTimes,
};
pub use polygon::{PolygonOfInterest, MAX_POLYGON_VERTICES};
pub use polygon2d::{signed_area, Polygon2};
pub use prepared::{Child, Prepared, MIN_CLOUD_POINTS};
pub use quality::{overlap_rate, seam_gap, seam_points, Gap};
pub use regions::{blend_regions, BlendRegions, ParentClass, RegionParams};
pub use session::{supersede, supersede_indices, BlendSession, DropState, ModelSources};
pub use shroud_msg::{BlendCommand, LocalAdjust};
pub use tetra::{sample_zero_set, sample_zero_set_with, SampledSurface};
pub use transform::{drop_transform, AdjustTransform, RigidTransform};
pub use write_ply::write_ply_with_normals;
