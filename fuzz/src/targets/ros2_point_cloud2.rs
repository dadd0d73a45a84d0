//! ROS 2 sensor_msgs/PointCloud2 payloads, read both ways (shroud-ros2's
//! borrowed `decode_borrowed` and owned `RosMessage::decode`): both must
//! agree, and what decodes must round trip.

use super::ros2_messages::check;
use crate::check::{named, same};
use shroud_ros2::{PointCloud2, PointField, RosMessage};
use std::borrow::Cow;

pub fn run(data: &[u8]) {
    let borrowed = PointCloud2::decode_borrowed(data);
    match (&borrowed, PointCloud2::<'static>::decode(data)) {
        (Ok(borrowed), Ok(owned)) => same(borrowed, &owned, "borrowed and owned clouds"),
        (Err(e), Err(_)) => named(e),
        (borrowed, owned) => panic!("the readers disagree: {borrowed:?} / {owned:?}"),
    }
    check::<PointCloud2<'static>>(data);
}

fn xyz(datatype: u8, size: u32) -> Vec<PointField> {
    ["x", "y", "z"]
        .into_iter()
        .zip(0..)
        .map(|(name, i)| PointField::scalar(name, i * size, datatype))
        .collect()
}

/// A 2-point float32 cloud and a 1-point float64 cloud.
pub fn seeds() -> Vec<Vec<u8>> {
    let float32 = PointCloud2 {
        height: 1,
        width: 2,
        fields: xyz(PointField::FLOAT32, 4),
        point_step: 12,
        row_step: 24,
        data: Cow::Owned(
            [1.0f32, 2.0, 3.0, -1.5, 0.25, 8.0]
                .iter()
                .flat_map(|v| v.to_le_bytes())
                .collect(),
        ),
        is_dense: true,
        ..PointCloud2::default()
    };
    let float64 = PointCloud2 {
        width: 1,
        fields: xyz(PointField::FLOAT64, 8),
        point_step: 24,
        row_step: 24,
        data: Cow::Owned(
            [1.5f64, -2.5, 1e-3]
                .iter()
                .flat_map(|v| v.to_le_bytes())
                .collect(),
        ),
        ..float32.clone()
    };
    vec![float32.encode(), float64.encode()]
}
