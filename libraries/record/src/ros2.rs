//! ROS 2 recordings (rosbag2, MCAP storage, CDR serialisation), without I/O:
//! which ROS topics `shroud replay` maps to which shroud streams
//! ([`RosTopicMap`]) and whether a bag's channel can be replayed
//! ([`RosTopicMap::channel`]); which `.mcap` files a bag directory's
//! `metadata.yaml` lists ([`bag_files`]); and the ROS 2 channels
//! `shroud record --ros2` writes ([`ros2_channel`], [`ros2_path`]), with the
//! message definitions rosbag2 stores as their schemas.

use super::error::RecordError;
use super::layout::ChannelDescription;
use shroud_msg::{check_name, TopicKey, TopicKind};
use std::path::{Component, Path, PathBuf};

/// The message encoding of rosbag2's channels.
pub const ROS2_MESSAGE_ENCODING: &str = "cdr";
/// The schema encoding of a `.msg` definition.
pub const ROS2_SCHEMA_ENCODING: &str = "ros2msg";
/// The MCAP profile of a ROS 2 recording.
pub const ROS2_PROFILE: &str = "ros2";

pub const POINT_CLOUD2: &str = "sensor_msgs/msg/PointCloud2";
pub const JOINT_STATE: &str = "sensor_msgs/msg/JointState";
pub const DIAGNOSTIC_STATUS: &str = "diagnostic_msgs/msg/DiagnosticStatus";

// The full message definitions, as rosbag2 stores them in a schema: the
// type's `.msg` text, then for each type it uses a line of 80 `=`, `MSG:
// pkg/Type` and that type's text. Produced once with rosbags 0.11.9:
//     from rosbags.typesys import Stores, get_typestore
//     get_typestore(Stores.ROS2_JAZZY).generate_msgdef(TYPE, ros_version=2)[0]
const RULE: &str =
    "================================================================================\n";

/// `sensor_msgs/msg/PointCloud2`'s definition.
pub fn point_cloud2_definition() -> String {
    [
        "std_msgs/Header header\nuint32 height\nuint32 width\nsensor_msgs/PointField[] fields\n\
         bool is_bigendian\nuint32 point_step\nuint32 row_step\nuint8[] data\nbool is_dense\n",
        RULE,
        HEADER_DEFINITIONS,
        RULE,
        "MSG: sensor_msgs/PointField\nuint8 INT8=1\nuint8 UINT8=2\nuint8 INT16=3\nuint8 UINT16=4\n\
         uint8 INT32=5\nuint8 UINT32=6\nuint8 FLOAT32=7\nuint8 FLOAT64=8\nstring name\n\
         uint32 offset\nuint8 datatype\nuint32 count\n",
    ]
    .concat()
}

/// `std_msgs/Header` and `builtin_interfaces/Time`, the dependencies every
/// stamped message shares.
const HEADER_DEFINITIONS: &str =
    "MSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n\
     ================================================================================\n\
     MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n";

/// `sensor_msgs/msg/JointState`'s definition.
pub fn joint_state_definition() -> String {
    [
        "std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\n\
         float64[] effort\n",
        RULE,
        HEADER_DEFINITIONS,
    ]
    .concat()
}

/// `diagnostic_msgs/msg/DiagnosticStatus`'s definition.
pub fn diagnostic_status_definition() -> String {
    [
        "byte OK=0\nbyte WARN=1\nbyte ERROR=2\nbyte STALE=3\nbyte level\nstring name\n\
         string message\nstring hardware_id\ndiagnostic_msgs/KeyValue[] values\n",
        RULE,
        "MSG: diagnostic_msgs/KeyValue\nstring key\nstring value\n",
    ]
    .concat()
}

/// A ROS 2 channel `shroud record --ros2` writes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RosChannel {
    pub topic: String,
    pub type_name: &'static str,
}

impl RosChannel {
    /// The schema data: the type's full message definition.
    pub fn definition(&self) -> String {
        match self.type_name {
            POINT_CLOUD2 => point_cloud2_definition(),
            JOINT_STATE => joint_state_definition(),
            _ => diagnostic_status_definition(),
        }
    }
}

/// The ROS 2 channel of a shroud topic: clouds on `/shroud/cloud/<stream>`
/// (`PointCloud2`), joint states on `/shroud/joints/<arm>` (`JointState`),
/// verdicts on `/shroud/verdict/<arm>` (`DiagnosticStatus`); other kinds have
/// none. A stream name's `-` and `.` become `_` (not allowed in ROS names).
pub fn ros2_channel(key: &TopicKey) -> Option<RosChannel> {
    let (part, type_name) = match key.kind {
        TopicKind::Cloud => ("cloud", POINT_CLOUD2),
        TopicKind::Joints => ("joints", JOINT_STATE),
        TopicKind::Collision => ("verdict", DIAGNOSTIC_STATUS),
        _ => return None,
    };
    let token: String = key
        .name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    Some(RosChannel {
        topic: format!("/shroud/{part}/{token}"),
        type_name,
    })
}

/// The ROS 2 file written beside a recording's file: `run.mcap` →
/// `run.ros2.mcap` (rosbags refuses a file holding any schema that is not a
/// ROS one, so shroud's and Foxglove's channels cannot share it).
pub fn ros2_path(path: &Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!("{stem}.ros2.mcap"))
}

/// `--ros2-topic TOPIC=KIND/NAME` options: each ROS topic replayed and the
/// shroud stream it goes to (clouds from `PointCloud2`, joint states from
/// `JointState`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RosTopicMap {
    entries: Vec<(String, TopicKind, String)>,
}

impl RosTopicMap {
    pub fn parse(options: &[String]) -> Result<Self, RecordError> {
        let fail = |text: &str, reason: String| RecordError::Option {
            option: "--ros2-topic",
            reason: format!("{text:?}: {reason}"),
        };
        let mut entries: Vec<(String, TopicKind, String)> = Vec::new();
        for text in options {
            let Some((topic, stream)) = text.split_once('=') else {
                return Err(fail(
                    text,
                    "not TOPIC=KIND/NAME (e.g. /points=cloud/camera)".into(),
                ));
            };
            let (topic, stream) = (topic.trim(), stream.trim());
            if !topic.starts_with('/') || topic.len() < 2 || topic.contains(char::is_whitespace) {
                return Err(fail(
                    text,
                    "a ROS topic is an absolute name such as /points".into(),
                ));
            }
            let kind = match stream.split_once('/') {
                Some(("cloud", _)) => TopicKind::Cloud,
                Some(("joints", _)) => TopicKind::Joints,
                _ => {
                    return Err(fail(
                        text,
                        "the stream is cloud/<name> or joints/<name>".into(),
                    ))
                }
            };
            let name = stream.split_once('/').map_or("", |(_, n)| n);
            check_name("--ros2-topic", name).map_err(|e| fail(text, e.to_string()))?;
            if entries.iter().any(|(t, _, _)| t == topic) {
                return Err(fail(text, format!("{topic} is mapped twice")));
            }
            entries.push((topic.to_owned(), kind, name.to_owned()));
        }
        if entries.is_empty() {
            return Err(fail("", "no topic mapped".into()));
        }
        Ok(Self { entries })
    }

    /// `(ROS topic, kind, stream)`, in the order given.
    pub fn entries(&self) -> impl Iterator<Item = (&str, TopicKind, &str)> {
        self.entries
            .iter()
            .map(|(t, k, n)| (t.as_str(), *k, n.as_str()))
    }

    /// The stream a bag's channel replays to: `Ok(None)` for a topic that is
    /// not mapped; an error for a mapped topic whose channel is not CDR, has
    /// no schema or another message type than its stream's kind takes.
    pub fn channel(
        &self,
        channel: &ChannelDescription<'_>,
        has_schema: bool,
    ) -> Result<Option<(TopicKind, String)>, RecordError> {
        let Some((_, kind, name)) = self.entries.iter().find(|(t, _, _)| t == channel.topic) else {
            return Ok(None);
        };
        let fail = |reason: String| RecordError::Channel {
            topic: channel.topic.to_owned(),
            reason,
        };
        if channel.message_encoding != ROS2_MESSAGE_ENCODING {
            return Err(fail(format!(
                "message encoding {:?} is not {ROS2_MESSAGE_ENCODING:?} (ROS 2's CDR)",
                channel.message_encoding
            )));
        }
        if !has_schema {
            return Err(fail("has no schema: its message type is unknown".into()));
        }
        let expected = match kind {
            TopicKind::Cloud => POINT_CLOUD2,
            _ => JOINT_STATE,
        };
        if channel.schema_name != expected {
            return Err(fail(format!(
                "holds {:?}, but {kind}/{name} takes {expected}",
                channel.schema_name
            )));
        }
        Ok(Some((*kind, name.clone())))
    }
}

/// The `.mcap` files of a rosbag2 directory, in order, from its
/// `metadata.yaml`: the items of `relative_file_paths` (a block list, one
/// `- name` a line, as rosbag2 and rosbags write it; other YAML forms are
/// refused by name). The storage must be `mcap`; a path must stay inside
/// the directory.
pub fn bag_files(metadata_yaml: &str) -> Result<Vec<PathBuf>, RecordError> {
    let fail = |reason: String| RecordError::Option {
        option: "metadata.yaml",
        reason,
    };
    let value_of = |key: &str| {
        metadata_yaml.lines().find_map(|l| {
            let (k, v) = l.trim().split_once(':')?;
            (k == key).then(|| v.trim().trim_matches(['"', '\'']).to_owned())
        })
    };
    match value_of("storage_identifier").as_deref() {
        Some("mcap") => {}
        Some(other) => {
            return Err(fail(format!(
                "storage {other:?}: shroud reads mcap bags only (convert with `ros2 bag convert`)"
            )))
        }
        None => {
            return Err(fail(
                "no storage_identifier: not a rosbag2 metadata file".into(),
            ))
        }
    }
    let mut lines = metadata_yaml.lines();
    let Some(start) = lines.by_ref().find(|l| l.trim() == "relative_file_paths:") else {
        return Err(fail("no relative_file_paths block list".into()));
    };
    let indent = |l: &str| l.len() - l.trim_start().len();
    let base = indent(start);
    let mut files = Vec::new();
    for line in lines {
        let item = line.trim();
        if item.is_empty() {
            continue;
        }
        if indent(line) < base || (indent(line) == base && !item.starts_with('-')) {
            break;
        }
        let Some(name) = item.strip_prefix("- ") else {
            return Err(fail(format!(
                "relative_file_paths: {item:?} is not a list item"
            )));
        };
        let path = PathBuf::from(name.trim().trim_matches(['"', '\'']));
        let inside = path
            .components()
            .all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
        if !inside || path.as_os_str().is_empty() {
            return Err(fail(format!(
                "{} is not a file inside the bag",
                path.display()
            )));
        }
        if path.extension().is_none_or(|e| e != "mcap") {
            return Err(fail(format!("{} is not an .mcap file", path.display())));
        }
        files.push(path);
    }
    if files.is_empty() {
        return Err(fail("relative_file_paths lists no file".into()));
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(options: &[&str]) -> Result<RosTopicMap, RecordError> {
        RosTopicMap::parse(&options.iter().map(|s| s.to_string()).collect::<Vec<_>>())
    }

    fn channel<'a>(topic: &'a str, encoding: &'a str, schema: &'a str) -> ChannelDescription<'a> {
        ChannelDescription {
            topic,
            message_encoding: encoding,
            schema_name: schema,
            schema_encoding: ROS2_SCHEMA_ENCODING,
            schema_data: b"",
        }
    }

    #[test]
    fn topics_map_to_cloud_and_joint_streams_and_mismatches_are_named() {
        let m = map(&["/points=cloud/camera", " /joint_states = joints/demo_arm"]).unwrap();
        let entries: Vec<_> = m.entries().collect();
        assert_eq!(entries[1], ("/joint_states", TopicKind::Joints, "demo_arm"));
        let cloud = m.channel(&channel("/points", "cdr", POINT_CLOUD2), true);
        assert_eq!(cloud.unwrap(), Some((TopicKind::Cloud, "camera".into())));
        assert_eq!(m.channel(&channel("/tf", "cdr", "x"), true).unwrap(), None);
        let wrong = m.channel(&channel("/points", "cdr", JOINT_STATE), true);
        let e = wrong.unwrap_err().to_string();
        assert!(
            e.contains("/points") && e.contains("takes sensor_msgs/msg/PointCloud2"),
            "{e}"
        );
        let json = m.channel(&channel("/points", "json", POINT_CLOUD2), true);
        assert!(json.unwrap_err().to_string().contains("\"json\""));
        let bare = m.channel(&channel("/points", "cdr", ""), false);
        assert!(bare.unwrap_err().to_string().contains("no schema"));
        for bad in [
            "points=cloud/a",
            "/points",
            "/points=surrogate/a",
            "/points=cloud/a*b",
            "/points=cloud/",
        ] {
            assert!(map(&[bad]).is_err(), "{bad}");
        }
        assert!(map(&["/a=cloud/x", "/a=joints/y"]).is_err());
        assert!(map(&[]).is_err());
    }

    #[test]
    fn a_bags_metadata_lists_its_files_in_order() {
        let yaml = "rosbag2_bagfile_information:\n  version: 9\n  storage_identifier: mcap\n  \
                    relative_file_paths:\n    - bag_0.mcap\n    - \"bag_1.mcap\"\n  \
                    starting_time:\n    nanoseconds_since_epoch: 1\n";
        let files = bag_files(yaml).unwrap();
        assert_eq!(
            files,
            [PathBuf::from("bag_0.mcap"), PathBuf::from("bag_1.mcap")]
        );
        // rosbag2 may write the list at the key's own indentation.
        let flush = "storage_identifier: mcap\nrelative_file_paths:\n- a.mcap\nfiles:\n- x\n";
        assert_eq!(bag_files(flush).unwrap(), [PathBuf::from("a.mcap")]);
        let sqlite = yaml.replace("mcap\n  relative", "sqlite3\n  relative");
        assert!(bag_files(&sqlite)
            .unwrap_err()
            .to_string()
            .contains("sqlite3"));
        for bad in ["../x.mcap", "/etc/x.mcap", "x.db3"] {
            let y = format!("storage_identifier: mcap\nrelative_file_paths:\n  - {bad}\n");
            assert!(bag_files(&y).is_err(), "{bad}");
        }
        assert!(bag_files("storage_identifier: mcap\nrelative_file_paths: []\n").is_err());
        assert!(bag_files("").is_err());
    }

    #[test]
    fn shroud_topics_have_ros_channels_and_a_file_beside_theirs() {
        let key = TopicKey::parse("shroud/demo/cloud/cam-1.a").unwrap();
        let c = ros2_channel(&key).unwrap();
        assert_eq!(
            (c.topic.as_str(), c.type_name),
            ("/shroud/cloud/cam_1_a", POINT_CLOUD2)
        );
        let verdict = ros2_channel(&TopicKey::parse("shroud/d/collision/arm").unwrap()).unwrap();
        assert_eq!(verdict.topic, "/shroud/verdict/arm");
        assert!(verdict.definition().starts_with("byte OK=0\n"));
        assert!(ros2_channel(&TopicKey::parse("shroud/d/surrogate/arm").unwrap()).is_none());
        assert_eq!(
            ros2_path(Path::new("/d/run-001.mcap")),
            Path::new("/d/run-001.ros2.mcap")
        );
        let cloud = point_cloud2_definition();
        assert_eq!(cloud.matches(RULE).count(), 3);
        assert!(cloud.contains("\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n"));
        assert_eq!(joint_state_definition().matches("MSG: ").count(), 2);
    }
}
