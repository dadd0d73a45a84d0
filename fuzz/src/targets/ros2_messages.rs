//! ROS 2 CDR messages (shroud-ros2's `RosMessage::decode`): the first byte
//! picks the type, the rest is the payload. A payload that decodes must
//! encode and decode again to the same message, with the same bytes.

use crate::check::{named, same};
use shroud_ros2::{
    DiagnosticStatus, Float64, Header, KeyValue, Marker, RosMessage, TFMessage, Time,
    TransformStamped,
};

/// Decodes `data` as `M`; checks the round trip of what decodes and the
/// message of what does not.
pub fn check<M: RosMessage + std::fmt::Debug>(data: &[u8]) {
    match M::decode(data) {
        Ok(message) => {
            let bytes = message.encode();
            let again = M::decode(&bytes).expect("an encoded message decodes");
            same(&message, &again, "messages after a round trip");
            assert!(again.encode() == bytes, "re-encoding changed the bytes");
        }
        Err(e) => named(&e),
    }
}

/// The types this target reads, chosen by the first byte (modulo their count).
const DECODERS: &[fn(&[u8])] = &[
    check::<Float64>,
    check::<DiagnosticStatus>,
    check::<TFMessage>,
    check::<Marker>,
];

pub fn run(data: &[u8]) {
    if let Some((&selector, payload)) = data.split_first() {
        DECODERS[usize::from(selector) % DECODERS.len()](payload);
    }
}

fn header() -> Header {
    Header {
        stamp: Time { sec: 5, nanosec: 6 },
        frame_id: "map".into(),
    }
}

/// One message of each type, behind its selector byte.
pub fn seeds() -> Vec<Vec<u8>> {
    let status = DiagnosticStatus {
        level: DiagnosticStatus::WARN,
        name: "lidar".into(),
        values: vec![KeyValue {
            key: "rate".into(),
            value: "9.5".into(),
        }],
        ..DiagnosticStatus::default()
    };
    let tf = TFMessage {
        transforms: vec![TransformStamped {
            header: header(),
            child_frame_id: "base_link".into(),
            ..TransformStamped::default()
        }],
    };
    let marker = Marker {
        header: header(),
        type_: Marker::SPHERE,
        text: "hi".into(),
        ..Marker::default()
    };
    let payloads = [
        Float64 { data: -12.5 }.encode(),
        status.encode(),
        tf.encode(),
        marker.encode(),
    ];
    (0u8..)
        .zip(payloads)
        .map(|(selector, payload)| [vec![selector], payload].concat())
        .collect()
}
