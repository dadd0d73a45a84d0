//! How shroud's messages are laid out in an MCAP file (documented in
//! `docs/formats.md`, "MCAP recordings"): one channel per zenoh key, named by
//! the key itself, with message encoding `msgpack` (the payload exactly as it
//! travelled) and one schema per message type (`shroud.CloudMessage`...,
//! schema encoding `shroud-msgpack`, whose data names the schema version);
//! and the metadata record that describes the recording.

use super::error::RecordError;
use shroud_msg::{TopicKey, TopicKind, SCHEMA_VERSION};
use std::collections::BTreeMap;

/// The MCAP message encoding of shroud's channels (registered in the MCAP
/// well-known encodings).
pub const MESSAGE_ENCODING: &str = "msgpack";
/// The schema encoding of shroud's schemas (not a well-known one: viewers
/// show these channels as undecodable; they are for `shroud replay`).
pub const SCHEMA_ENCODING: &str = "shroud-msgpack";
/// The name of the metadata record every recording starts with.
pub const RECORDING_METADATA: &str = "shroud.recording";

/// A schema record's content.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SchemaRecord {
    pub name: String,
    pub encoding: &'static str,
    pub data: Vec<u8>,
}

/// The schema of a topic kind's messages: `shroud.<Type>`, its data a JSON
/// object naming the kind's schema version ([`TopicKind::schema_version`])
/// and where it is specified.
pub fn schema_for(kind: TopicKind) -> SchemaRecord {
    let data = format!(
        // "specification" is a frozen identifier in every recording of schema 2 (the
        // specification now lives in docs/formats.md): a recording's bytes do not
        // change with the repository's layout.
        "{{\"schema_version\":{},\"specification\":\"core/FORMATS.md\",\"topic_kind\":\"{kind}\"}}",
        kind.schema_version()
    );
    SchemaRecord {
        name: format!("shroud.{}", type_name(kind)),
        encoding: SCHEMA_ENCODING,
        data: data.into_bytes(),
    }
}

fn type_name(kind: TopicKind) -> &'static str {
    match kind {
        TopicKind::Cloud => "CloudMessage",
        TopicKind::Surrogate => "SurrogateMessage",
        TopicKind::Joints => "JointStateMessage",
        TopicKind::Collision => "CollisionMessage",
        TopicKind::Status => "NodeStatusMessage",
        TopicKind::Blend => "BlendCommandMessage",
        TopicKind::Smooth => "SmoothPatchesMessage",
        TopicKind::Alive => "LivelinessToken",
    }
}

/// A channel's metadata: the key's parts, so that a reader need not parse
/// the topic.
pub fn channel_metadata(key: &TopicKey) -> BTreeMap<String, String> {
    BTreeMap::from([
        ("shroud.namespace".to_owned(), key.namespace.clone()),
        ("shroud.kind".to_owned(), key.kind.to_string()),
        ("shroud.name".to_owned(), key.name.clone()),
    ])
}

/// The recording's metadata record: what was recorded, by which shroud, and
/// where the publish times come from.
pub fn recording_metadata(
    namespace: &str,
    topics: &str,
    shroud_version: &str,
) -> BTreeMap<String, String> {
    BTreeMap::from([
        ("namespace".to_owned(), namespace.to_owned()),
        ("topics".to_owned(), topics.to_owned()),
        ("shroud_version".to_owned(), shroud_version.to_owned()),
        ("schema_version".to_owned(), SCHEMA_VERSION.to_string()),
        (
            "log_time".to_owned(),
            "receive time on the recorder's wall clock, ns since the Unix epoch".to_owned(),
        ),
        (
            "publish_time".to_owned(),
            "the zenoh sample's timestamp when it has one, else the log time".to_owned(),
        ),
    ])
}

/// What replay needs of a channel: its encodings, its schema, its topic.
#[derive(Debug, Clone, Copy)]
pub struct ChannelDescription<'a> {
    pub topic: &'a str,
    pub message_encoding: &'a str,
    pub schema_name: &'a str,
    pub schema_encoding: &'a str,
    pub schema_data: &'a [u8],
}

/// The key a channel replays to: `Ok(None)` for a channel that is not one of
/// shroud's (e.g. a Foxglove channel for viewers), an error for a shroud
/// channel that this shroud cannot replay (another schema version, a
/// schema that does not fit its topic).
pub fn replayable(channel: &ChannelDescription<'_>) -> Result<Option<TopicKey>, RecordError> {
    if channel.message_encoding != MESSAGE_ENCODING || channel.schema_encoding != SCHEMA_ENCODING {
        return Ok(None);
    }
    let fail = |reason: String| RecordError::Channel {
        topic: channel.topic.to_owned(),
        reason,
    };
    let key = TopicKey::parse(channel.topic)
        .ok_or_else(|| fail("not a shroud/<namespace>/<kind>/<name> key".into()))?;
    let expected = schema_for(key.kind);
    if channel.schema_name != expected.name {
        return Err(fail(format!(
            "schema {:?} does not describe {} messages ({:?})",
            channel.schema_name, key.kind, expected.name
        )));
    }
    let version = schema_version(channel.schema_data);
    let speaks = key.kind.schema_version();
    if version != Some(u64::from(speaks)) {
        return Err(fail(format!(
            "recorded with {} message schema version {}, this shroud speaks version {speaks}",
            key.kind,
            version.map_or("unknown".to_owned(), |v| v.to_string())
        )));
    }
    Ok(Some(key))
}

fn schema_version(data: &[u8]) -> Option<u64> {
    let value: serde_json::Value = serde_json::from_slice(data).ok()?;
    value.get("schema_version")?.as_u64()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn describe<'a>(topic: &'a str, schema: &'a SchemaRecord) -> ChannelDescription<'a> {
        ChannelDescription {
            topic,
            message_encoding: MESSAGE_ENCODING,
            schema_name: &schema.name,
            schema_encoding: schema.encoding,
            schema_data: &schema.data,
        }
    }

    #[test]
    fn shroud_channels_replay_to_their_key() {
        let schema = schema_for(TopicKind::Cloud);
        assert_eq!(schema.name, "shroud.CloudMessage");
        let key = replayable(&describe("shroud/demo/cloud/spheres", &schema))
            .unwrap()
            .unwrap();
        assert_eq!((key.kind, key.name.as_str()), (TopicKind::Cloud, "spheres"));
        let meta = channel_metadata(&key);
        assert_eq!(meta["shroud.kind"], "cloud");
    }

    #[test]
    fn other_channels_are_skipped_and_mismatches_refused() {
        let schema = schema_for(TopicKind::Cloud);
        let mut foxglove = describe("/cloud/spheres", &schema);
        foxglove.message_encoding = "protobuf";
        assert_eq!(replayable(&foxglove).unwrap(), None);
        let wrong_kind = describe("shroud/demo/surrogate/spheres", &schema);
        assert!(replayable(&wrong_kind)
            .unwrap_err()
            .to_string()
            .contains("does not describe"));
        let old = SchemaRecord {
            data: b"{\"schema_version\":1}".to_vec(),
            ..schema.clone()
        };
        let e = replayable(&describe("shroud/demo/cloud/a", &old)).unwrap_err();
        assert!(e.to_string().contains("version 1"), "{e}");
        assert!(replayable(&describe("elsewhere/cloud", &schema)).is_err());
    }

    #[test]
    fn each_kind_records_its_own_schema_version() {
        let joints = schema_for(TopicKind::Joints);
        assert_eq!(schema_version(&joints.data), Some(3));
        assert_eq!(
            schema_version(&schema_for(TopicKind::Collision).data),
            Some(3)
        );
        assert_eq!(schema_version(&schema_for(TopicKind::Cloud).data), Some(2));
        assert!(replayable(&describe("shroud/demo/joints/arm", &joints))
            .unwrap()
            .is_some());
        // Joint states recorded before velocities: refused by kind and version.
        let before = SchemaRecord {
            data: b"{\"schema_version\":2}".to_vec(),
            ..joints
        };
        let e = replayable(&describe("shroud/demo/joints/arm", &before)).unwrap_err();
        assert!(
            e.to_string().contains("joints message schema version 2"),
            "{e}"
        );
    }
}
