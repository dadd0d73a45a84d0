//! Point clouds as the fitters and formats see them: f32 xyz triples, validated.
// `!(x > 0.0)` deliberately rejects NaN as well, which `x <= 0.0` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod boundary;
mod neighbours;
mod no_return;
mod normals;
mod plane;
mod point_cloud;
mod sectors;

pub use point_cloud::validate_points;

pub use boundary::{
    boundary_loops, boundary_points, find_rim, BoundaryFailure, BoundaryLoop, BoundaryParams,
};
pub use neighbours::{to_dvec3, to_f32, NeighbourIndex};
pub use no_return::{dark_cones, EmptyRays};
pub use normals::{
    default_orientation, estimate_normals, orient_normals, oriented_normals, Orientation,
};
pub use plane::{fit_plane, symmetric_eigen3, Plane, PlaneFit};
pub use point_cloud::{CloudError, PointCloud};
pub use sectors::{
    check_sectors, no_return_in_sector, points_in_sector, sector, SectorError, MAX_SECTOR_GRID,
};
