//! Cloud messages, read both ways the nodes read them: the borrowed
//! `CloudView` (points in place when aligned) and the owned `CloudMessage`.
//! Both must agree, and a message that decodes has valid arrays.

use crate::check::{named, same};
use crate::round_trip;
use shroud_msg::{CloudMessage, CloudView, PointChannel, SensorPose};

pub fn run(data: &[u8]) {
    let view = CloudView::from_bytes(data);
    let message = CloudMessage::from_bytes(data);
    match (&view, &message) {
        (Ok(view), Ok(message)) => agree(view, message),
        (Err(e), Err(_)) => named(e),
        (Ok(_), Err(e)) => {
            // The owned message checks what the view leaves to read_points.
            named(e);
        }
        (Err(e), Ok(_)) => panic!("the view refused a message the owned reader took: {e}"),
    }
}

fn agree(view: &CloudView<'_>, message: &CloudMessage) {
    let points = message
        .point_array()
        .expect("a decoded message has valid points");
    message
        .intensity_array()
        .expect("a decoded message has valid intensity");
    message
        .channel_arrays()
        .expect("a decoded message has valid channels");
    let mut read = Vec::new();
    view.read_points(&mut read)
        .expect("the view reads what the message holds");
    same(&points, &read, "points of the view and of the message");
    assert_eq!(view.len(), points.len(), "the view's length");
    if let Some(Ok(in_place)) = view.points_in_place() {
        same(&points.as_slice(), &in_place, "points in place");
    }
    round_trip::message(message, CloudMessage::to_bytes, CloudMessage::from_bytes);
    let view_bytes = view.to_bytes().expect("a decoded view encodes");
    let again = CloudMessage::from_bytes(&view_bytes).expect("an encoded view decodes");
    same(message, &again, "the view re-encoded and the message");
}

pub fn seeds() -> Vec<Vec<u8>> {
    let points = [[0.0, 1.5, -2.25], [1e-3, 2e6, 3.0], [-0.0, 4.0, 5.5]];
    let pose = SensorPose {
        position: [1.0, 2.0, 3.0],
        orientation: [0.0, 0.0, 0.6, 0.8],
    };
    let plain = CloudMessage::new(7, 3, "lidar", pose, &points);
    let rich = plain
        .clone()
        .with_intensity(&[1.0, 2.0, 3.0])
        .with_channels(&[PointChannel::new("velocity", vec![0.5, -0.5, 0.0])]);
    let aligned = CloudView::new(9, 1, "a", SensorPose::default(), &points)
        .aligned()
        .and_then(|v| v.to_bytes());
    [plain.to_bytes(), rich.to_bytes(), aligned]
        .into_iter()
        .map(|b| b.expect("seed messages encode"))
        .collect()
}
