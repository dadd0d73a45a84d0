//! The `PointCloud` container and its validation.

use thiserror::Error;

/// Why a cloud cannot be used.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CloudError {
    #[error("the point cloud is empty")]
    Empty,
    #[error("point {index} has a non-finite coordinate ({x}, {y}, {z})")]
    NonFinite {
        index: usize,
        x: f32,
        y: f32,
        z: f32,
    },
}

/// A cloud of points stored as raw f32 xyz triples (the wire and file layout).
///
/// `[f32; 3]` rather than a SIMD vector type so that a message blob or a binary PLY
/// body can be viewed as points with `bytemuck` without copying.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PointCloud {
    pub points: Vec<[f32; 3]>,
}

impl PointCloud {
    pub fn new(points: Vec<[f32; 3]>) -> Self {
        Self { points }
    }

    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Checks that the cloud is non-empty and every coordinate is finite.
    pub fn validate(&self) -> Result<(), CloudError> {
        validate_points(&self.points)
    }
}

/// Checks that `points` is non-empty and every coordinate is finite.
pub fn validate_points(points: &[[f32; 3]]) -> Result<(), CloudError> {
    if points.is_empty() {
        return Err(CloudError::Empty);
    }
    match points
        .iter()
        .position(|p| !(p[0].is_finite() && p[1].is_finite() && p[2].is_finite()))
    {
        Some(index) => {
            let [x, y, z] = points[index];
            Err(CloudError::NonFinite { index, x, y, z })
        }
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_empty_and_nan() {
        assert_eq!(PointCloud::default().validate(), Err(CloudError::Empty));
        let c = PointCloud::new(vec![[0.0, 0.0, 0.0], [1.0, f32::NAN, 0.0]]);
        assert!(matches!(
            c.validate(),
            Err(CloudError::NonFinite { index: 1, .. })
        ));
        let c = PointCloud::new(vec![[0.0, f32::INFINITY, 0.0]]);
        assert!(matches!(
            c.validate(),
            Err(CloudError::NonFinite { index: 0, .. })
        ));
        assert!(PointCloud::new(vec![[1.0, 2.0, 3.0]]).validate().is_ok());
    }
}
