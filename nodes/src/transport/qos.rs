//! Publishers with their topic's documented quality of service
//! ([`TopicKind::qos`]): the one place that maps shroud's QoS table to zenoh's.

use anyhow::Result;
use shroud_msg::{Congestion, TopicKind, TopicPriority};
use zenoh::qos::{CongestionControl, Priority};
use zenoh::Wait;

/// A publisher on `key`, a topic of `kind`.
pub fn topic_publisher(
    session: &zenoh::Session,
    key: String,
    kind: TopicKind,
) -> Result<zenoh::pubsub::Publisher<'static>> {
    let qos = kind.qos();
    let congestion = match qos.congestion {
        Congestion::Drop => CongestionControl::Drop,
        Congestion::Block => CongestionControl::Block,
    };
    let priority = match qos.priority {
        TopicPriority::RealTime => Priority::RealTime,
        TopicPriority::Data => Priority::Data,
        TopicPriority::Bulk => Priority::DataLow,
    };
    session
        .declare_publisher(key.clone())
        .congestion_control(congestion)
        .priority(priority)
        .express(qos.express)
        .wait()
        .map_err(|e| anyhow::anyhow!("publisher {key}: {e}"))
}
