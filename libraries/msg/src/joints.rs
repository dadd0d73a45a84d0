//! Joint-state messages: one arm's joint positions, and velocities when its
//! source measures them, at one instant.

use super::blob::encode;
use super::error::MessageError;
use super::{check_finite, decode_versioned};
use serde::{Deserialize, Serialize};

/// Joint positions of an arm (radians for revolute joints, metres for
/// prismatic) and, when the source measures them, velocities (rad/s, m/s).
/// Small, so the values travel as plain MessagePack arrays.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointStateMessage {
    pub version: u16,
    pub stamp_ns: u64,
    pub sequence: u64,
    pub arm: String,
    pub names: Vec<String>,
    pub positions: Vec<f64>,
    /// Empty when the source measures no velocities, otherwise one per name
    /// (rad/s for revolute joints, m/s for prismatic), all finite.
    pub velocities: Vec<f64>,
}

impl JointStateMessage {
    /// The schema version of joint states (version 3 added `velocities`);
    /// decoders refuse any other.
    pub const VERSION: u16 = 3;

    /// A joint state without velocities (add them with [`Self::with_velocities`]).
    pub fn new(
        stamp_ns: u64,
        sequence: u64,
        arm: &str,
        names: Vec<String>,
        positions: Vec<f64>,
    ) -> Self {
        Self {
            version: Self::VERSION,
            stamp_ns,
            sequence,
            arm: arm.to_owned(),
            names,
            positions,
            velocities: Vec::new(),
        }
    }

    /// The same joint state with these measured velocities, one per name
    /// (not checked here: [`Self::from_bytes`] checks them).
    pub fn with_velocities(self, velocities: Vec<f64>) -> Self {
        Self { velocities, ..self }
    }

    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// Decodes and validates: the version (first, so that a joint state of
    /// another version is refused as that), one name per position, finite
    /// positions, and either no velocities or one finite velocity per name.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: Self = decode_versioned(bytes, "joint state", Self::VERSION)?;
        if msg.names.len() != msg.positions.len() {
            return Err(MessageError::Count {
                field: "positions",
                found: msg.positions.len(),
                expected: msg.names.len(),
            });
        }
        check_finite("positions", &msg.positions)?;
        if !msg.velocities.is_empty() && msg.velocities.len() != msg.names.len() {
            return Err(MessageError::Count {
                field: "velocities",
                found: msg.velocities.len(),
                expected: msg.names.len(),
            });
        }
        check_finite("velocities", &msg.velocities)?;
        Ok(msg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mutation::{assert_named, mutated};
    use proptest::prelude::*;

    fn two_joints() -> JointStateMessage {
        JointStateMessage::new(5, 1, "arm", vec!["a".into(), "b".into()], vec![0.1, -2.0])
    }

    fn decode(msg: &JointStateMessage) -> Result<JointStateMessage, MessageError> {
        JointStateMessage::from_bytes(&msg.to_bytes().unwrap())
    }

    #[test]
    fn round_trips_and_rejects_mismatch_and_nan() {
        let msg = two_joints();
        assert_eq!(msg.version, JointStateMessage::VERSION);
        assert!(msg.velocities.is_empty());
        assert_eq!(decode(&msg).unwrap(), msg);
        let mut bad = msg.clone();
        bad.positions.pop();
        assert!(matches!(
            decode(&bad),
            Err(MessageError::Count {
                field: "positions",
                ..
            })
        ));
        let mut bad = msg;
        bad.positions[1] = f64::INFINITY;
        assert!(matches!(
            decode(&bad),
            Err(MessageError::NonFinite { index: 1, .. })
        ));
    }

    #[test]
    fn round_trips_velocities_and_refuses_a_wrong_count_or_a_non_finite_one() {
        let msg = two_joints().with_velocities(vec![0.5, -1.25]);
        assert_eq!(msg.velocities, [0.5, -1.25]);
        assert_eq!(decode(&msg).unwrap(), msg);
        for velocities in [vec![0.5], vec![0.5, 0.0, 1.0]] {
            let found = velocities.len();
            assert_eq!(
                decode(&two_joints().with_velocities(velocities)),
                Err(MessageError::Count {
                    field: "velocities",
                    found,
                    expected: 2,
                })
            );
        }
        for value in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                decode(&two_joints().with_velocities(vec![0.0, value])),
                Err(MessageError::NonFinite {
                    field: "velocities",
                    index: 1,
                })
            );
        }
    }

    #[test]
    fn another_version_is_refused_by_name() {
        for version in [0, 1, 2, 4, u16::MAX] {
            let mut msg = two_joints();
            msg.version = version;
            let err = decode(&msg).unwrap_err();
            assert_eq!(
                err,
                MessageError::Version {
                    message: "joint state",
                    found: version,
                    expected: 3,
                }
            );
            assert_eq!(
                err.to_string(),
                format!("joint state message version {version}, this build reads version 3")
            );
        }
    }

    /// A version 2 joint state, as an older build sends it: no `velocities`.
    #[derive(Serialize)]
    struct Version2 {
        version: u16,
        stamp_ns: u64,
        sequence: u64,
        arm: String,
        names: Vec<String>,
        positions: Vec<f64>,
    }

    #[test]
    fn an_older_builds_joint_state_is_refused_as_version_2_not_as_malformed() {
        let old = Version2 {
            version: 2,
            stamp_ns: 5,
            sequence: 1,
            arm: "arm".into(),
            names: vec!["a".into()],
            positions: vec![0.1],
        };
        let bytes = encode(&old).unwrap();
        assert_eq!(
            JointStateMessage::from_bytes(&bytes),
            Err(MessageError::Version {
                message: "joint state",
                found: 2,
                expected: 3,
            })
        );
        // Without the version check first it would be malformed (a missing
        // field), as a version 3 message without velocities is.
        let missing = Version2 { version: 3, ..old };
        assert!(matches!(
            JointStateMessage::from_bytes(&encode(&missing).unwrap()),
            Err(MessageError::Malformed(_))
        ));
    }

    /// Valid version 3 joint states: 0 to 6 joints, with or without velocities.
    fn valid() -> impl Strategy<Value = JointStateMessage> {
        (0usize..7, any::<bool>(), any::<u64>(), any::<u64>()).prop_flat_map(
            |(n, moving, stamp_ns, sequence)| {
                let values = proptest::collection::vec(-10.0..10.0f64, n);
                (values.clone(), values).prop_map(move |(positions, velocities)| {
                    let names = (0..n).map(|i| format!("joint_{i}")).collect();
                    let msg = JointStateMessage::new(stamp_ns, sequence, "arm", names, positions);
                    if moving {
                        msg.with_velocities(velocities)
                    } else {
                        msg
                    }
                })
            },
        )
    }

    proptest! {
        // Cheap (microseconds a case), and most mutations only break the
        // MessagePack structure: many cases, so that enough reach the checks.
        #![proptest_config(ProptestConfig::with_cases(2048))]

        #[test]
        fn valid_joint_states_round_trip(msg in valid()) {
            prop_assert_eq!(decode(&msg).unwrap(), msg);
        }

        #[test]
        fn mutated_joint_states_decode_valid_or_fail_by_name(
            bytes in valid().prop_flat_map(|m| mutated(m.to_bytes().unwrap()))
        ) {
            match JointStateMessage::from_bytes(&bytes) {
                Ok(msg) => {
                    prop_assert_eq!(msg.version, JointStateMessage::VERSION);
                    prop_assert_eq!(msg.positions.len(), msg.names.len());
                    prop_assert!(msg.positions.iter().all(|v| v.is_finite()));
                    prop_assert!(msg.velocities.is_empty() || msg.velocities.len() == msg.names.len());
                    prop_assert!(msg.velocities.iter().all(|v| v.is_finite()));
                    prop_assert_eq!(&decode(&msg).unwrap(), &msg);
                }
                Err(err) => assert_named(&err, "joint state", &["positions", "velocities"]),
            }
        }
    }
}
