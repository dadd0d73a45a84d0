//! Collision-status messages: the guard's verdict for one arm pose against the
//! latest certified surrogate.

use super::blob::encode;
use super::error::MessageError;
use super::{check_finite, decode_versioned};
use serde::{Deserialize, Serialize};

/// One link's conservative clearance (metres; 0 when contact cannot be excluded).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LinkClearance {
    pub link: String,
    pub clearance: f64,
    /// The link's bound is set by space that no fresh surrogate saw (outside
    /// their domains, over trimmed triangles): an obstacle there was not seen,
    /// only not excluded.
    #[serde(default)]
    pub unobserved: bool,
}

/// Why the guard says stop or go.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GuardVerdict {
    /// Every link is farther than the stop distance, after the motion
    /// allowance, from what some fresh view saw occupied and (under
    /// `--unobserved stop`) from what it did not see.
    Clear,
    /// Some link is within the stop distance, or the joint state could not be
    /// checked at all (the `reason` says which).
    Stop,
    /// No certified surrogate has arrived yet: the guard cannot vouch for
    /// anything, so it stops.
    NoSurrogate,
    /// Every surrogate is older than the allowed age, measured on the guard's
    /// own clock plus the pipeline delay the upstream nodes measured.
    Stale,
    /// Some link is within the stop distance of space no fresh view saw (and
    /// of nothing a view saw occupied), and the guard's policy is
    /// `--unobserved stop`.
    Unobserved,
    /// Not sent by the guard: a verdict consumer's own state when no verdict
    /// for one of its recent joint states arrived in time (the deadman).
    NoVerdict,
}

impl GuardVerdict {
    /// Every verdict, in [`Self::index`] order.
    pub const ALL: [GuardVerdict; 6] = [
        Self::Clear,
        Self::Stop,
        Self::NoSurrogate,
        Self::Stale,
        Self::Unobserved,
        Self::NoVerdict,
    ];

    /// Position in [`Self::ALL`], for tables indexed by verdict.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The guard's status counter of this verdict (`verdict_stop`, ...).
    pub fn verdict_counter(self) -> &'static str {
        [
            "verdict_clear",
            "verdict_stop",
            "verdict_no_surrogate",
            "verdict_stale",
            "verdict_unobserved",
            "verdict_no_verdict",
        ][self.index()]
    }

    /// A verdict consumer's status counter of halts for this verdict
    /// (`halts_stop`, `halts_no_verdict`, ...).
    pub fn halt_counter(self) -> &'static str {
        [
            "halts_clear",
            "halts_stop",
            "halts_no_surrogate",
            "halts_stale",
            "halts_unobserved",
            "halts_no_verdict",
        ][self.index()]
    }

    /// The wire name (`clear`, `stop`, `no-surrogate`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Self::Clear => "clear",
            Self::Stop => "stop",
            Self::NoSurrogate => "no-surrogate",
            Self::Stale => "stale",
            Self::Unobserved => "unobserved",
            Self::NoVerdict => "no-verdict",
        }
    }
}

/// The guard's output for one joint state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CollisionMessage {
    pub version: u16,
    /// Stamp and sequence of the joint state checked (0 and `u64::MAX` when it
    /// could not be decoded).
    pub joints_stamp_ns: u64,
    pub joints_sequence: u64,
    pub arm: String,
    /// Stamp and sequence of the cloud behind the oldest surrogate used (0 if
    /// none). The stamp is the device's word, kept for the record only.
    pub surrogate_stamp_ns: u64,
    pub surrogate_sequence: u64,
    /// Age of the oldest surrogate used at the decision: time since it reached
    /// the guard (guard's monotonic clock) plus its `pipeline_ns`.
    pub surrogate_age_ns: u64,
    /// Fresh surrogate views the decision used.
    pub views: u32,
    pub verdict: GuardVerdict,
    /// `true` unless the verdict is `clear`.
    pub stop: bool,
    /// A human-readable reason for the verdict (empty for `clear`).
    pub reason: String,
    pub stop_distance: f64,
    /// Smallest link clearance, after the motion allowance
    /// (`--max-obstacle-speed` times the surrogate's age); 0 without a
    /// usable surrogate.
    pub min_clearance: f64,
    pub closest_link: String,
    /// Some link reaches unobserved space (see [`LinkClearance::unobserved`]).
    pub unobserved: bool,
    pub links: Vec<LinkClearance>,
    /// Wall time of the check, nanoseconds.
    pub check_ns: u64,
    /// The largest fraction, in [0, 1], of each joint's velocity limit the
    /// arm may move at until this verdict expires: in (0, 1] for `clear`, 0
    /// for every other verdict.
    pub speed_scale: f64,
    /// The link whose separation sets `speed_scale` (empty when nothing
    /// limits it below 1, or without a clearance report).
    pub limiting_link: String,
    /// Metres, finite and >= 0: the protective separation distance the
    /// limiting link needed at this scale (`stop_distance` when speed
    /// monitoring is off).
    pub protective_distance: f64,
}

impl CollisionMessage {
    /// The schema version of collision messages (version 3 added
    /// `speed_scale`, `limiting_link` and `protective_distance`); decoders
    /// refuse any other.
    pub const VERSION: u16 = 3;

    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// Decodes and validates: the version (first, so that a collision
    /// message of another version is refused as that), finite distances,
    /// `stop` and the speed scale agreeing with the verdict.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: Self = decode_versioned(bytes, "collision", Self::VERSION)?;
        let clearances: Vec<f64> = msg.links.iter().map(|l| l.clearance).collect();
        check_finite("links.clearance", &clearances)?;
        check_finite("stop_distance", &[msg.stop_distance])?;
        if msg.min_clearance.is_nan() {
            return Err(MessageError::NonFinite {
                field: "min_clearance",
                index: 0,
            });
        }
        if msg.verdict == GuardVerdict::NoVerdict {
            return Err(MessageError::Invalid {
                field: "verdict",
                reason: "no-verdict is a consumer's state, never a guard's message".into(),
            });
        }
        if msg.stop != (msg.verdict != GuardVerdict::Clear) {
            return Err(MessageError::Invalid {
                field: "stop",
                reason: format!("stop = {} contradicts verdict {:?}", msg.stop, msg.verdict),
            });
        }
        check_speed_scale(msg.speed_scale, msg.verdict)?;
        if !(msg.protective_distance.is_finite() && msg.protective_distance >= 0.0) {
            return Err(MessageError::Invalid {
                field: "protective_distance",
                reason: format!("{} is not a finite distance >= 0", msg.protective_distance),
            });
        }
        Ok(msg)
    }
}

/// A speed scale is a fraction in [0, 1], above 0 exactly for `clear`.
fn check_speed_scale(scale: f64, verdict: GuardVerdict) -> Result<(), MessageError> {
    let invalid = |reason: String| {
        Err(MessageError::Invalid {
            field: "speed_scale",
            reason,
        })
    };
    if !scale.is_finite() {
        invalid(format!("{scale} is not finite"))
    } else if !(0.0..=1.0).contains(&scale) {
        invalid(format!("{scale} is outside [0, 1]"))
    } else if verdict == GuardVerdict::Clear && scale == 0.0 {
        invalid("a clear verdict carries a scale in (0, 1], not 0".into())
    } else if verdict != GuardVerdict::Clear && scale > 0.0 {
        invalid(format!(
            "{scale} with verdict {}: every verdict but clear carries 0",
            verdict.name()
        ))
    } else {
        Ok(())
    }
}

/// A collision message with this verdict, for tests of consumers.
/// Public only for the tests of other crates.
#[doc(hidden)]
pub fn sample_collision(verdict: GuardVerdict) -> CollisionMessage {
    CollisionMessage {
        version: CollisionMessage::VERSION,
        joints_stamp_ns: 1,
        joints_sequence: 2,
        arm: "arm".into(),
        surrogate_stamp_ns: 3,
        surrogate_sequence: 4,
        surrogate_age_ns: 5,
        views: 1,
        verdict,
        stop: verdict != GuardVerdict::Clear,
        reason: String::new(),
        stop_distance: 0.05,
        min_clearance: 0.2,
        closest_link: "wrist".into(),
        unobserved: false,
        links: vec![LinkClearance {
            link: "wrist".into(),
            clearance: 0.2,
            unobserved: false,
        }],
        check_ns: 900,
        speed_scale: if verdict == GuardVerdict::Clear {
            1.0
        } else {
            0.0
        },
        limiting_link: String::new(),
        protective_distance: 0.05,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mutation::{assert_named, mutated};
    use proptest::prelude::*;

    #[test]
    fn round_trips_and_checks_consistency() {
        for v in [
            GuardVerdict::Clear,
            GuardVerdict::Stop,
            GuardVerdict::NoSurrogate,
            GuardVerdict::Stale,
            GuardVerdict::Unobserved,
        ] {
            let msg = sample_collision(v);
            assert_eq!(
                CollisionMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap(),
                msg
            );
        }
        let mut lying = sample_collision(GuardVerdict::Stop);
        lying.stop = false;
        assert!(matches!(
            CollisionMessage::from_bytes(&lying.to_bytes().unwrap()),
            Err(MessageError::Invalid { field: "stop", .. })
        ));
        let consumer_state = sample_collision(GuardVerdict::NoVerdict);
        assert!(matches!(
            CollisionMessage::from_bytes(&consumer_state.to_bytes().unwrap()),
            Err(MessageError::Invalid {
                field: "verdict",
                ..
            })
        ));
    }

    /// The verdicts a guard sends.
    const SENT: [GuardVerdict; 5] = [
        GuardVerdict::Clear,
        GuardVerdict::Stop,
        GuardVerdict::NoSurrogate,
        GuardVerdict::Stale,
        GuardVerdict::Unobserved,
    ];

    fn decode(msg: &CollisionMessage) -> Result<CollisionMessage, MessageError> {
        CollisionMessage::from_bytes(&msg.to_bytes().unwrap())
    }

    /// The field and reason of an `Invalid` error, or the error.
    fn invalid(msg: &CollisionMessage) -> (&'static str, String) {
        match decode(msg) {
            Err(MessageError::Invalid { field, reason }) => (field, reason),
            other => panic!("not refused as invalid: {other:?}"),
        }
    }

    #[test]
    fn round_trips_a_scaled_clear_with_its_limiting_link() {
        let mut msg = sample_collision(GuardVerdict::Clear);
        assert_eq!(msg.version, CollisionMessage::VERSION);
        assert_eq!(msg.speed_scale, 1.0);
        (msg.speed_scale, msg.limiting_link, msg.protective_distance) = (0.4, "wrist".into(), 0.31);
        assert_eq!(decode(&msg).unwrap(), msg);
        for v in SENT.into_iter().skip(1) {
            assert_eq!(sample_collision(v).speed_scale, 0.0);
        }
        // The smallest positive scale is a clear's; 0 is every other verdict's.
        msg.speed_scale = f64::MIN_POSITIVE;
        assert_eq!(decode(&msg).unwrap(), msg);
    }

    #[test]
    fn refuses_a_speed_scale_out_of_range_or_against_the_verdict() {
        for scale in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut msg = sample_collision(GuardVerdict::Clear);
            msg.speed_scale = scale;
            let (field, reason) = invalid(&msg);
            assert_eq!(
                (field, reason.contains("not finite")),
                ("speed_scale", true)
            );
        }
        for (verdict, scale) in [
            (GuardVerdict::Clear, 1.5),
            (GuardVerdict::Clear, -0.25),
            (GuardVerdict::Stop, -1.0),
        ] {
            let mut msg = sample_collision(verdict);
            msg.speed_scale = scale;
            let (field, reason) = invalid(&msg);
            assert_eq!(field, "speed_scale");
            assert!(reason.contains("outside [0, 1]"), "{reason}");
        }
        let mut stopped_clear = sample_collision(GuardVerdict::Clear);
        stopped_clear.speed_scale = 0.0;
        let (field, reason) = invalid(&stopped_clear);
        assert_eq!(field, "speed_scale");
        assert!(reason.contains("clear"), "{reason}");
        for verdict in SENT.into_iter().skip(1) {
            let mut moving_stop = sample_collision(verdict);
            moving_stop.speed_scale = 0.5;
            let (field, reason) = invalid(&moving_stop);
            assert_eq!(field, "speed_scale");
            assert!(reason.contains(verdict.name()), "{reason}");
        }
    }

    #[test]
    fn refuses_a_protective_distance_that_is_not_a_finite_distance() {
        for distance in [-0.01, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut msg = sample_collision(GuardVerdict::Stop);
            msg.protective_distance = distance;
            assert_eq!(invalid(&msg).0, "protective_distance");
        }
        let mut msg = sample_collision(GuardVerdict::Stop);
        msg.protective_distance = 0.0;
        assert_eq!(decode(&msg).unwrap(), msg);
    }

    #[test]
    fn another_version_is_refused_by_name() {
        for version in [0, 1, 2, 4, u16::MAX] {
            let mut msg = sample_collision(GuardVerdict::Clear);
            msg.version = version;
            let err = decode(&msg).unwrap_err();
            assert_eq!(
                err,
                MessageError::Version {
                    message: "collision",
                    found: version,
                    expected: 3,
                }
            );
            assert_eq!(
                err.to_string(),
                format!("collision message version {version}, this build reads version 3")
            );
        }
    }

    #[test]
    fn an_older_builds_message_is_refused_as_version_2_not_as_malformed() {
        // A version 2 message, as an older guard sends it: without the
        // fields version 3 added.
        let mut old = serde_json::to_value(sample_collision(GuardVerdict::Stop)).unwrap();
        let fields = old.as_object_mut().unwrap();
        for field in ["speed_scale", "limiting_link", "protective_distance"] {
            fields.remove(field).unwrap();
        }
        old["version"] = 2.into();
        let bytes = encode(&old).unwrap();
        assert_eq!(
            CollisionMessage::from_bytes(&bytes),
            Err(MessageError::Version {
                message: "collision",
                found: 2,
                expected: 3,
            })
        );
        old["version"] = 3.into();
        assert!(matches!(
            CollisionMessage::from_bytes(&encode(&old).unwrap()),
            Err(MessageError::Malformed(_))
        ));
    }

    /// Valid version 3 collision messages of every verdict a guard sends.
    fn valid() -> impl Strategy<Value = CollisionMessage> {
        let link = ("[a-z_]{0,8}", 0.0..2.0f64, any::<bool>()).prop_map(
            |(link, clearance, unobserved)| LinkClearance {
                link,
                clearance,
                unobserved,
            },
        );
        (
            proptest::sample::select(SENT.to_vec()),
            proptest::collection::vec(link, 0..4),
            (f64::MIN_POSITIVE..=1.0, 0.0..1.0f64, 0.0..3.0f64),
            ("[a-z_]{0,8}", "[ -~]{0,16}", any::<u64>(), any::<u32>()),
        )
            .prop_map(
                |(
                    verdict,
                    links,
                    (scale, stop_distance, protective),
                    (limiting, reason, ns, views),
                )| {
                    let mut msg = sample_collision(verdict);
                    msg.speed_scale = if verdict == GuardVerdict::Clear {
                        scale
                    } else {
                        0.0
                    };
                    (msg.stop_distance, msg.protective_distance) = (stop_distance, protective);
                    (msg.limiting_link, msg.reason, msg.check_ns, msg.views) =
                        (limiting, reason, ns, views);
                    msg.min_clearance = links.iter().map(|l| l.clearance).fold(0.0, f64::max);
                    msg.links = links;
                    msg
                },
            )
    }

    proptest! {
        // Cheap (microseconds a case), and most mutations only break the
        // MessagePack structure: many cases, so that enough reach the checks.
        #![proptest_config(ProptestConfig::with_cases(2048))]

        #[test]
        fn valid_collision_messages_round_trip(msg in valid()) {
            prop_assert_eq!(decode(&msg).unwrap(), msg);
        }

        #[test]
        fn mutated_collision_messages_decode_valid_or_fail_by_name(
            bytes in valid().prop_flat_map(|m| mutated(m.to_bytes().unwrap()))
        ) {
            match CollisionMessage::from_bytes(&bytes) {
                Ok(msg) => {
                    prop_assert_eq!(msg.version, CollisionMessage::VERSION);
                    prop_assert!(msg.verdict != GuardVerdict::NoVerdict);
                    prop_assert_eq!(msg.stop, msg.verdict != GuardVerdict::Clear);
                    prop_assert!((0.0..=1.0).contains(&msg.speed_scale));
                    prop_assert_eq!(msg.speed_scale > 0.0, msg.verdict == GuardVerdict::Clear);
                    prop_assert!(msg.protective_distance.is_finite() && msg.protective_distance >= 0.0);
                    prop_assert!(msg.stop_distance.is_finite());
                    prop_assert!(msg.links.iter().all(|l| l.clearance.is_finite()));
                    prop_assert!(!msg.min_clearance.is_nan());
                    let again = decode(&msg).unwrap();
                    prop_assert_eq!(format!("{again:?}"), format!("{msg:?}"));
                }
                Err(err) => assert_named(&err, "collision", &[
                    "links.clearance",
                    "stop_distance",
                    "min_clearance",
                    "verdict",
                    "stop",
                    "speed_scale",
                    "protective_distance",
                ]),
            }
        }
    }

    #[test]
    fn verdict_names_are_the_wire_names() {
        for (i, v) in GuardVerdict::ALL.into_iter().enumerate() {
            assert_eq!(v.index(), i);
            let json = serde_json::to_string(&v).unwrap();
            assert_eq!(json, format!("\"{}\"", v.name()));
            // Counters are the wire name in snake case behind their prefix.
            let snake = v.name().replace('-', "_");
            assert_eq!(v.verdict_counter(), format!("verdict_{snake}"));
            assert_eq!(v.halt_counter(), format!("halts_{snake}"));
        }
    }
}
