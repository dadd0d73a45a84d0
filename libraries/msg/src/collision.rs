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
        Ok(msg)
    }
}

/// A collision message with this verdict, for tests of consumers.
/// Public only for the tests of other crates.
#[doc(hidden)]
pub fn sample_collision(verdict: GuardVerdict) -> CollisionMessage {
    CollisionMessage {
        version: super::SCHEMA_VERSION,
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
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
