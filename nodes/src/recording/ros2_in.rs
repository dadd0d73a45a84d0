//! `shroud replay` of a ROS 2 recording (rosbag2 with MCAP storage, CDR
//! messages; a bag directory with `metadata.yaml`, or a bare `.mcap`): the
//! channels of the topics `--ros2-topic` maps are checked (CDR, the message
//! type their stream takes) and their messages converted as the `ros2` node
//! converts live ones (`PointCloud2` placed by `--cloud-mount`, `JointState`
//! matched to the arm file's joints); other channels are skipped, said once.
//! A message that cannot be converted (malformed CDR, a cloud that cannot be
//! placed, a joint missing) is logged and counted as a malformed drop.

use crate::arm_file::{joint_names, read_arm_file};
use crate::runtime::NodeContext;
use anyhow::{bail, Context, Result};
use mcap::records::Record;
use shroud_graph::metrics::names as metric;
use shroud_msg::{TopicKey, TopicKind};
use shroud_record::layout::ChannelDescription;
use shroud_record::ros2::{bag_files, RosTopicMap};
use shroud_ros2::{JointState, PointCloud2, RosMessage};
use shroud_ros2_bridge::{cloud_from_ros, CloudMount, JointMatcher};
use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};

/// Publishes one replayed message (key, log time, payload); false to stop.
pub type PublishFn<'a> = dyn FnMut(&TopicKey, u64, &[u8]) -> Result<bool> + 'a;

/// The files of a ROS 2 recording, in order: those a bag directory's
/// `metadata.yaml` lists, or the one `.mcap` file given.
pub fn bag_inputs(path: &Path) -> Result<Vec<PathBuf>> {
    if !path.is_dir() {
        return Ok(vec![path.to_path_buf()]);
    }
    let metadata = path.join("metadata.yaml");
    let text = std::fs::read_to_string(&metadata).with_context(|| {
        format!(
            "{} is a directory without a readable metadata.yaml: not a rosbag2 recording",
            path.display()
        )
    })?;
    let files = bag_files(&text).with_context(|| format!("{}", metadata.display()))?;
    let files: Vec<PathBuf> = files.iter().map(|f| path.join(f)).collect();
    if let Some(missing) = files.iter().find(|f| !f.is_file()) {
        bail!(
            "{} lists {}, which is not there",
            metadata.display(),
            missing.display()
        );
    }
    Ok(files)
}

/// What replays a ROS 2 recording, and what it keeps from pass to pass.
pub struct RosBag {
    map: RosTopicMap,
    mount: CloudMount,
    /// By arm (the stream of a `joints/<arm>` mapping).
    matchers: HashMap<String, JointMatcher>,
    /// The next shroud sequence number of each stream.
    sequences: HashMap<String, u64>,
    /// Topics skipped and joint names dropped, each said once.
    said: BTreeSet<String>,
}

impl RosBag {
    /// The topic map, the clouds' mount, and the arm files of the joint
    /// streams: the one whose arm has the stream's name, or the only one.
    pub fn new(map: RosTopicMap, mount: CloudMount, arm_files: &[PathBuf]) -> Result<Self> {
        let arms = arm_files
            .iter()
            .map(|path| read_arm_file(path).map(|f| (f.arm.name().to_owned(), joint_names(&f))))
            .collect::<Result<Vec<_>>>()?;
        let mut matchers = HashMap::new();
        for (topic, kind, name) in map.entries() {
            if kind != TopicKind::Joints {
                continue;
            }
            let joints = match arms.iter().find(|(arm, _)| arm == name) {
                Some((_, joints)) => joints,
                None if arms.len() == 1 => &arms[0].1,
                None => bail!(
                    "--ros2-topic {topic}=joints/{name}: give the arm's --arm-file (its joint names){}",
                    match arms.is_empty() {
                        true => String::new(),
                        false => format!("; the arm files given are of {:?}", arms.iter().map(|a| &a.0).collect::<Vec<_>>()),
                    }
                ),
            };
            matchers.insert(name.to_owned(), JointMatcher::new(name, joints.clone()));
        }
        Ok(Self {
            map,
            mount,
            matchers,
            sequences: HashMap::new(),
            said: BTreeSet::new(),
        })
    }

    /// Checks the channels of each file's start (up to its first message):
    /// a mapped topic that cannot be replayed fails before the node starts.
    pub fn check_start(&self, files: &[PathBuf]) -> Result<()> {
        for file in files {
            let mut pass = RosPass::default();
            super::reader::read_records(file, |record| {
                if matches!(record, Record::Message { .. }) {
                    return Ok(false);
                }
                pass.channel_of(self, record).map(|_| true)
            })?;
        }
        Ok(())
    }

    /// Topics of the map that no file of the recording held (after a pass).
    pub fn missing(&self, pass: &RosPass) -> Vec<String> {
        self.map
            .entries()
            .filter(|(topic, _, _)| !pass.seen.contains(*topic))
            .map(|(topic, kind, name)| format!("{topic} (for {kind}/{name})"))
            .collect()
    }

    fn next_sequence(&mut self, stream: &str) -> u64 {
        let n = self.sequences.entry(stream.to_owned()).or_insert(0);
        *n += 1;
        *n - 1
    }

    /// Says `what` once per replay.
    fn once(&mut self, what: String) -> bool {
        self.said.insert(what)
    }

    /// The shroud message of a ROS message on `topic`; `None` (counted and
    /// logged) when it cannot be converted.
    fn convert(
        &mut self,
        ctx: &NodeContext,
        topic: &str,
        key: &TopicKey,
        cdr: &[u8],
    ) -> Option<Vec<u8>> {
        let converted = match key.kind {
            TopicKind::Cloud => self
                .cloud(key, cdr)
                .map_err(|e| format!("PointCloud2: {e}")),
            _ => self
                .joints(ctx, topic, key, cdr)
                .map_err(|e| format!("JointState: {e}")),
        };
        match converted {
            Ok(bytes) => Some(bytes),
            Err(e) => {
                ctx.drop_malformed(topic, &e);
                None
            }
        }
    }

    fn cloud(&mut self, key: &TopicKey, cdr: &[u8]) -> Result<Vec<u8>, String> {
        let cloud = PointCloud2::decode_borrowed(cdr).map_err(|e| e.to_string())?;
        let sequence = self.next_sequence(&key.name);
        let ros =
            cloud_from_ros(&cloud, &self.mount, &key.name, sequence).map_err(|e| e.to_string())?;
        ros.message.to_bytes().map_err(|e| e.to_string())
    }

    fn joints(
        &mut self,
        ctx: &NodeContext,
        topic: &str,
        key: &TopicKey,
        cdr: &[u8],
    ) -> Result<Vec<u8>, String> {
        let state = JointState::decode(cdr).map_err(|e| e.to_string())?;
        let sequence = self.next_sequence(&key.name);
        let matcher = self.matchers.get(&key.name).ok_or("no arm file")?;
        let matched = matcher
            .match_joints(&state, sequence)
            .map_err(|e| e.to_string())?;
        if !matched.unknown.is_empty() {
            ctx.metrics
                .add(metric::ROS2_UNKNOWN_JOINTS, matched.unknown.len() as u64);
            for name in &matched.unknown {
                if self.once(format!("joint {topic} {name}")) {
                    tracing::warn!(
                        "{topic}: joint {name:?} is not a joint of arm {}: its values are dropped",
                        key.name
                    );
                }
            }
        }
        matched.message.to_bytes().map_err(|e| e.to_string())
    }
}

/// The schemas and channels of one pass over a file.
#[derive(Default)]
pub struct RosPass {
    /// By id: name, encoding, data.
    schemas: HashMap<u16, (String, String, Vec<u8>)>,
    /// By channel id: the ROS topic and the key it replays to (`None`: skipped).
    channels: HashMap<u16, Option<(String, TopicKey)>>,
    /// Mapped topics met in this pass.
    seen: BTreeSet<String>,
}

impl RosPass {
    /// A pass over the next file keeps the topics seen so far.
    pub fn next_file(self) -> Self {
        Self {
            seen: self.seen,
            ..Self::default()
        }
    }

    /// Takes a record; hands each converted message to `publish(key, log
    /// time, payload)`, which returns false to stop.
    pub fn take(
        &mut self,
        bag: &mut RosBag,
        ctx: &NodeContext,
        record: Record<'_>,
        publish: &mut PublishFn<'_>,
    ) -> Result<bool> {
        let Record::Message { header, data } = record else {
            return self.channel_of(bag, record).map(|said| {
                if let Some(text) = said.filter(|t| bag.once(t.clone())) {
                    tracing::info!("{text}");
                }
                true
            });
        };
        let Some(Some((topic, key))) = self.channels.get(&header.channel_id) else {
            return Ok(true);
        };
        match bag.convert(ctx, topic, key, &data) {
            Some(bytes) => publish(key, header.log_time, &bytes),
            None => Ok(true),
        }
    }

    /// Takes a schema or channel record; for a channel not in the map, what
    /// to say about its skipping.
    fn channel_of(&mut self, bag: &RosBag, record: Record<'_>) -> Result<Option<String>> {
        match record {
            Record::Schema { header, data } => {
                self.schemas
                    .insert(header.id, (header.name, header.encoding, data.into_owned()));
                Ok(None)
            }
            Record::Channel(c) => {
                let schema = self.schemas.get(&c.schema_id);
                let (name, encoding, data) = schema
                    .map(|(n, e, d)| (n.as_str(), e.as_str(), d.as_slice()))
                    .unwrap_or_default();
                let description = ChannelDescription {
                    topic: &c.topic,
                    message_encoding: &c.message_encoding,
                    schema_name: name,
                    schema_encoding: encoding,
                    schema_data: data,
                };
                let mapped = bag.map.channel(&description, schema.is_some())?;
                let said = match &mapped {
                    Some(_) => {
                        self.seen.insert(c.topic.clone());
                        None
                    }
                    None => Some(format!(
                        "{} ({}) is not mapped by --ros2-topic: skipped",
                        c.topic,
                        if name.is_empty() { "no schema" } else { name }
                    )),
                };
                let key = mapped.map(|(kind, name)| {
                    let key = TopicKey {
                        namespace: String::new(),
                        kind,
                        name,
                    };
                    (c.topic.clone(), key)
                });
                self.channels.insert(c.id, key);
                Ok(said)
            }
            _ => Ok(None),
        }
    }
}
