//! Collision verdict messages (`CollisionMessage::from_bytes`).

use crate::check::named;
use crate::round_trip;
use shroud_msg::{CollisionMessage, GuardVerdict, LinkClearance};

pub fn run(data: &[u8]) {
    match CollisionMessage::from_bytes(data) {
        Ok(message) => {
            round_trip::message(
                &message,
                CollisionMessage::to_bytes,
                CollisionMessage::from_bytes,
            );
        }
        Err(e) => named(&e),
    }
}

/// A stop, and a clear that lets the arm move at a scaled speed.
pub fn seeds() -> Vec<Vec<u8>> {
    let stop = CollisionMessage {
        version: CollisionMessage::VERSION,
        joints_stamp_ns: 100,
        joints_sequence: 7,
        arm: "arm".into(),
        surrogate_stamp_ns: 90,
        surrogate_sequence: 3,
        surrogate_age_ns: 10,
        views: 2,
        verdict: GuardVerdict::Stop,
        stop: true,
        reason: "link forearm within 0.05 m".into(),
        stop_distance: 0.05,
        min_clearance: 0.01,
        closest_link: "forearm".into(),
        unobserved: false,
        links: vec![LinkClearance {
            link: "forearm".into(),
            clearance: 0.01,
            unobserved: true,
        }],
        check_ns: 5000,
        speed_scale: 0.0,
        limiting_link: String::new(),
        protective_distance: 0.05,
    };
    let clear = CollisionMessage {
        verdict: GuardVerdict::Clear,
        stop: false,
        reason: String::new(),
        min_clearance: 0.3,
        links: vec![LinkClearance {
            link: "forearm".into(),
            clearance: 0.3,
            unobserved: false,
        }],
        speed_scale: 0.35,
        limiting_link: "forearm".into(),
        protective_distance: 0.27,
        ..stop.clone()
    };
    [stop, clear]
        .iter()
        .map(|m| m.to_bytes().expect("the seed message encodes"))
        .collect()
}
