//! rmw_zenoh's wire contract (Jazzy 0.2.4 and later, Kilted, Rolling): the
//! key a topic's samples travel on, the liveliness tokens that put entities
//! in the ROS graph, the QoS string inside them, the attachment every sample
//! needs, and the gid derived from a token.

mod attachment;
mod error;
mod gid;
mod liveliness;
mod qos;
mod topic_key;

pub use attachment::{Attachment, ATTACHMENT_LEN, GID_LEN_MARKER};
pub use error::RmwError;
pub use gid::entity_gid;
pub use liveliness::{
    liveliness_subscription_key, EntityKind, LivelinessToken, TopicInfo, ADMIN_SPACE,
};
pub use qos::{Durability, History, QosProfile, Reliability, RMW_ZENOH_DEFAULT_DEPTH};
pub use topic_key::{topic_key, validate_topic_name};
