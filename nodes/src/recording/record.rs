//! `shroud record` (also `shroud node record`): subscribes to the namespace's
//! topics picked by `--topics`, queues each message with its receive time,
//! and a writer thread stores them into MCAP (`writer.rs`); on Ctrl-C,
//! SIGTERM, `--duration` or a stopped writer, the queue is drained, the file
//! finished, and a summary printed.

use super::mcap_file::{FileOptions, McapFile};
use super::shared::Recording;
use super::views::{FoxgloveViews, ViewSettings};
use super::writer::{run_writer, Arrival, WriterPlan, WrittenFile};
use crate::args::ViewLimits;
use crate::runtime::{self, run_node, NodeCommon, NodeContext};
use crate::transport::WaitQueue;
use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use shroud_graph::metrics::names as metric;
use shroud_msg::TopicKey;
use shroud_record::layout::recording_metadata;
use shroud_record::ros2::ros2_path;
use shroud_record::{
    split_path, ByteQueue, ChunkPolicy, DiskReserve, DropCause, SplitPolicy, TopicFilter,
};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

#[derive(Debug, Clone, Args)]
pub struct RecordArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The MCAP file (with --split-size: <stem>-000.mcap, <stem>-001.mcap...).
    #[arg(short, long, default_value = "run.mcap")]
    pub output: PathBuf,
    /// Topics to record: comma-separated <kind>/<name> patterns, `*` and `?`
    /// as wildcards (e.g. cloud/*,surrogate/*; default: every topic).
    #[arg(long, default_value = "*/*")]
    pub topics: String,
    /// Stop after this many seconds (default: at Ctrl-C or SIGTERM).
    #[arg(long)]
    pub duration: Option<f64>,
    /// Continue in a new file before one would pass this many MB.
    #[arg(long, value_name = "MB")]
    pub split_size: Option<f64>,
    /// Replace existing files instead of refusing to start.
    #[arg(long)]
    pub overwrite: bool,
    /// Chunk compression.
    #[arg(long, default_value = "zstd")]
    pub compression: CompressionArg,
    /// Messages waiting for the disk, MB at most; beyond, the newest are
    /// dropped and counted (a slow disk).
    #[arg(long, value_name = "MB", default_value_t = 256.0)]
    pub queue_size: f64,
    /// Free space to leave on the disk, MB: below it the recording stops and
    /// its file is finished (a full disk).
    #[arg(long, value_name = "MB", default_value_t = 256.0)]
    pub min_free: f64,
    /// Also store the data as Foxglove's well-known schemas (point clouds,
    /// scene updates, frame transforms, JSON), so that Foxglove or Lichtblick
    /// shows the scene; `--foxglove false` records the raw messages only.
    #[arg(long, value_name = "BOOL", default_value_t = true, action = clap::ArgAction::Set)]
    pub foxglove: bool,
    /// Most points of each cloud in its Foxglove view (thinned by an even
    /// stride; the raw cloud is recorded whole).
    #[arg(long, default_value_t = 50_000)]
    pub points_budget: usize,
    /// Most Foxglove views a second of each cloud, surrogate and arm stream
    /// (the raw messages are all recorded).
    #[arg(long, value_name = "HZ", default_value_t = 10.0)]
    pub foxglove_rate: f64,
    /// An arm file (as the guard's) whose arm is drawn at its recorded joint
    /// states in the Foxglove views. Repeatable.
    #[arg(long = "arm-file", value_name = "FILE")]
    pub arm_files: Vec<PathBuf>,
    /// Seconds without a verdict after which the Foxglove views show
    /// `no-verdict`.
    #[arg(long, default_value_t = 0.5)]
    pub verdict_timeout: f64,
    /// Also write a ROS 2 recording beside each file, `<stem>.ros2.mcap`
    /// (read by `ros2 bag play` and rosbags): clouds as
    /// `sensor_msgs/msg/PointCloud2` on `/shroud/cloud/<stream>`, joint
    /// states as `sensor_msgs/msg/JointState` on `/shroud/joints/<arm>`,
    /// verdicts as `diagnostic_msgs/msg/DiagnosticStatus` on
    /// `/shroud/verdict/<arm>`.
    #[arg(long)]
    pub ros2: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CompressionArg {
    Zstd,
    None,
}

/// Chunks close at 4 MB of messages or after a second, whichever first: a
/// recorder killed without warning loses at most its last second.
const CHUNK: ChunkPolicy = ChunkPolicy {
    chunk_bytes: 4_000_000,
    max_age_ns: 1_000_000_000,
};

/// How long the body waits between looks at its stop conditions.
const TICK: Duration = Duration::from_millis(50);

/// The checked options.
struct Plan {
    filter: TopicFilter,
    duration: Option<Duration>,
    queue_bytes: usize,
    writer: WriterPlan,
}

pub fn run(args: RecordArgs) -> Result<()> {
    let plan = plan(&args)?;
    for index in 0..2 {
        let path = split_path(&plan.writer.base, plan.writer.split.splits(), index);
        let ros = args.ros2.then(|| ros2_path(&path));
        for path in std::iter::once(path).chain(ros) {
            if path.exists() && !args.overwrite {
                bail!("{} exists (give --overwrite to replace it)", path.display());
            }
        }
    }
    let first_path = split_path(&plan.writer.base, plan.writer.split.splits(), 0);
    let first = McapFile::create(&first_path, &plan.writer.options)?;
    let common = args.common.clone();
    run_node(&common, "record", move |ctx| record(ctx, plan, first))
}

fn plan(args: &RecordArgs) -> Result<Plan> {
    let filter = TopicFilter::parse(&args.topics)?;
    let duration = args
        .duration
        .map(|s| {
            anyhow::ensure!(
                s.is_finite() && s > 0.0 && s <= 1e7,
                "--duration must be between 0 and 10^7 seconds, not {s}"
            );
            Ok(Duration::from_secs_f64(s))
        })
        .transpose()?;
    let split = match args.split_size {
        Some(mb) => SplitPolicy::from_mb(mb)?,
        None => SplitPolicy::never(),
    };
    anyhow::ensure!(
        args.queue_size.is_finite() && (1.0..=65_536.0).contains(&args.queue_size),
        "--queue-size must be between 1 and 65536 MB, not {}",
        args.queue_size
    );
    anyhow::ensure!(
        args.min_free.is_finite() && (0.0..=1e9).contains(&args.min_free),
        "--min-free must be between 0 and 10^9 MB, not {}",
        args.min_free
    );
    let compression = match args.compression {
        CompressionArg::Zstd => Some(mcap::Compression::Zstd),
        CompressionArg::None => None,
    };
    let namespace = &args.common.zenoh.namespace;
    let views = args.foxglove.then(|| views(args)).transpose()?;
    Ok(Plan {
        filter,
        duration,
        queue_bytes: (args.queue_size * 1e6) as usize,
        writer: WriterPlan {
            base: args.output.clone(),
            split,
            chunk: CHUNK,
            reserve: DiskReserve {
                reserve_bytes: (args.min_free * 1e6) as u64,
            },
            options: FileOptions {
                compression,
                metadata: recording_metadata(namespace, &args.topics, env!("CARGO_PKG_VERSION")),
                overwrite: args.overwrite,
                ros2: args.ros2,
            },
            views,
        },
    })
}

/// The `--foxglove` views' settings, checked.
fn views(args: &RecordArgs) -> Result<FoxgloveViews> {
    let limits = ViewLimits {
        point_budget: ("--points-budget", args.points_budget),
        rate: ("--foxglove-rate", args.foxglove_rate, "views"),
        verdict_timeout: args.verdict_timeout,
        arm_files: &args.arm_files,
    };
    let (pace_ns, arms, verdict_timeout_ns) = limits.check()?;
    Ok(FoxgloveViews::new(ViewSettings {
        point_budget: args.points_budget,
        pace_ns,
        arms,
        verdict_timeout_ns,
    }))
}

fn record(ctx: Arc<NodeContext>, plan: Plan, first: McapFile) -> Result<()> {
    let started = Instant::now();
    let recording = Arc::new(Recording::new(ctx.metrics.clone()));
    let queue = Arc::new(WaitQueue::new(ByteQueue::new(plan.queue_bytes)));
    let writer = {
        let (queue, recording) = (queue.clone(), recording.clone());
        std::thread::Builder::new()
            .name("mcap-writer".into())
            .spawn(move || run_writer(plan.writer, first, queue, recording))
            .context("cannot start the writer thread")?
    };
    let filter = Arc::new(plan.filter);
    let mut subscribers = Vec::new();
    for key in filter.subscriptions(ctx.topics.namespace()) {
        let (queue, recording, filter) = (queue.clone(), recording.clone(), filter.clone());
        let listener = ctx.listen_raw(&key, move |sample| {
            on_sample(sample, &filter, &queue, &recording)
        })?;
        subscribers.push(listener);
    }
    tracing::info!("recording");
    while !ctx.stopping()
        && !writer.is_finished()
        && recording.refusing().is_none()
        && plan.duration.is_none_or(|d| started.elapsed() < d)
    {
        std::thread::sleep(TICK);
    }
    // No new message once the subscribers are gone; the writer drains the
    // queue and finishes the file.
    drop(subscribers);
    queue.close();
    let files = writer
        .join()
        .map_err(|_| anyhow::anyhow!("the writer thread panicked"))?;
    print_summary(&files, &recording, started.elapsed());
    match recording.refusal() {
        Some((cause, reason)) => bail!("recording stopped early ({cause}): {reason}"),
        None => Ok(()),
    }
}

/// A sample from zenoh's thread: matched against the filter, stamped, and
/// queued (or counted as dropped).
fn on_sample(
    sample: runtime::Arrival,
    filter: &TopicFilter,
    queue: &WaitQueue<ByteQueue<Arrival>>,
    recording: &Recording,
) {
    let log_ns = sample.received_wall_ns;
    let topic = sample.key.as_str();
    let Some(key) = TopicKey::parse(topic).filter(|k| filter.matches(k)) else {
        return;
    };
    recording.received();
    if let Some(cause) = recording.refusing() {
        recording.dropped(topic, cause);
        return;
    }
    // Without a zenoh timestamp, its publication is taken as its arrival.
    let publish_ns = sample.published_ns.unwrap_or(log_ns);
    let payload = sample.payload.clone();
    let len = payload.len();
    let arrival = Arrival {
        key,
        topic: topic.to_owned(),
        payload,
        log_ns,
        publish_ns,
    };
    // Full, or closed as the recording ends.
    if queue.push(|q| q.push(arrival, len).is_ok()) != Some(true) {
        recording.dropped(topic, DropCause::QueueFull);
    }
}

fn print_summary(files: &[WrittenFile], recording: &Recording, elapsed: Duration) {
    let messages: u64 = files.iter().map(|f| f.messages).sum();
    let bytes: u64 = files.iter().map(|f| f.bytes).sum();
    let seconds = elapsed.as_secs_f64();
    println!(
        "recorded {} of {} messages received (and {} Foxglove views): {messages} MCAP messages, {:.3} MB in {} file(s) over {seconds:.1} s ({:.2} MB/s)",
        recording.counter(metric::WRITTEN),
        recording.counter(metric::RECEIVED),
        recording.counter(metric::VIEWS_WRITTEN),
        bytes as f64 / 1e6,
        files.len(),
        bytes as f64 / 1e6 / seconds.max(1e-9)
    );
    for f in files {
        println!(
            "  {}: {} messages, {:.3} MB",
            f.path.display(),
            f.messages,
            f.bytes as f64 / 1e6
        );
        if let Some(ros2) = &f.ros2 {
            println!("    and its ROS 2 recording {}", ros2.display());
        }
    }
    let drops = recording.drops();
    let by_cause: Vec<String> = DropCause::ALL
        .iter()
        .map(|&c| format!("{c} {}", drops.of_cause(c)))
        .collect();
    println!("dropped {} ({})", drops.total(), by_cause.join(", "));
    for (topic, cause, n) in drops.iter() {
        println!("  {topic}: {cause} {n}");
    }
}
