//! The camera model checked against the cloud it is to place: every returned
//! pixel of an organised cloud must lie along (within one ray spacing of) the
//! pinhole ray through its pixel's centre. A cloud in another frame than the
//! camera's optical frame, a wrong field of view or an off-centre principal
//! point fails here, before its empty rays are placed by that model.

use super::layout::PointLayout;
use super::mount::PinholeCamera;
use crate::CloudInError;

/// The largest angle between a returned point's direction (in the cloud's
/// frame) and its pixel's model ray; an error when it exceeds the ray
/// spacing `spread` (the model is then not this cloud's camera).
pub fn model_deviation(
    layout: &PointLayout,
    data: &[u8],
    camera: &PinholeCamera,
    spread: f64,
) -> Result<f64, CloudInError> {
    let mut worst = 0.0f64;
    for row in 0..layout.height {
        for column in 0..layout.width {
            let point = layout.point(data, row, column);
            let p = layout.xyz(point);
            if !p.is_finite() || p.length_squared() == 0.0 {
                continue;
            }
            let ray = camera.ray(layout.height, layout.width, row, column);
            let angle = ray.angle_between(p);
            if angle > spread {
                return Err(CloudInError::CameraModel {
                    row,
                    column,
                    degrees: angle.to_degrees(),
                    spread_degrees: spread.to_degrees(),
                });
            }
            worst = worst.max(angle);
        }
    }
    Ok(worst)
}
