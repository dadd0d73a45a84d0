//! ROS 2 visualization_msgs/MarkerArray payloads (shroud-ros2): round trips
//! of what decodes, named errors for the rest.

use super::ros2_messages::check;
use shroud_ros2::{ColorRGBA, Marker, MarkerArray, Point, RosMessage};

pub fn run(data: &[u8]) {
    check::<MarkerArray>(data);
}

/// An empty array and one TRIANGLE_LIST marker with per-vertex colors.
pub fn seeds() -> Vec<Vec<u8>> {
    let corner = |x, y| Point { x, y, z: 0.0 };
    let red = ColorRGBA {
        r: 1.0,
        g: 0.0,
        b: 0.0,
        a: 1.0,
    };
    let triangle = Marker {
        ns: "shroud".into(),
        type_: Marker::TRIANGLE_LIST,
        points: vec![corner(0.0, 0.0), corner(1.0, 0.0), corner(0.0, 1.0)],
        colors: vec![red; 3],
        ..Marker::default()
    };
    vec![
        MarkerArray::default().encode(),
        MarkerArray {
            markers: vec![triangle],
        }
        .encode(),
    ]
}
