//! A surrogate as markers: one `TRIANGLE_LIST` per certified side (ids 0 for
//! the upper surface, 1 for the lower, in namespace `shroud/<stream>`), the
//! trimmed mesh the viewers draw (`shroud_viewers::scene::surrogate_meshes`),
//! and a `DELETE` for a side the surrogate does not have, so that RViz drops
//! what an earlier surrogate of the stream showed.

use super::{marker, point, rgba};
use glam::DVec3;
use shroud_msg::SurrogateMessage;
use shroud_ros2::{Marker, MarkerArray};
use shroud_surrogate::{Side, Surrogate};
use shroud_viewers::scene::{surface_rgba, surrogate_meshes};

/// `surrogate` of stream `stream` (decoded from `msg`), in `frame_id`, each
/// trim triangle split into `per_cell * per_cell` triangles.
pub fn surrogate_markers(
    stream: &str,
    msg: &SurrogateMessage,
    surrogate: &Surrogate,
    frame_id: &str,
    per_cell: usize,
) -> MarkerArray {
    let ns = format!("shroud/{stream}");
    let meshes = surrogate_meshes(surrogate, per_cell);
    let markers = [Side::Upper, Side::Lower]
        .into_iter()
        .zip(0..)
        .map(|(side, id)| {
            let mut m = marker(
                frame_id,
                msg.source_stamp_ns,
                &ns,
                id,
                Marker::TRIANGLE_LIST,
            );
            match meshes.iter().find(|mesh| mesh.side == side) {
                Some(mesh) => {
                    m.color = rgba(surface_rgba(side));
                    m.points = mesh
                        .indices
                        .iter()
                        .map(|&i| point(DVec3::from(mesh.positions[i as usize].map(f64::from))))
                        .collect();
                }
                None => m.action = Marker::DELETE,
            }
            m
        })
        .collect();
    MarkerArray { markers }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_surrogate::{fit_surrogate, FitOptions, Sides, SurrogateWire};

    #[test]
    fn each_side_is_a_triangle_list_of_its_mesh_and_a_missing_side_is_deleted() {
        let points: Vec<[f32; 3]> = (0..400)
            .map(|i| {
                [
                    (i % 20) as f32 * 0.05,
                    (i / 20) as f32 * 0.05,
                    0.1 * (i % 7) as f32,
                ]
            })
            .collect();
        let options = FitOptions {
            sides: Sides::Upper,
            ..FitOptions::default()
        };
        let s = fit_surrogate(&points, &options).unwrap();
        let msg = SurrogateMessage::from_surrogate(&s, 1_700_000_000_000_000_000, 3, "cam", 0);
        let array = surrogate_markers("cam", &msg, &s, "world", 1);
        assert_eq!(array.markers.len(), 2);
        let (upper, lower) = (&array.markers[0], &array.markers[1]);
        assert_eq!(
            (upper.ns.as_str(), upper.id, upper.type_),
            ("shroud/cam", 0, Marker::TRIANGLE_LIST)
        );
        assert_eq!(upper.action, Marker::ADD);
        assert!(!upper.points.is_empty() && upper.points.len() % 3 == 0);
        assert_eq!(upper.header.frame_id, "world");
        assert_eq!((lower.id, lower.action), (1, Marker::DELETE));
        // The markers survive their own wire format.
        let bytes = shroud_ros2::RosMessage::encode(&array);
        assert_eq!(
            <MarkerArray as shroud_ros2::RosMessage>::decode(&bytes).unwrap(),
            array
        );
    }
}
