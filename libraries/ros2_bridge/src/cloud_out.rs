//! A shroud cloud as a ROS 2 `PointCloud2` (unorganised, little endian,
//! float32 x, y, z and, when the cloud has them, intensity: the layout of
//! PCL's `PointXYZ`/`PointXYZI` without padding, which RViz and PCL read).

use crate::time_of_ns;
use shroud_msg::{CloudView, MessageError};
use shroud_ros2::{Header, PointCloud2, PointField};
use std::borrow::Cow;

/// `cloud`'s points in `frame_id` (shroud's world as the ROS side names it),
/// stamped with the cloud's own stamp.
pub fn point_cloud2_of(
    cloud: &CloudView<'_>,
    frame_id: &str,
) -> Result<PointCloud2<'static>, MessageError> {
    let count = cloud.len();
    let mut names = vec!["x", "y", "z"];
    let intensity = cloud.intensity.as_deref();
    if let Some(bytes) = intensity {
        if bytes.len() != count * 4 {
            return Err(MessageError::Count {
                field: "intensity",
                found: bytes.len() / 4,
                expected: count,
            });
        }
        names.push("intensity");
    }
    let point_step = 4 * names.len();
    let data = match intensity {
        None => cloud.points.to_vec(),
        Some(values) => interleave(&cloud.points, values),
    };
    let fields = names
        .iter()
        .zip(0u32..)
        .map(|(name, k)| PointField::scalar(name, 4 * k, PointField::FLOAT32))
        .collect();
    let too_many = || MessageError::Invalid {
        field: "points",
        reason: format!("{count} points do not fit a PointCloud2's width and row step"),
    };
    let width = u32::try_from(count).map_err(|_| too_many())?;
    let row_step = u32::try_from(point_step * count).map_err(|_| too_many())?;
    Ok(PointCloud2 {
        header: Header {
            stamp: time_of_ns(cloud.stamp_ns),
            frame_id: frame_id.to_owned(),
        },
        height: 1,
        width,
        fields,
        is_bigendian: false,
        point_step: point_step as u32,
        row_step,
        data: Cow::Owned(data),
        // Shroud's clouds hold returned points only.
        is_dense: true,
    })
}

/// 12 bytes of xyz then 4 of intensity, point after point.
fn interleave(points: &[u8], intensity: &[u8]) -> Vec<u8> {
    let mut data = Vec::with_capacity(points.len() + intensity.len());
    for (xyz, i) in points.chunks_exact(12).zip(intensity.chunks_exact(4)) {
        data.extend_from_slice(xyz);
        data.extend_from_slice(i);
    }
    data
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{cloud_from_ros, CloudMount};
    use shroud_msg::{CloudMessage, SensorPose};

    #[test]
    fn a_cloud_goes_out_and_comes_back_with_its_points_and_intensity() {
        let points = [[1.0f32, 2.0, 3.0], [-4.0, 5.5, 0.25]];
        let msg = CloudMessage::new(
            1_700_000_000_000_000_001,
            4,
            "cam",
            SensorPose::default(),
            &points,
        )
        .with_intensity(&[0.5, 7.0]);
        let bytes = msg.to_bytes().unwrap();
        let view = CloudView::from_bytes(&bytes).unwrap();
        let ros = point_cloud2_of(&view, "world").unwrap();
        assert_eq!(
            (ros.width, ros.height, ros.point_step, ros.row_step),
            (2, 1, 16, 32)
        );
        assert_eq!(ros.header.frame_id, "world");
        let back = cloud_from_ros(&ros, &CloudMount::default(), "cam", 4).unwrap();
        assert_eq!(back.message.point_array().unwrap(), points);
        assert_eq!(back.message.intensity_array().unwrap().unwrap(), [0.5, 7.0]);
        assert_eq!(back.message.stamp_ns, msg.stamp_ns);
    }
}
