//! The key-expression convention: every topic lives under `shroud/<namespace>/`,
//! followed by its kind and the name of the stream, e.g.
//! `shroud/demo/cloud/spheres` or `shroud/demo/surrogate/spheres`.
//!
//! | kind | key | payload |
//! |---|---|---|
//! | point clouds | `shroud/<ns>/cloud/<source>` | [`super::CloudMessage`] |
//! | surrogates | `shroud/<ns>/surrogate/<source>` | [`super::SurrogateMessage`] |
//! | joint states | `shroud/<ns>/joints/<arm>` | [`super::JointStateMessage`] |
//! | collision status | `shroud/<ns>/collision/<arm>` | [`super::CollisionMessage`] |
//! | node status | `shroud/<ns>/status/<node>` | [`super::NodeStatusMessage`] |
//! | blend commands | `shroud/<ns>/blend/<blender>` | [`super::BlendCommandMessage`] |
//! | smooth patches | `shroud/<ns>/smooth/<stream>` | [`super::SmoothPatchesMessage`] |
//! | node presence | `shroud/<ns>/alive/<node>` | liveliness token |

use super::error::MessageError;
use std::fmt;

/// The first chunk of every shroud key expression.
pub const ROOT: &str = "shroud";

/// What a topic carries; its name is the third chunk of the key.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TopicKind {
    Cloud,
    Surrogate,
    Joints,
    Collision,
    Status,
    Alive,
    Blend,
    Smooth,
}

impl TopicKind {
    /// The schema version of this kind's messages: joint states and
    /// collision messages are at 3 (velocities; the speed scale), every other
    /// kind at [`crate::SCHEMA_VERSION`].
    pub fn schema_version(self) -> u16 {
        match self {
            Self::Joints => crate::JointStateMessage::VERSION,
            Self::Collision => crate::CollisionMessage::VERSION,
            _ => crate::SCHEMA_VERSION,
        }
    }

    pub const ALL: [TopicKind; 8] = [
        Self::Cloud,
        Self::Surrogate,
        Self::Joints,
        Self::Collision,
        Self::Status,
        Self::Alive,
        Self::Blend,
        Self::Smooth,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            Self::Cloud => "cloud",
            Self::Surrogate => "surrogate",
            Self::Joints => "joints",
            Self::Collision => "collision",
            Self::Status => "status",
            Self::Alive => "alive",
            Self::Blend => "blend",
            Self::Smooth => "smooth",
        }
    }

    pub fn parse(chunk: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.as_str() == chunk)
    }

    /// The topic's documented quality of service (`docs/formats.md`), which
    /// every publisher of the kind uses.
    pub fn qos(self) -> TopicQos {
        use TopicPriority::{Bulk, Data, RealTime};
        let (congestion, priority) = match self {
            // Each supersedes the last: a sensor or fitter never waits for a
            // slow reader. Clouds are the bulk of the traffic: everything
            // else overtakes them in a congested link's queues.
            Self::Cloud => (Congestion::Drop, Bulk),
            Self::Status | Self::Smooth | Self::Alive => (Congestion::Drop, Data),
            // Superseding too, but the guard must get fresh ones first.
            Self::Surrogate | Self::Joints => (Congestion::Drop, RealTime),
            // A stop must never be discarded by a congested link.
            Self::Collision => (Congestion::Block, RealTime),
            // A commit or a clear must arrive.
            Self::Blend => (Congestion::Block, Data),
        };
        TopicQos {
            congestion,
            priority,
            express: priority == RealTime,
        }
    }
}

/// What a congested link does with a new message of a topic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Congestion {
    /// Drop it (the next one supersedes it).
    Drop,
    /// Block the publisher until it can be sent.
    Block,
}

/// Which of a link's queues a topic's messages wait in: a higher one is
/// always sent first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TopicPriority {
    /// What the guard and the arm decide with.
    RealTime,
    /// The default: statuses, models, commands.
    Data,
    /// Large and superseding: clouds.
    Bulk,
}

/// Per-topic quality of service, as plain data; the nodes map it to zenoh's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TopicQos {
    pub congestion: Congestion,
    /// Which of a link's queues its messages wait in.
    pub priority: TopicPriority,
    /// Sent at once rather than batched.
    pub express: bool,
}

impl fmt::Display for TopicKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Checks a namespace or stream name: one non-empty key chunk of ASCII letters,
/// digits, `-`, `_` and `.`. Wildcards and separators would change the meaning
/// of every key built from it, so they are refused rather than escaped.
pub fn check_name(field: &'static str, name: &str) -> Result<(), MessageError> {
    let ok = !name.is_empty()
        && name.len() <= 64
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || matches!(b, b'-' | b'_' | b'.'));
    if ok {
        Ok(())
    } else {
        Err(MessageError::Invalid {
            field,
            reason: format!(
                "{name:?} must be 1 to 64 characters of letters, digits, '-', '_' or '.'"
            ),
        })
    }
}

/// The stream that carries sector `index` of the surrogates of stream
/// `name`: a fit node with `sectors` publishes the whole view on `name` and
/// each sector on `name.s<index>`, and a guard with `sectors` reads them.
pub fn sector_stream(name: &str, index: usize) -> String {
    format!("{name}.s{index}")
}

/// Whether `name` is named as a sector's stream ([`sector_stream`]): it ends
/// in `.s` and digits.
pub fn is_sector_stream(name: &str) -> bool {
    name.rsplit_once(".s").is_some_and(|(base, index)| {
        !base.is_empty() && !index.is_empty() && index.bytes().all(|b| b.is_ascii_digit())
    })
}

#[cfg(test)]
mod sector_stream_tests {
    use super::*;

    #[test]
    fn sector_streams_are_named_and_recognised() {
        assert_eq!(sector_stream("cam", 3), "cam.s3");
        assert!(is_sector_stream(&sector_stream("front.cam", 15)));
        for name in ["cam", "cam.s", "cam.sx", ".s3", "cam.s3b", "cams3"] {
            assert!(!is_sector_stream(name), "{name}");
        }
    }
}

/// Builds keys of one namespace.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Topics {
    namespace: String,
}

impl Topics {
    pub fn new(namespace: &str) -> Result<Self, MessageError> {
        check_name("namespace", namespace)?;
        Ok(Self {
            namespace: namespace.to_owned(),
        })
    }

    pub fn namespace(&self) -> &str {
        &self.namespace
    }

    /// `shroud/<ns>/<kind>/<name>`; `name` may be `*` to match every stream.
    pub fn key(&self, kind: TopicKind, name: &str) -> Result<String, MessageError> {
        if name != "*" {
            check_name("stream name", name)?;
        }
        Ok(format!("{ROOT}/{}/{kind}/{name}", self.namespace))
    }

    /// Every topic of the namespace: `shroud/<ns>/**`.
    pub fn all(&self) -> String {
        format!("{ROOT}/{}/**", self.namespace)
    }
}

/// A parsed shroud key.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TopicKey {
    pub namespace: String,
    pub kind: TopicKind,
    pub name: String,
}

impl TopicKey {
    /// Parses `shroud/<ns>/<kind>/<name>`; `None` for a key outside the convention.
    pub fn parse(key: &str) -> Option<Self> {
        let mut chunks = key.split('/');
        let (root, ns, kind, name) = (
            chunks.next()?,
            chunks.next()?,
            chunks.next()?,
            chunks.next()?,
        );
        if root != ROOT || chunks.next().is_some() {
            return None;
        }
        check_name("namespace", ns).ok()?;
        check_name("stream name", name).ok()?;
        Some(Self {
            namespace: ns.to_owned(),
            kind: TopicKind::parse(kind)?,
            name: name.to_owned(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_stops_and_blend_commands_block_the_guards_inputs_are_urgent_and_clouds_bulk() {
        for kind in TopicKind::ALL {
            let qos = kind.qos();
            let blocks = qos.congestion == Congestion::Block;
            assert_eq!(
                blocks,
                matches!(kind, TopicKind::Collision | TopicKind::Blend),
                "{kind}"
            );
            let urgent = matches!(
                kind,
                TopicKind::Surrogate | TopicKind::Joints | TopicKind::Collision
            );
            let real_time = qos.priority == TopicPriority::RealTime;
            assert_eq!((real_time, qos.express), (urgent, urgent), "{kind}");
            let bulk = qos.priority == TopicPriority::Bulk;
            assert_eq!(bulk, kind == TopicKind::Cloud, "{kind}");
        }
    }

    #[test]
    fn keys_follow_the_convention_and_parse_back() {
        let t = Topics::new("lab-2").unwrap();
        let key = t.key(TopicKind::Surrogate, "spheres").unwrap();
        assert_eq!(key, "shroud/lab-2/surrogate/spheres");
        assert_eq!(
            TopicKey::parse(&key),
            Some(TopicKey {
                namespace: "lab-2".into(),
                kind: TopicKind::Surrogate,
                name: "spheres".into()
            })
        );
        assert_eq!(
            t.key(TopicKind::Cloud, "*").unwrap(),
            "shroud/lab-2/cloud/*"
        );
        assert_eq!(t.all(), "shroud/lab-2/**");
    }

    #[test]
    fn wildcards_separators_and_foreign_keys_are_refused() {
        for bad in ["", "a/b", "*", "**", "a b", "$x", &"n".repeat(65)] {
            assert!(Topics::new(bad).is_err(), "{bad:?}");
        }
        assert!(Topics::new("x")
            .unwrap()
            .key(TopicKind::Cloud, "a/b")
            .is_err());
        for foreign in [
            "robot/demo/cloud/a",
            "shroud/demo/pointcloud/a",
            "shroud/demo/cloud",
            "shroud/demo/cloud/a/extra",
        ] {
            assert_eq!(TopicKey::parse(foreign), None, "{foreign}");
        }
    }
}
