//! Joint-state messages (`JointStateMessage::from_bytes`).

use crate::check::named;
use crate::round_trip;
use shroud_msg::JointStateMessage;

pub fn run(data: &[u8]) {
    match JointStateMessage::from_bytes(data) {
        Ok(message) => {
            round_trip::message(
                &message,
                JointStateMessage::to_bytes,
                JointStateMessage::from_bytes,
            );
        }
        Err(e) => named(&e),
    }
}

/// A joint state without velocities, and one with them.
pub fn seeds() -> Vec<Vec<u8>> {
    let names = vec!["shoulder".to_string(), "elbow".to_string()];
    let still = JointStateMessage::new(10, 4, "arm", names, vec![0.5, -1.25]);
    let moving = still.clone().with_velocities(vec![0.75, -0.2]);
    [still, moving]
        .iter()
        .map(|m| m.to_bytes().expect("the seed message encodes"))
        .collect()
}
