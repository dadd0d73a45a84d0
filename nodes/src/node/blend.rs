//! The `blend` node: interactive scene composition (paper 001). It holds a
//! parent cloud (a file or a snapshot of a cloud stream) and a palette of
//! parts (files and the simulator's parts), follows drop / adjust / clear /
//! commit commands from `shroud/<ns>/blend/<name>` (a drop may name the part
//! to paste), and republishes the blended model as a cloud whose intensity is
//! each point's source (0 parent, 1 child, 2 transition). Its status labels
//! announce the palette (`blend.stream`, `blend.output`, `blend.parts`) for
//! dashboards.

use crate::args::{points3, BlendShapeArgs};
use crate::files;
use crate::runtime::{run_node, Arrival, Input, NodeCommon, NodeContext, Output};
use crate::transport::unix_ns;
use anyhow::{Context, Result};
use clap::Args;
use shroud_graph::metrics::names as metric;
use shroud_msg::{BlendCommandMessage, CloudMessage, CloudView, SensorPose, TopicKind};
use shroud_shapes::blend::{
    supersede_indices, BlendCommand, BlendParams, BlendSession, Child, PolygonOfInterest, Prepared,
};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

#[derive(Debug, Clone, Args)]
pub struct BlendNodeArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The parent cloud (.ply, .pcd, .xyz, .csv).
    #[arg(
        long,
        required_unless_present = "parent_stream",
        conflicts_with = "parent_stream"
    )]
    pub parent: Option<PathBuf>,
    /// Or: the first cloud of this stream (`shroud/<ns>/cloud/<name>`) is the parent.
    #[arg(long)]
    pub parent_stream: Option<String>,
    /// A part from a cloud file, with an open boundary (its polygon of
    /// interest); named by its file name in the palette. Repeatable.
    #[arg(long = "child", value_name = "FILE")]
    pub children: Vec<PathBuf>,
    /// A simulated part: hemisphere or half-cylinder. Repeatable. The palette
    /// is the files, then these; the first is held at the start.
    #[arg(long = "child-part", value_name = "NAME")]
    pub child_parts: Vec<String>,
    /// Size of the simulated part (its radius), cloud units.
    #[arg(long, default_value_t = 0.3)]
    pub part_size: f64,
    /// Points of the simulated part.
    #[arg(long, default_value_t = 3_000)]
    pub part_points: usize,
    /// Polygon of interest in the child's coordinates: "x,y,z;x,y,z;..."
    /// (default: the child's longest open boundary loop). Only with a single part.
    #[arg(long, allow_hyphen_values = true)]
    pub polygon: Option<String>,
    /// Command stream (`shroud/<ns>/blend/<name>`) and, unless --output is given,
    /// the blended cloud's stream (`shroud/<ns>/cloud/<name>`).
    #[arg(long, default_value = "blend")]
    pub stream: String,
    /// Stream of the blended cloud.
    #[arg(long)]
    pub output: Option<String>,
    /// Republish the unchanged model this often (seconds; 0: only on change),
    /// so that a dashboard that joins late sees it.
    #[arg(long, default_value_t = 1.0)]
    pub republish: f64,
    #[command(flatten)]
    pub shape: BlendShapeArgs,
}

pub fn run(args: BlendNodeArgs) -> Result<()> {
    let params = args.shape.params()?;
    anyhow::ensure!(
        args.republish.is_finite() && args.republish >= 0.0,
        "--republish must be >= 0 seconds"
    );
    let common = args.common.clone();
    run_node(&common, "blend", move |ctx| serve(ctx, args, params))
}

fn serve(ctx: Arc<NodeContext>, args: BlendNodeArgs, params: BlendParams) -> Result<()> {
    // A bad stream name is refused before the wait for the parent.
    ctx.key(TopicKind::Blend, &args.stream)?;
    let output = args.output.as_deref().unwrap_or(&args.stream);
    let mut palette = Palette::new(&args, &params)?;
    let m = &ctx.metrics;
    m.set_label("blend.stream".into(), args.stream.clone());
    m.set_label("blend.output".into(), output.to_string());
    m.set_label("blend.parts".into(), palette.names().join(","));
    let Some((parent, parent_age)) = parent(&ctx, &args, &params)? else {
        return Ok(()); // stopped while waiting for the parent stream
    };
    let mut session = BlendSession::new(parent, palette.take_first(), params);
    // Every command counts (a commit must not be lost), so the queue is deep;
    // the worker skips the drops a later drop supersedes instead.
    let commands = ctx.subscribe::<BlendCommandMessage>(&args.stream, 1024)?;
    // The model is large and each one supersedes the last: a cloud topic.
    let output = ctx.output_shared::<CloudMessage>(output, 64 << 20)?;
    let mut model = Model {
        ctx: &ctx,
        output: &output,
        source: format!("{}/blend", ctx.name),
        sequence: 0,
        parent_age,
    };
    tracing::info!(commands = commands.key(), output = output.key(), "blending");
    model.publish(&session);
    let mut last_publish = Instant::now();
    let republish = (args.republish > 0.0).then(|| Duration::from_secs_f64(args.republish));
    while !ctx.stopping() {
        let Some(first) = commands.recv_timeout(Duration::from_millis(100)) else {
            if republish.is_some_and(|period| last_publish.elapsed() >= period) {
                model.publish(&session);
                last_publish = Instant::now();
            }
            continue;
        };
        let mut batch = vec![first];
        while let Some(more) = commands.recv_timeout(Duration::ZERO) {
            batch.push(more);
        }
        if apply_batch(&ctx, &commands, &mut session, &mut palette, &batch) {
            model.publish(&session);
            last_publish = Instant::now();
        }
    }
    Ok(())
}

/// Decodes and applies a batch of commands; true when the model changed.
fn apply_batch(
    ctx: &NodeContext,
    commands: &Input<BlendCommandMessage>,
    session: &mut BlendSession,
    palette: &mut Palette,
    batch: &[Arrival],
) -> bool {
    let decoded: Vec<(BlendCommand, Option<String>)> = batch
        .iter()
        .filter_map(|arrival| {
            let command = commands.decoded(arrival, |m| Ok((m.command()?, m.part)))?;
            command
                .map_err(|e: shroud_msg::MessageError| ctx.drop_malformed(&arrival.key, &e))
                .ok()
        })
        .collect();
    let todo = supersede_indices(&decoded.iter().map(|(c, _)| *c).collect::<Vec<_>>());
    ctx.metrics
        .add(metric::SUPERSEDED, (decoded.len() - todo.len()) as u64);
    let mut changed = false;
    for (command, part) in todo.into_iter().map(|i| &decoded[i]) {
        if let Some(name) = part {
            if let Err(e) = palette.hold(session, name) {
                ctx.metrics.add(metric::BLEND_ERRORS, 1);
                tracing::warn!("drop refused: {e:#}");
                continue;
            }
        }
        let start = Instant::now();
        match session.apply(command) {
            Ok(report) => {
                changed = true;
                ctx.metrics.add(metric::APPLIED, 1);
                if let Some(r) = report {
                    ctx.metrics
                        .set(metric::BLEND_MS, start.elapsed().as_secs_f64() * 1e3);
                    ctx.metrics.set(metric::CENTRES, r.greedy.centres as f64);
                    ctx.metrics
                        .set(metric::TRANSITION_POINTS, r.kept_transition as f64);
                }
                ctx.metrics.set(metric::COMMITS, session.commits() as f64);
            }
            Err(e) => {
                ctx.metrics.add(metric::BLEND_ERRORS, 1);
                tracing::warn!(?command, "blend command refused: {e}");
            }
        }
    }
    changed
}

/// The parts a drop may paste, prepared once; the session holds one of them.
struct Palette {
    names: Vec<String>,
    /// `None` at the held part's place (the session has it).
    parts: Vec<Option<Child>>,
    held: usize,
}

impl Palette {
    fn new(args: &BlendNodeArgs, params: &BlendParams) -> Result<Self> {
        let count = args.children.len() + args.child_parts.len();
        anyhow::ensure!(
            count > 0,
            "give at least one --child FILE or --child-part NAME"
        );
        anyhow::ensure!(
            args.polygon.is_none() || count == 1,
            "--polygon names the polygon of one part: give a single --child or --child-part with it"
        );
        let polygon = match &args.polygon {
            Some(text) => Some(PolygonOfInterest::from_polyline(points3(text, "polygon")?)?),
            None => None,
        };
        let mut palette = Self {
            names: Vec::new(),
            parts: Vec::new(),
            held: 0,
        };
        for path in &args.children {
            let points = files::read_cloud(path)?;
            let name = part_name(path);
            let child = prepare_child(&points, polygon.clone(), params)
                .with_context(|| format!("part {}", path.display()))?;
            palette.add(name, child)?;
        }
        for name in &args.child_parts {
            let points = shroud_sim::parts::part_by_name(name, args.part_size, args.part_points)?;
            let child = prepare_child(&points, polygon.clone(), params)
                .with_context(|| format!("part {name}"))?;
            palette.add(name.clone(), child)?;
        }
        Ok(palette)
    }

    fn add(&mut self, name: String, child: Child) -> Result<()> {
        anyhow::ensure!(!self.names.contains(&name), "two parts are called {name:?}");
        self.names.push(name);
        self.parts.push(Some(child));
        Ok(())
    }

    fn names(&self) -> &[String] {
        &self.names
    }

    /// The first part, for the session to hold.
    fn take_first(&mut self) -> Child {
        self.held = 0;
        self.parts[0].take().expect("a palette has a first part")
    }

    /// Makes the session hold part `name` (it keeps it if it holds it).
    fn hold(&mut self, session: &mut BlendSession, name: &str) -> Result<()> {
        let Some(index) = self.names.iter().position(|n| n == name) else {
            anyhow::bail!("no part {name:?} (the parts are {})", self.names.join(", "));
        };
        if index != self.held {
            let child = self.parts[index].take().expect("only the held part is out");
            self.parts[self.held] = Some(session.replace_child(child));
            self.held = index;
        }
        Ok(())
    }
}

/// A part's name in the palette: its file name, with characters a name may
/// not hold replaced by `_`.
fn part_name(path: &std::path::Path) -> String {
    let base = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let clean: String = base
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .take(64)
        .collect();
    if clean.is_empty() {
        "part".into()
    } else {
        clean
    }
}

fn prepare_child(
    points: &[[f32; 3]],
    polygon: Option<PolygonOfInterest>,
    params: &BlendParams,
) -> Result<Child> {
    let cloud = Prepared::new(points, "child", params.normal_k)?;
    Ok(Child::new(cloud, polygon, &params.boundary)?)
}

/// Where the blended model goes.
struct Model<'a> {
    ctx: &'a NodeContext,
    output: &'a Output<CloudMessage>,
    source: String,
    sequence: u64,
    parent_age: DataAge,
}

/// How old the parent's data is: its time in shroud before it reached this
/// node, and when it did (a snapshot only grows older; a composed model is
/// as old as its parent).
#[derive(Debug, Clone, Copy)]
struct DataAge {
    pipeline_ns: u64,
    received: Instant,
}

impl DataAge {
    fn now_ns(&self) -> u64 {
        let held = self.received.elapsed().as_nanos() as u64;
        self.pipeline_ns.saturating_add(held)
    }
}

impl Model<'_> {
    fn publish(&mut self, session: &BlendSession) {
        let (points, sources) = session.model();
        let xyz: Vec<[f32; 3]> = points.iter().map(|p| p.as_vec3().to_array()).collect();
        let codes: Vec<f32> = (0..points.len())
            .map(|i| f32::from(sources.get(i) as u8))
            .collect();
        let view = CloudView::new(
            unix_ns(),
            self.sequence,
            &self.source,
            SensorPose::default(),
            &xyz,
        )
        .with_intensity(&codes)
        .with_pipeline_ns(self.parent_age.now_ns());
        match view.aligned() {
            Ok(view) => {
                self.output.put(&view);
            }
            Err(e) => {
                self.ctx.metrics.add(metric::PUBLISH_ERRORS, 1);
                tracing::warn!("publish the blended cloud: {e}");
            }
        }
        self.ctx.metrics.set(metric::POINTS, points.len() as f64);
        self.sequence += 1;
    }
}

/// The parent and its age: read from its file (as old as the node's copy of
/// it), or the first valid cloud of its stream (`None` if the node is
/// stopped first).
fn parent(
    ctx: &Arc<NodeContext>,
    args: &BlendNodeArgs,
    params: &BlendParams,
) -> Result<Option<(Prepared, DataAge)>> {
    if let Some(path) = &args.parent {
        let points = files::read_cloud(path)?;
        let age = DataAge {
            pipeline_ns: 0,
            received: Instant::now(),
        };
        let parent = Prepared::new(&points, "parent", params.normal_k)
            .with_context(|| format!("parent {}", path.display()))?;
        return Ok(Some((parent, age)));
    }
    let stream = args.parent_stream.as_deref().unwrap_or("sim");
    let input = ctx.subscribe::<CloudMessage>(stream, 1)?;
    tracing::info!(key = input.key(), "waiting for the parent cloud");
    while !ctx.stopping() {
        let Some(arrival) = input.recv_timeout(Duration::from_millis(100)) else {
            continue;
        };
        // Validated as a whole message (intensity and channels too), as
        // `CloudMessage::from_bytes` does.
        let decoded = input.decoded(&arrival, |cloud| {
            let cloud = cloud.to_message()?;
            Ok::<_, shroud_msg::MessageError>((cloud.point_array()?, cloud.pipeline_ns))
        });
        let (points, pipeline_ns) = match decoded {
            Some(Ok(decoded)) => decoded,
            Some(Err(e)) => {
                ctx.drop_malformed(&arrival.key, &e);
                continue;
            }
            None => continue,
        };
        // Its age runs from its arrival, on this node's clock.
        let now = Instant::now();
        let received = now
            .checked_sub(Duration::from_nanos(arrival.held_ns()))
            .unwrap_or(now);
        match Prepared::new(&points, "parent", params.normal_k) {
            Ok(parent) => {
                let age = DataAge {
                    pipeline_ns,
                    received,
                };
                return Ok(Some((parent, age)));
            }
            Err(e) => {
                ctx.metrics.add(metric::PARENT_REFUSED, 1);
                tracing::warn!(key = input.key(), "parent cloud refused: {e}");
            }
        }
    }
    Ok(None)
}
