//! Node status messages (`NodeStatusMessage::from_bytes`).

use crate::check::named;
use crate::round_trip;
use shroud_msg::NodeStatusMessage;

pub fn run(data: &[u8]) {
    match NodeStatusMessage::from_bytes(data) {
        Ok(message) => {
            round_trip::message(
                &message,
                NodeStatusMessage::to_bytes,
                NodeStatusMessage::from_bytes,
            );
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let mut message = NodeStatusMessage::new("scanner", "scanner", 42);
    message.counters.insert("received".into(), 10);
    message.gauges.insert("rate_hz".into(), 9.5);
    message
        .labels
        .insert("device.state".into(), "streaming".into());
    vec![message.to_bytes().expect("the seed message encodes")]
}
