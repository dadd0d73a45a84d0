//! Joint-state messages: one arm's joint positions at one instant.

use super::blob::{decode, encode};
use super::error::MessageError;
use super::{check_finite, check_version, SCHEMA_VERSION};
use serde::{Deserialize, Serialize};

/// Joint positions of an arm (radians for revolute joints, metres for prismatic).
/// Small, so the positions travel as a plain MessagePack array.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointStateMessage {
    pub version: u16,
    pub stamp_ns: u64,
    pub sequence: u64,
    pub arm: String,
    pub names: Vec<String>,
    pub positions: Vec<f64>,
}

impl JointStateMessage {
    pub fn new(
        stamp_ns: u64,
        sequence: u64,
        arm: &str,
        names: Vec<String>,
        positions: Vec<f64>,
    ) -> Self {
        Self {
            version: SCHEMA_VERSION,
            stamp_ns,
            sequence,
            arm: arm.to_owned(),
            names,
            positions,
        }
    }

    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// Decodes and validates: version, one name per position, finite positions.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: Self = decode(bytes)?;
        check_version(msg.version)?;
        if msg.names.len() != msg.positions.len() {
            return Err(MessageError::Count {
                field: "positions",
                found: msg.positions.len(),
                expected: msg.names.len(),
            });
        }
        check_finite("positions", &msg.positions)?;
        Ok(msg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_rejects_mismatch_and_nan() {
        let msg =
            JointStateMessage::new(5, 1, "arm", vec!["a".into(), "b".into()], vec![0.1, -2.0]);
        let back = JointStateMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap();
        assert_eq!(back, msg);
        let mut bad = msg.clone();
        bad.positions.pop();
        assert!(matches!(
            JointStateMessage::from_bytes(&bad.to_bytes().unwrap()),
            Err(MessageError::Count { .. })
        ));
        let mut bad = msg;
        bad.positions[1] = f64::INFINITY;
        assert!(matches!(
            JointStateMessage::from_bytes(&bad.to_bytes().unwrap()),
            Err(MessageError::NonFinite { index: 1, .. })
        ));
    }
}
