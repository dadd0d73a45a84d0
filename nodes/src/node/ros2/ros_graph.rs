//! The bridge as a node of the ROS 2 graph, the way rmw_zenoh makes one: a
//! liveliness token for the node and one per publisher and subscription
//! (`@ros2_lv/...`, which `ros2 node list` and `ros2 topic list` read),
//! publishers on rmw_zenoh's topic keys that attach the 33-byte
//! `(sequence, source timestamp, gid)` to every sample (rmw_zenoh drops a
//! sample without it), and subscribers that check it.

use anyhow::Result;
use shroud_ros2::rmw::{
    entity_gid, topic_key, Attachment, Durability, EntityKind, History, LivelinessToken,
    QosProfile, Reliability, TopicInfo,
};
use std::sync::atomic::{AtomicI64, AtomicU64, Ordering};
use zenoh::liveliness::LivelinessToken as ZenohToken;
use zenoh::qos::{CongestionControl, Priority};
use zenoh::Wait;

use crate::transport::unix_ns;

/// Where the bridge sits in the ROS graph.
#[derive(Debug, Clone)]
pub struct RosIdentity {
    pub domain_id: u32,
    pub namespace: String,
    pub node_name: String,
}

/// The bridge's node in the ROS graph: its token and the next entity id.
pub struct RosNode {
    session: zenoh::Session,
    identity: RosIdentity,
    zid: String,
    next_entity: AtomicU64,
    _token: ZenohToken,
}

/// One ROS topic of the bridge: its key, its type, and how it is delivered.
#[derive(Debug, Clone)]
pub struct RosTopic {
    pub name: String,
    pub type_name: &'static str,
    pub type_hash: &'static str,
    pub qos: QosProfile,
}

impl RosTopic {
    pub fn of<M: shroud_ros2::RosMessage>(name: &str, qos: QosProfile) -> Self {
        Self {
            name: name.to_owned(),
            type_name: M::TYPE_NAME,
            type_hash: M::TYPE_HASH,
            qos,
        }
    }
}

/// Reliable, volatile, the last `depth` kept (`QosProfile::DEFAULT` keeps 10).
pub fn reliable(depth: u32) -> QosProfile {
    QosProfile {
        reliability: Reliability::Reliable,
        durability: Durability::Volatile,
        history: History::KeepLast(depth),
    }
}

/// Reliable, transient local, the last one kept: how `/tf_static` is published.
pub fn latched() -> QosProfile {
    QosProfile {
        reliability: Reliability::Reliable,
        durability: Durability::TransientLocal,
        history: History::KeepLast(1),
    }
}

impl RosNode {
    pub fn declare(session: &zenoh::Session, identity: RosIdentity) -> Result<Self> {
        let zid = session.zid().to_string();
        let node = LivelinessToken {
            domain_id: identity.domain_id,
            zid: zid.clone(),
            node_id: 0,
            entity_id: 0,
            kind: EntityKind::Node,
            enclave: "/".into(),
            namespace: identity.namespace.clone(),
            node_name: identity.node_name.clone(),
            topic: None,
        };
        let token = declare_token(session, &node.to_keyexpr())?;
        Ok(Self {
            session: session.clone(),
            identity,
            zid,
            next_entity: AtomicU64::new(1),
            _token: token,
        })
    }

    /// The token of a new entity of `kind` on `topic`.
    fn entity(&self, kind: EntityKind, topic: &RosTopic) -> Result<(String, ZenohToken)> {
        let info = TopicInfo {
            name: topic.name.clone(),
            type_name: shroud_ros2::dds_type_name(topic.type_name)?,
            type_hash: topic.type_hash.to_owned(),
            qos: topic.qos,
        };
        let token = LivelinessToken {
            domain_id: self.identity.domain_id,
            zid: self.zid.clone(),
            node_id: 0,
            entity_id: self.next_entity.fetch_add(1, Ordering::Relaxed),
            kind,
            enclave: "/".into(),
            namespace: self.identity.namespace.clone(),
            node_name: self.identity.node_name.clone(),
            topic: Some(info),
        };
        let keyexpr = token.to_keyexpr();
        let declared = declare_token(&self.session, &keyexpr)?;
        Ok((keyexpr, declared))
    }

    /// rmw_zenoh's key of `topic`, with the type hash or, for a
    /// subscription that takes any distribution's definition, `*` in its
    /// place (rmw_zenoh's own subscribers match the hash exactly).
    fn key(&self, topic: &RosTopic, any_hash: bool) -> Result<String> {
        let dds = shroud_ros2::dds_type_name(topic.type_name)?;
        let topic_name = self.resolve(&topic.name);
        let key = topic_key(self.identity.domain_id, &topic_name, &dds, topic.type_hash)
            .map_err(|e| anyhow::anyhow!("ROS topic {}: {e}", topic.name))?;
        Ok(match (any_hash, key.rsplit_once('/')) {
            (true, Some((typed, _hash))) => format!("{typed}/*"),
            _ => key,
        })
    }

    /// A relative topic name inside the node's namespace.
    fn resolve(&self, name: &str) -> String {
        match (name.starts_with('/'), self.identity.namespace.as_str()) {
            (true, _) | (false, "/") => format!("/{}", name.trim_start_matches('/')),
            (false, ns) => format!("{}/{name}", ns.trim_end_matches('/')),
        }
    }

    /// A publisher on `topic`. It drops rather than blocks on a congested
    /// link, as rmw_zenoh's publishers do unless RELIABLE + KEEP_ALL
    /// (`rmw_publisher_data.cpp@3e19ec73`): verdicts are put from zenoh's
    /// callback, which must not wait on a slow ROS link, and a ROS consumer
    /// that misses a verdict halts by its deadman.
    pub fn publisher(&self, topic: &RosTopic, priority: Priority) -> Result<RosPublisher> {
        let key = self.key(topic, false)?;
        let (token_key, token) = self.entity(EntityKind::Publisher, topic)?;
        let publisher = self
            .session
            .declare_publisher(key.clone())
            .congestion_control(CongestionControl::Drop)
            .priority(priority)
            .wait()
            .map_err(|e| anyhow::anyhow!("ROS publisher {key}: {e}"))?;
        Ok(RosPublisher {
            publisher,
            gid: entity_gid(&token_key),
            sequence: AtomicI64::new(0),
            _token: token,
        })
    }

    /// Subscribes to `topic` (any type hash), handing each sample's
    /// payload and attachment to `handler` in zenoh's callback.
    pub fn subscribe(
        &self,
        topic: &RosTopic,
        handler: impl Fn(&str, &[u8], Option<&[u8]>) + Send + Sync + 'static,
    ) -> Result<RosSubscription> {
        let key = self.key(topic, true)?;
        let (_, token) = self.entity(EntityKind::Subscription, topic)?;
        let subscriber = self
            .session
            .declare_subscriber(key.clone())
            .callback(move |sample| {
                let payload = sample.payload().to_bytes();
                let attachment = sample.attachment().map(|a| a.to_bytes());
                handler(sample.key_expr().as_str(), &payload, attachment.as_deref());
            })
            .wait()
            .map_err(|e| anyhow::anyhow!("ROS subscription {key}: {e}"))?;
        Ok(RosSubscription {
            _subscriber: subscriber,
            _token: token,
        })
    }
}

fn declare_token(session: &zenoh::Session, keyexpr: &str) -> Result<ZenohToken> {
    session
        .liveliness()
        .declare_token(keyexpr.to_owned())
        .wait()
        .map_err(|e| anyhow::anyhow!("liveliness token {keyexpr}: {e}"))
}

/// A ROS publisher: puts CDR payloads with rmw_zenoh's attachment.
pub struct RosPublisher {
    publisher: zenoh::pubsub::Publisher<'static>,
    gid: [u8; 16],
    sequence: AtomicI64,
    _token: ZenohToken,
}

impl RosPublisher {
    /// Sends `payload` (CDR with its header); whether zenoh took it.
    pub fn put(&self, payload: Vec<u8>) -> Result<()> {
        let attachment = Attachment {
            sequence_number: self.sequence.fetch_add(1, Ordering::Relaxed) + 1,
            source_timestamp_ns: i64::try_from(unix_ns()).unwrap_or(i64::MAX),
            gid: self.gid,
        };
        self.publisher
            .put(payload)
            .attachment(attachment.encode().to_vec())
            .wait()
            .map_err(|e| anyhow::anyhow!("put {}: {e}", self.publisher.key_expr()))
    }
}

/// A ROS subscription, alive while it lives.
pub struct RosSubscription {
    _subscriber: zenoh::pubsub::Subscriber<()>,
    _token: ZenohToken,
}
