//! Point clouds as the fitters and formats see them: f32 xyz triples, validated.

mod point_cloud;

pub use point_cloud::validate_points;

pub use point_cloud::{CloudError, PointCloud};
