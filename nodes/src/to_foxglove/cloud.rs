//! A cloud as `foxglove.PointCloud`: the points thinned to a budget
//! ([`Decimation`]) and packed little-endian, `x y z` as f32 and `intensity`
//! after them when the cloud has it (Foxglove's schema:
//! <https://docs.foxglove.dev/docs/visualization/message-schemas/point-cloud>).

use super::geometry::{identity, timestamp, WORLD_FRAME};
use foxglove::messages::packed_element_field::NumericType;
use foxglove::messages::{PackedElementField, PointCloud};
use shroud_msg::{CloudView, MessageError};
use shroud_viewers::scene::Decimation;

/// Bytes of one packed coordinate or intensity.
const F32: usize = 4;

/// `view`'s points, at most `budget` of them, refusing a cloud with a
/// non-finite coordinate (as every consumer of the schema does).
pub fn point_cloud(view: &CloudView<'_>, budget: usize) -> Result<PointCloud, MessageError> {
    view.check_finite_points()?;
    let keep = Decimation::new(view.len(), budget);
    let intensity = view.intensity.as_deref();
    let stride = if intensity.is_some() {
        4 * F32
    } else {
        3 * F32
    };
    let mut data = Vec::with_capacity(stride * keep.kept());
    for i in keep.indices() {
        data.extend_from_slice(&view.points[3 * F32 * i..3 * F32 * (i + 1)]);
        if let Some(values) = intensity {
            let value = f32::from_le_bytes(values.as_chunks::<4>().0[i]);
            // Foxglove colours by the field's range: one NaN would blank it.
            let value = if value.is_finite() { value } else { 0.0 };
            data.extend_from_slice(&value.to_le_bytes());
        }
    }
    let names: &[&str] = if intensity.is_some() {
        &["x", "y", "z", "intensity"]
    } else {
        &["x", "y", "z"]
    };
    Ok(PointCloud {
        timestamp: Some(timestamp(view.stamp_ns)),
        frame_id: WORLD_FRAME.into(),
        pose: Some(identity()),
        point_stride: stride as u32,
        fields: names
            .iter()
            .enumerate()
            .map(|(k, name)| PackedElementField {
                name: (*name).into(),
                offset: (k * F32) as u32,
                r#type: NumericType::Float32 as i32,
            })
            .collect(),
        data: data.into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_msg::SensorPose;

    fn floats(bytes: &[u8]) -> Vec<f32> {
        bytes
            .as_chunks::<4>()
            .0
            .iter()
            .map(|c| f32::from_le_bytes(*c))
            .collect()
    }

    #[test]
    fn points_are_packed_xyz_then_intensity_and_thinned_to_the_budget() {
        let points: Vec<[f32; 3]> = (0..1000).map(|i| [i as f32, 1.0, -(i as f32)]).collect();
        let intensity: Vec<f32> = (0..1000)
            .map(|i| if i == 10 { f32::NAN } else { i as f32 / 10.0 })
            .collect();
        let view = CloudView::new(1_500_000_000, 7, "sim", SensorPose::default(), &points)
            .with_intensity(&intensity);
        let cloud = point_cloud(&view, 100).unwrap();
        assert_eq!(cloud.point_stride, 16);
        assert_eq!(cloud.data.len(), 100 * 16);
        let offsets: Vec<(&str, u32)> = cloud
            .fields
            .iter()
            .map(|f| (f.name.as_str(), f.offset))
            .collect();
        assert_eq!(offsets, [("x", 0), ("y", 4), ("z", 8), ("intensity", 12)]);
        assert!(cloud
            .fields
            .iter()
            .all(|f| f.r#type == NumericType::Float32 as i32));
        let values = floats(&cloud.data);
        // Point 1 of the packed cloud is source point 10 (stride 10), whose
        // NaN intensity is sent as 0.
        assert_eq!(&values[4..8], &[10.0, 1.0, -10.0, 0.0]);
        assert_eq!(&values[8..12], &[20.0, 1.0, -20.0, 2.0]);
        let t = cloud.timestamp.unwrap();
        assert_eq!((t.sec(), t.nsec()), (1, 500_000_000));
        assert_eq!(cloud.frame_id, WORLD_FRAME);
    }

    #[test]
    fn a_cloud_without_intensity_has_three_fields_and_small_clouds_stay_whole() {
        let points = [[1.0f32, 2.0, 3.0], [4.0, 5.0, 6.0]];
        let view = CloudView::new(0, 0, "sim", SensorPose::default(), &points);
        let cloud = point_cloud(&view, 1000).unwrap();
        assert_eq!((cloud.point_stride, cloud.fields.len()), (12, 3));
        assert_eq!(floats(&cloud.data), [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    }

    #[test]
    fn a_non_finite_coordinate_is_refused_with_its_index() {
        let mut points = vec![[0.0f32; 3]; 50];
        points[42][2] = f32::INFINITY;
        let view = CloudView::new(0, 0, "sim", SensorPose::default(), &points);
        assert_eq!(
            point_cloud(&view, 10),
            Err(MessageError::NonFinite {
                field: "points",
                index: 42
            })
        );
    }
}
