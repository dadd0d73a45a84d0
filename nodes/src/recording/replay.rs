//! `shroud replay FILE` (also the node kind `replay` of launch files):
//! publishes the shroud messages of a recording (its `msgpack` channels; the
//! Foxglove ones are for viewers) into `--namespace`, each on its recorded
//! topic kind and name, by log time (`shroud-record`'s [`ReplaySchedule`]), pass after
//! pass with `--loop`. The file is streamed, one chunk in memory at a time; a
//! truncated file is replayed up to its last complete chunk, with a warning.
//! With `--ros2-topic`, FILE is a ROS 2 recording (rosbag2) whose mapped
//! topics are converted and replayed the same way (`ros2_in.rs`).

use super::reader::{read_records, Ending};
use super::ros2_in::{bag_inputs, PublishFn, RosBag, RosPass};
use crate::args::RosCloudArgs;
use crate::runtime::{run_node, NodeCommon, NodeContext};
use crate::transport::{unix_ns, PayloadWriter};
use anyhow::Result;
use clap::Args;
use mcap::records::Record;
use shroud_graph::metrics::names as metric;
use shroud_msg::{CloudMessage, JointStateMessage, TopicKey, TopicKind};
use shroud_record::layout::{replayable, ChannelDescription};
use shroud_record::ros2::{RosTopicMap, ROS2_MESSAGE_ENCODING};
use shroud_record::{Pace, ReplaySchedule, TopicFilter};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use zenoh::Wait;

#[derive(Debug, Clone, Args)]
pub struct ReplayArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The MCAP recording (`shroud record`); with --ros2-topic, a ROS 2
    /// recording: a rosbag2 directory (its metadata.yaml lists its .mcap
    /// files) or one .mcap file.
    pub file: PathBuf,
    /// Times real time (0.001 to 1000).
    #[arg(long, default_value_t = 1.0)]
    pub speed: f64,
    /// As fast as possible (instead of --speed).
    #[arg(long, conflicts_with = "speed")]
    pub max: bool,
    /// Start again at the end, forever.
    #[arg(long = "loop")]
    pub looping: bool,
    /// Topics to replay: comma-separated <kind>/<name> patterns (default:
    /// every kind but status, which the replayed graph's own nodes publish).
    #[arg(long, conflicts_with = "ros2_topics")]
    pub topics: Option<String>,
    /// A topic of a ROS 2 recording and the stream it replays to,
    /// `TOPIC=cloud/NAME` (`sensor_msgs/msg/PointCloud2`) or
    /// `TOPIC=joints/ARM` (`sensor_msgs/msg/JointState`), e.g.
    /// `/points=cloud/camera`. Repeatable; other topics are skipped.
    #[arg(long = "ros2-topic", value_name = "TOPIC=KIND/NAME")]
    pub ros2_topics: Vec<String>,
    /// The arm file of a `joints/ARM` stream of --ros2-topic (its joint
    /// names): the one whose arm is named ARM, or the only one. Repeatable.
    #[arg(long = "arm-file", value_name = "FILE", requires = "ros2_topics")]
    pub arm_files: Vec<PathBuf>,
    /// Where the clouds of --ros2-topic were taken from.
    #[command(flatten)]
    pub placement: RosCloudArgs,
    /// Wait up to this many seconds for a subscriber on each replayed topic
    /// before its first message (0: publish at once).
    #[arg(long, value_name = "S", default_value_t = 0.0)]
    pub wait_subscribers: f64,
    /// Stamp clouds and joint states with the time they are published, as a
    /// live sensor would (a guard refuses stamps far from its clock); off,
    /// every message is published exactly as recorded.
    #[arg(long)]
    pub restamp: bool,
}

/// What a replay was told.
struct Plan {
    file: PathBuf,
    pace: Pace,
    looping: bool,
    source: Source,
    wait_subscribers: Duration,
    restamp: bool,
}

/// What the recording is and which of its messages are replayed.
enum Source {
    /// Shroud's own recording, its topics picked by `--topics`.
    Shroud(TopicFilter),
    /// A ROS 2 recording's files, in order.
    Ros2(Vec<PathBuf>, Box<RosBag>),
}

/// The channels and schemas of one pass over a file.
enum PassState {
    Shroud(Pass),
    Ros2(RosPass),
}

/// Publishing shared memory segment: a few large clouds.
const SHM_POOL: usize = 64 << 20;
/// Longest sleep between looks at the stop flag.
const STOP_POLL: Duration = Duration::from_millis(50);

pub fn run(args: ReplayArgs) -> Result<()> {
    let plan = plan(&args)?;
    // Read the file's start now: a missing or foreign file (or a mapped ROS
    // topic of another type) fails before the node starts.
    match &plan.source {
        Source::Shroud(_) => {
            read_records(&plan.file, |_| Ok(false))?;
        }
        Source::Ros2(files, bag) => bag.check_start(files)?,
    }
    let common = args.common.clone();
    run_node(&common, "replay", move |ctx| replay(ctx, plan))
}

fn plan(args: &ReplayArgs) -> Result<Plan> {
    let pace = match args.max {
        true => Pace::Max,
        false => Pace::speed(args.speed)?,
    };
    let source = match (&args.topics, args.ros2_topics.is_empty()) {
        (_, false) => {
            let map = RosTopicMap::parse(&args.ros2_topics)?;
            let bag = RosBag::new(map, args.placement.mount()?, &args.arm_files)?;
            Source::Ros2(bag_inputs(&args.file)?, Box::new(bag))
        }
        (Some(text), true) => Source::Shroud(TopicFilter::parse(text)?),
        (None, true) => Source::Shroud(TopicFilter::all().without(TopicKind::Status)),
    };
    anyhow::ensure!(
        args.wait_subscribers.is_finite() && (0.0..=3600.0).contains(&args.wait_subscribers),
        "--wait-subscribers must be between 0 and 3600 seconds"
    );
    Ok(Plan {
        file: args.file.clone(),
        pace,
        looping: args.looping,
        source,
        wait_subscribers: Duration::from_secs_f64(args.wait_subscribers),
        restamp: args.restamp,
    })
}

fn replay(ctx: Arc<NodeContext>, mut plan: Plan) -> Result<()> {
    let started = Instant::now();
    // Moves on by the time spent waiting for subscribers, so that messages
    // keep their spacing after a wait rather than going out in a burst.
    let mut origin = started;
    let mut schedule = ReplaySchedule::new(plan.pace);
    let mut out = Publishers::new(&ctx, started + plan.wait_subscribers);
    let mut warned = false;
    let files = match &plan.source {
        Source::Shroud(_) => vec![plan.file.clone()],
        Source::Ros2(files, _) => files.clone(),
    };
    for pass in 0u64.. {
        ctx.metrics.set(metric::PASS, pass as f64);
        let mut published = 0u64;
        let mut state = match plan.source {
            Source::Shroud(_) => PassState::Shroud(Pass::default()),
            Source::Ros2(..) => PassState::Ros2(RosPass::default()),
        };
        for file in &files {
            state = match state {
                PassState::Shroud(p) => PassState::Shroud(Pass {
                    cdr_channels: p.cdr_channels,
                    ..Pass::default()
                }),
                PassState::Ros2(p) => PassState::Ros2(p.next_file()),
            };
            let mut publish = |key: &TopicKey, log_ns: u64, data: &[u8]| {
                let due = origin + Duration::from_nanos(schedule.due_ns(log_ns));
                if !sleep_until(&ctx, due) {
                    return Ok(false);
                }
                let restamped = plan.restamp.then(|| restamp(key, data)).flatten();
                origin += out.publish(key, restamped.as_deref().unwrap_or(data))?;
                published += 1;
                Ok(true)
            };
            let ending = read_records(file, |record| match (&mut state, &mut plan.source) {
                (PassState::Shroud(p), Source::Shroud(filter)) => {
                    p.take(record, filter, &mut publish)
                }
                (PassState::Ros2(p), Source::Ros2(_, bag)) => {
                    p.take(bag, &ctx, record, &mut publish)
                }
                _ => unreachable!("a pass is of its source's kind"),
            })?;
            if let (Ending::Truncated { reason, .. }, false) = (&ending, warned) {
                tracing::warn!(
                    "{} is truncated ({reason}): replayed up to its last complete chunk",
                    file.display()
                );
                warned = true;
            }
            if ctx.stopping() {
                break;
            }
        }
        if let (0, PassState::Ros2(p), Source::Ros2(_, bag)) = (pass, &state, &plan.source) {
            for topic in bag.missing(p) {
                tracing::warn!("{} has no channel {topic}", plan.file.display());
            }
        }
        if published == 0 && !ctx.stopping() {
            let hint = match &state {
                PassState::Shroud(p) if p.cdr_channels => {
                    " (it holds ROS 2 CDR channels: map them with --ros2-topic)"
                }
                _ => "",
            };
            anyhow::bail!(
                "nothing to replay: no message of {} is on a channel that --topics or --ros2-topic takes{hint}",
                plan.file.display()
            );
        }
        if !plan.looping || ctx.stopping() {
            break;
        }
        schedule.next_pass();
    }
    Ok(())
}

/// A cloud or joint state stamped now (`--restamp`); `None` for other kinds
/// and for a message that does not decode (published as recorded, for its
/// subscribers to refuse and count).
fn restamp(key: &TopicKey, data: &[u8]) -> Option<Vec<u8>> {
    match key.kind {
        TopicKind::Cloud => {
            let mut msg = CloudMessage::from_bytes(data).ok()?;
            msg.stamp_ns = unix_ns();
            msg.to_bytes().ok()
        }
        TopicKind::Joints => {
            let mut msg = JointStateMessage::from_bytes(data).ok()?;
            msg.stamp_ns = unix_ns();
            msg.to_bytes().ok()
        }
        _ => None,
    }
}

/// Waits until `due` or the stop flag; false if stopped.
fn sleep_until(ctx: &NodeContext, due: Instant) -> bool {
    loop {
        if ctx.stopping() {
            return false;
        }
        let left = due.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return true;
        }
        std::thread::sleep(left.min(STOP_POLL));
    }
}

/// The channels and schemas of one pass over the file.
#[derive(Default)]
struct Pass {
    schemas: HashMap<u16, (String, String, Vec<u8>)>,
    /// By channel id: the key to publish to, `None` when not replayed.
    channels: HashMap<u16, Option<TopicKey>>,
    /// Whether a ROS 2 channel was met (the file may be a rosbag2 one).
    cdr_channels: bool,
}

impl Pass {
    /// Takes a record; hands each replayed message to `publish(key, log
    /// time, payload)`, which returns false to stop.
    fn take(
        &mut self,
        record: Record<'_>,
        filter: &TopicFilter,
        publish: &mut PublishFn<'_>,
    ) -> Result<bool> {
        match record {
            Record::Schema { header, data } => {
                self.schemas
                    .insert(header.id, (header.name, header.encoding, data.into_owned()));
            }
            Record::Channel(c) => {
                let (name, encoding, data) = self
                    .schemas
                    .get(&c.schema_id)
                    .map(|(n, e, d)| (n.as_str(), e.as_str(), d.as_slice()))
                    .unwrap_or_default();
                let key = replayable(&ChannelDescription {
                    topic: &c.topic,
                    message_encoding: &c.message_encoding,
                    schema_name: name,
                    schema_encoding: encoding,
                    schema_data: data,
                })?;
                self.cdr_channels |= c.message_encoding == ROS2_MESSAGE_ENCODING;
                self.channels
                    .insert(c.id, key.filter(|k| filter.matches(k)));
            }
            Record::Message { header, data } => {
                if let Some(Some(key)) = self.channels.get(&header.channel_id) {
                    return publish(key, header.log_time, &data);
                }
            }
            _ => {}
        }
        Ok(true)
    }
}

/// A publisher per replayed topic, in the replay's namespace.
struct Publishers<'a> {
    ctx: &'a NodeContext,
    by_topic: HashMap<(TopicKind, String), zenoh::pubsub::Publisher<'static>>,
    writer: PayloadWriter,
    /// Until when a new publisher waits for its first subscriber.
    wait_until: Instant,
}

impl<'a> Publishers<'a> {
    fn new(ctx: &'a NodeContext, wait_until: Instant) -> Self {
        Self {
            ctx,
            by_topic: HashMap::new(),
            writer: ctx.payload_writer(SHM_POOL),
            wait_until,
        }
    }

    /// Publishes `data` on `key`'s topic; returns the time spent waiting
    /// for the topic's first subscriber (zero but for a new topic).
    fn publish(&mut self, key: &TopicKey, data: &[u8]) -> Result<Duration> {
        let topic = (key.kind, key.name.clone());
        let mut waited = Duration::ZERO;
        if !self.by_topic.contains_key(&topic) {
            let publisher = self.ctx.publisher(key.kind, &key.name)?;
            let before = Instant::now();
            let patience = self.wait_until.saturating_duration_since(before);
            self.ctx.wait_for_subscriber(&publisher, patience);
            waited = before.elapsed();
            self.by_topic.insert(topic.clone(), publisher);
        }
        let publisher = &self.by_topic[&topic];
        match publisher.put(self.writer.copy(data)).wait() {
            Ok(()) => self.ctx.metrics.add(metric::PUBLISHED, 1),
            Err(e) => {
                self.ctx.metrics.add(metric::PUBLISH_ERRORS, 1);
                tracing::warn!("publish {}: {e}", publisher.key_expr());
            }
        }
        Ok(waited)
    }
}
