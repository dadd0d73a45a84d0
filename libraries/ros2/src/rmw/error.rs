//! Why a topic name, QoS string, liveliness token or attachment was refused.

/// An rmw_zenoh key, token or attachment that is not well formed; each
/// variant quotes the input and says what is wrong with it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RmwError {
    #[error("topic name {name:?}: {problem}")]
    TopicName { name: String, problem: &'static str },
    #[error("topic key: {part} {value:?} {problem}")]
    KeyPart {
        part: &'static str,
        value: String,
        problem: &'static str,
    },
    #[error("QoS {qos:?}: {problem}")]
    Qos { qos: String, problem: String },
    #[error("liveliness token {token:?}: {problem}")]
    Token { token: String, problem: String },
    #[error(
        "attachment: {len} bytes, rmw_zenoh's has 33 \
         (i64 sequence number, i64 source timestamp, 0x10, 16-byte gid)"
    )]
    AttachmentLength { len: usize },
    #[error("attachment: byte 16 is {found:#04x}, not 0x10 (the length of the 16-byte gid)")]
    AttachmentGidMarker { found: u8 },
}
