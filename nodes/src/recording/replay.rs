//! `shroud replay FILE` (also the node kind `replay` of launch files):
//! publishes the shroud messages of a recording (its `msgpack` channels; the
//! Foxglove ones are for viewers) into `--namespace`, each on its recorded
//! topic kind and name, by log time (`shroud-record`'s [`ReplaySchedule`]), pass after
//! pass with `--loop`. The file is streamed, one chunk in memory at a time; a
//! truncated file is replayed up to its last complete chunk, with a warning.

use super::reader::{read_records, Ending};
use crate::runtime::{run_node, NodeCommon, NodeContext};
use crate::transport::{unix_ns, PayloadWriter};
use anyhow::Result;
use clap::Args;
use mcap::records::Record;
use shroud_graph::metrics::names as metric;
use shroud_msg::{CloudMessage, JointStateMessage, TopicKey, TopicKind};
use shroud_record::layout::{replayable, ChannelDescription};
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
    /// The MCAP recording (`shroud record`).
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
    #[arg(long)]
    pub topics: Option<String>,
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
    filter: TopicFilter,
    wait_subscribers: Duration,
    restamp: bool,
}

/// Publishing shared memory segment: a few large clouds.
const SHM_POOL: usize = 64 << 20;
/// Longest sleep between looks at the stop flag.
const STOP_POLL: Duration = Duration::from_millis(50);

pub fn run(args: ReplayArgs) -> Result<()> {
    let plan = plan(&args)?;
    // Read the file's start now: a missing or foreign file fails before the
    // node starts.
    read_records(&plan.file, |_| Ok(false))?;
    let common = args.common.clone();
    run_node(&common, "replay", move |ctx| replay(ctx, plan))
}

fn plan(args: &ReplayArgs) -> Result<Plan> {
    let pace = match args.max {
        true => Pace::Max,
        false => Pace::speed(args.speed)?,
    };
    let filter = match &args.topics {
        Some(text) => TopicFilter::parse(text)?,
        None => TopicFilter::all().without(TopicKind::Status),
    };
    anyhow::ensure!(
        args.wait_subscribers.is_finite() && (0.0..=3600.0).contains(&args.wait_subscribers),
        "--wait-subscribers must be between 0 and 3600 seconds"
    );
    Ok(Plan {
        file: args.file.clone(),
        pace,
        looping: args.looping,
        filter,
        wait_subscribers: Duration::from_secs_f64(args.wait_subscribers),
        restamp: args.restamp,
    })
}

fn replay(ctx: Arc<NodeContext>, plan: Plan) -> Result<()> {
    let started = Instant::now();
    // Moves on by the time spent waiting for subscribers, so that messages
    // keep their spacing after a wait rather than going out in a burst.
    let mut origin = started;
    let mut schedule = ReplaySchedule::new(plan.pace);
    let mut out = Publishers::new(&ctx, started + plan.wait_subscribers);
    let mut warned = false;
    for pass in 0u64.. {
        ctx.metrics.set(metric::PASS, pass as f64);
        let mut pass_state = Pass::default();
        let mut published = 0u64;
        let ending = read_records(&plan.file, |record| {
            pass_state.take(
                record,
                &plan.filter,
                &mut |key: &TopicKey, log_ns: u64, data: &[u8]| {
                    let due = origin + Duration::from_nanos(schedule.due_ns(log_ns));
                    if !sleep_until(&ctx, due) {
                        return Ok(false);
                    }
                    let restamped = plan.restamp.then(|| restamp(key, data)).flatten();
                    origin += out.publish(key, restamped.as_deref().unwrap_or(data))?;
                    published += 1;
                    Ok(true)
                },
            )
        })?;
        if published == 0 && !ctx.stopping() {
            anyhow::bail!(
                "nothing to replay: no message of {} is on a shroud channel that --topics takes",
                plan.file.display()
            );
        }
        if let (Ending::Truncated { reason, .. }, false) = (&ending, warned) {
            tracing::warn!(
                "{} is truncated ({reason}): replayed up to its last complete chunk",
                plan.file.display()
            );
            warned = true;
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

/// Publishes one replayed message (key, log time, payload); false to stop.
type PublishFn<'a> = dyn FnMut(&TopicKey, u64, &[u8]) -> Result<bool> + 'a;

/// The channels and schemas of one pass over the file.
#[derive(Default)]
struct Pass {
    schemas: HashMap<u16, (String, String, Vec<u8>)>,
    /// By channel id: the key to publish to, `None` when not replayed.
    channels: HashMap<u16, Option<TopicKey>>,
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
