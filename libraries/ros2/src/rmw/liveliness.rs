//! Liveliness tokens, which put nodes, publishers and subscriptions in the
//! ROS graph (liveliness_utils.cpp@3411fdec, `Entity::Entity` and
//! `Entity::make`; graph_cache.cpp@49db0109):
//! `@ros2_lv/<domain>/<zid>/<node_id>/<entity_id>/<kind>/<enclave>/<namespace>/<node>`
//! then, for every kind but a node, `/<topic>/<DDS type>/<type hash>/<qos>`.
//! Names are "mangled": every '/' becomes '%' (the root namespace and the
//! default enclave `/` become `%`).

use super::error::RmwError;
use super::qos::QosProfile;
use crate::msgs::{dds_type_name, RosMessage};

/// The admin space every token starts with.
pub const ADMIN_SPACE: &str = "@ros2_lv";
/// A node token's segments (admin space to node name).
const NODE_SEGMENTS: usize = 9;
/// Any other token's segments (with topic, type, hash and QoS).
const ENTITY_SEGMENTS: usize = 13;

/// The key expression matching every token of `domain_id`.
pub fn liveliness_subscription_key(domain_id: u32) -> String {
    format!("{ADMIN_SPACE}/{domain_id}/**")
}

/// What a token announces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EntityKind {
    Node,
    Publisher,
    Subscription,
    ServiceServer,
    ServiceClient,
}

impl EntityKind {
    const ALL: [Self; 5] = [
        Self::Node,
        Self::Publisher,
        Self::Subscription,
        Self::ServiceServer,
        Self::ServiceClient,
    ];

    /// The token's kind segment.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Node => "NN",
            Self::Publisher => "MP",
            Self::Subscription => "MS",
            Self::ServiceServer => "SS",
            Self::ServiceClient => "SC",
        }
    }

    fn parse(segment: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|kind| kind.as_str() == segment)
    }
}

/// The topic (or service) part of a non-node token.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TopicInfo {
    /// The fully qualified ROS name, `/shroud/cloud`.
    pub name: String,
    /// The DDS type name, as tokens carry it: `sensor_msgs::msg::dds_::PointCloud2_`.
    pub type_name: String,
    /// `RIHS01_…`.
    pub type_hash: String,
    pub qos: QosProfile,
}

impl TopicInfo {
    /// The topic `name` carrying messages of type `M`.
    pub fn for_message<M: RosMessage>(name: &str, qos: QosProfile) -> Self {
        Self {
            name: name.to_string(),
            type_name: dds_type_name(M::TYPE_NAME).expect("RosMessage type names are well formed"),
            type_hash: M::TYPE_HASH.to_string(),
            qos,
        }
    }
}

/// One liveliness token. Its text fields must not be empty (rmw_zenoh
/// rejects a token with an empty segment) nor hold '%' ([`Self::parse`]
/// reads every '%' back as '/').
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LivelinessToken {
    pub domain_id: u32,
    /// The zenoh session's id, as `zid.to_string()` writes it.
    pub zid: String,
    pub node_id: u64,
    /// The entity's id within the session (a node's is its `node_id`).
    pub entity_id: u64,
    pub kind: EntityKind,
    /// The security enclave, `/` by default.
    pub enclave: String,
    /// The node's namespace, `/` for the root.
    pub namespace: String,
    pub node_name: String,
    /// Present for every kind but [`EntityKind::Node`].
    pub topic: Option<TopicInfo>,
}

impl LivelinessToken {
    /// The token's key expression.
    pub fn to_keyexpr(&self) -> String {
        let mut keyexpr = format!(
            "{ADMIN_SPACE}/{}/{}/{}/{}/{}/{}/{}/{}",
            self.domain_id,
            self.zid,
            self.node_id,
            self.entity_id,
            self.kind.as_str(),
            mangle(&self.enclave),
            mangle(&self.namespace),
            mangle(&self.node_name),
        );
        if let Some(topic) = &self.topic {
            keyexpr += &format!(
                "/{}/{}/{}/{}",
                mangle(&topic.name),
                mangle(&topic.type_name),
                mangle(&topic.type_hash),
                topic.qos.to_keyexpr()
            );
        }
        keyexpr
    }

    /// Reads a token as rmw_zenoh's `Entity::make` does, but exactly: 9
    /// segments for a node, 13 for any other kind, none empty.
    pub fn parse(keyexpr: &str) -> Result<Self, RmwError> {
        let error = |problem: String| RmwError::Token {
            token: keyexpr.to_string(),
            problem,
        };
        let segments: Vec<&str> = keyexpr.split('/').collect();
        if let Some(index) = segments.iter().position(|s| s.is_empty()) {
            return Err(error(format!("segment {index} is empty")));
        }
        if segments.len() < NODE_SEGMENTS {
            return Err(error(format!(
                "{} segments, needs at least {NODE_SEGMENTS}",
                segments.len()
            )));
        }
        if segments[0] != ADMIN_SPACE {
            return Err(error(format!("does not start with {ADMIN_SPACE}")));
        }
        let kind = EntityKind::parse(segments[5]).ok_or_else(|| {
            error(format!(
                "kind {:?} is not NN, MP, MS, SS or SC",
                segments[5]
            ))
        })?;
        let expected = if kind == EntityKind::Node {
            NODE_SEGMENTS
        } else {
            ENTITY_SEGMENTS
        };
        if segments.len() != expected {
            return Err(error(format!(
                "{} segments, a {} token has {expected}",
                segments.len(),
                kind.as_str()
            )));
        }
        let topic = match kind {
            EntityKind::Node => None,
            _ => Some(TopicInfo {
                name: demangle(segments[9]),
                type_name: demangle(segments[10]),
                type_hash: demangle(segments[11]),
                qos: QosProfile::parse(segments[12]).map_err(|e| error(e.to_string()))?,
            }),
        };
        Ok(Self {
            domain_id: parse_number(segments[1], "domain id").map_err(error)?,
            zid: segments[2].to_string(),
            node_id: parse_number(segments[3], "node id").map_err(error)?,
            entity_id: parse_number(segments[4], "entity id").map_err(error)?,
            kind,
            enclave: demangle(segments[6]),
            namespace: demangle(segments[7]),
            node_name: demangle(segments[8]),
            topic,
        })
    }
}

/// A decimal number, digits only (as rmw_zenoh's `std::stoul` reads it).
fn parse_number<T: std::str::FromStr>(segment: &str, what: &str) -> Result<T, String> {
    let digits = segment.bytes().all(|b| b.is_ascii_digit());
    digits
        .then(|| segment.parse().ok())
        .flatten()
        .ok_or_else(|| format!("{what} {segment:?} is not a decimal number in range"))
}

/// rmw_zenoh's `mangle_name`: every '/' becomes '%'.
fn mangle(name: &str) -> String {
    name.replace('/', "%")
}

/// rmw_zenoh's `demangle_name`: every '%' becomes '/'.
fn demangle(segment: &str) -> String {
    segment.replace('%', "/")
}
