//! Collision-status messages: the guard's verdict for one arm pose against the
//! latest certified surrogate.

use super::blob::{decode, encode};
use super::error::MessageError;
use super::{check_finite, check_version};
use serde::{Deserialize, Serialize};

/// One link's conservative clearance (metres; 0 when contact cannot be excluded).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LinkClearance {
    pub link: String,
    pub clearance: f64,
}

/// Why the guard says stop or go.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GuardVerdict {
    /// Every link is farther than the stop distance from the surrogate sandwich.
    Clear,
    /// Some link is within the stop distance.
    Stop,
    /// No certified surrogate has arrived yet, or the latest one is older than
    /// the allowed age: the guard cannot vouch for anything, so it stops.
    NoSurrogate,
    Stale,
}

/// The guard's output for one joint state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CollisionMessage {
    pub version: u16,
    /// Stamp and sequence of the joint state checked.
    pub joints_stamp_ns: u64,
    pub joints_sequence: u64,
    pub arm: String,
    /// Stamp and sequence of the cloud behind the surrogate used (0 if none).
    pub surrogate_stamp_ns: u64,
    pub surrogate_sequence: u64,
    pub verdict: GuardVerdict,
    /// `true` unless the verdict is `clear`.
    pub stop: bool,
    pub stop_distance: f64,
    pub min_clearance: f64,
    pub closest_link: String,
    pub links: Vec<LinkClearance>,
    /// Wall time of the check, nanoseconds.
    pub check_ns: u64,
}

impl CollisionMessage {
    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// Decodes and validates: version, finite distances, `stop` agreeing with the verdict.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: Self = decode(bytes)?;
        check_version(msg.version)?;
        let clearances: Vec<f64> = msg.links.iter().map(|l| l.clearance).collect();
        check_finite("links.clearance", &clearances)?;
        check_finite("stop_distance", &[msg.stop_distance])?;
        if msg.min_clearance.is_nan() {
            return Err(MessageError::NonFinite {
                field: "min_clearance",
                index: 0,
            });
        }
        if msg.stop != (msg.verdict != GuardVerdict::Clear) {
            return Err(MessageError::Invalid {
                field: "stop",
                reason: format!("stop = {} contradicts verdict {:?}", msg.stop, msg.verdict),
            });
        }
        Ok(msg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::message::SCHEMA_VERSION;

    fn sample(verdict: GuardVerdict) -> CollisionMessage {
        CollisionMessage {
            version: SCHEMA_VERSION,
            joints_stamp_ns: 1,
            joints_sequence: 2,
            arm: "arm".into(),
            surrogate_stamp_ns: 3,
            surrogate_sequence: 4,
            verdict,
            stop: verdict != GuardVerdict::Clear,
            stop_distance: 0.05,
            min_clearance: 0.2,
            closest_link: "wrist".into(),
            links: vec![LinkClearance {
                link: "wrist".into(),
                clearance: 0.2,
            }],
            check_ns: 900,
        }
    }

    #[test]
    fn round_trips_and_checks_consistency() {
        for v in [
            GuardVerdict::Clear,
            GuardVerdict::Stop,
            GuardVerdict::NoSurrogate,
        ] {
            let msg = sample(v);
            assert_eq!(
                CollisionMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap(),
                msg
            );
        }
        let mut lying = sample(GuardVerdict::Stop);
        lying.stop = false;
        assert!(matches!(
            CollisionMessage::from_bytes(&lying.to_bytes().unwrap()),
            Err(MessageError::Invalid { field: "stop", .. })
        ));
    }
}
