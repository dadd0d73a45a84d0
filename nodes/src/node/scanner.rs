//! The `scanner` node: the simulator as a sensor. Publishes one cloud per tick of
//! a fixed-rate clock; a frame that cannot be produced in time is skipped and
//! counted rather than delaying every later one.

use crate::runtime::{run_node, NodeCommon, NodeContext};
use crate::transport::unix_ns;
use anyhow::{Context, Result};
use clap::Args;
use shroud_graph::metrics::names as metric;
use shroud_msg::{CloudMessage, CloudView, SensorPose};
use shroud_shapes::format::parse_triangle_mesh;
use shroud_sim::{RangeScanner, ScanResolution, Scene};
use std::sync::Arc;
use std::time::{Duration, Instant};

#[derive(Debug, Clone, Args)]
pub struct ScannerArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// Scene to scan (see `shroud sim --help` for the list).
    #[arg(long, default_value = "moving-spheres")]
    pub scene: String,
    /// Points per frame.
    #[arg(long, default_value_t = 30_000)]
    pub points: usize,
    /// Frames per second.
    #[arg(long, default_value_t = 10.0)]
    pub rate: f64,
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
    /// Stream name: clouds go to `shroud/<ns>/cloud/<stream>`.
    #[arg(long, default_value = "sim")]
    pub stream: String,
    /// Before the first frame, wait up to this many seconds for a
    /// subscriber (a zenoh peer drops what it publishes before it has heard
    /// of one; useful with --frames).
    #[arg(long, default_value_t = 0.0, value_name = "S")]
    pub wait_subscribers: f64,
    /// Stop after this many frames (0: run until stopped).
    #[arg(long, default_value_t = 0)]
    pub frames: u64,
    /// Scene seconds per wall second (0 freezes the scene).
    #[arg(long, default_value_t = 1.0)]
    pub time_scale: f64,
    /// With `--scene scan-mesh`: the mesh to range-scan (.obj or .ply).
    #[arg(long)]
    pub mesh: Option<std::path::PathBuf>,
    /// A JSON scene configuration (`shroud_sim::Scene`, as `shroud sim
    /// --config`), instead of `--scene`, `--points` and `--seed`.
    #[arg(long, conflicts_with_all = ["scene", "mesh", "points", "seed"])]
    pub config: Option<std::path::PathBuf>,
}

pub fn run(args: ScannerArgs) -> Result<()> {
    anyhow::ensure!(
        args.rate.is_finite() && args.rate > 0.0 && args.rate <= 1000.0,
        "--rate must be in (0, 1000] frames per second"
    );
    anyhow::ensure!(args.time_scale.is_finite(), "--time-scale must be finite");
    anyhow::ensure!(
        args.wait_subscribers.is_finite() && (0.0..=3600.0).contains(&args.wait_subscribers),
        "--wait-subscribers must be between 0 and 3600 seconds"
    );
    let scene = scene(&args)?;
    let common = args.common.clone();
    run_node(&common, "scanner", move |ctx| serve(ctx, args, scene))
}

/// The scene by name; `scan-mesh` orbits a range scanner around the user's mesh.
fn scene(args: &ScannerArgs) -> Result<Scene> {
    if let Some(path) = &args.config {
        let scene = crate::files::read_scene_config(path)?;
        scene.prepare()?;
        return Ok(scene);
    }
    if args.scene != Scene::MESH_SCENE {
        anyhow::ensure!(
            args.mesh.is_none(),
            "--mesh is only for --scene {}",
            Scene::MESH_SCENE
        );
        let scene = Scene::by_name(&args.scene, args.points, args.seed)
            .with_context(|| format!("scene {:?}", args.scene))?;
        scene.prepare()?;
        return Ok(scene);
    }
    let path = args
        .mesh
        .as_ref()
        .context("--scene scan-mesh needs --mesh FILE")?;
    let bytes =
        std::fs::read(path).with_context(|| format!("cannot read mesh {}", path.display()))?;
    let mesh = parse_triangle_mesh(&bytes).with_context(|| format!("mesh {}", path.display()))?;
    let scanner = RangeScanner {
        resolution: ScanResolution::Points(args.points),
        seed: args.seed,
        ..RangeScanner::orbiting(&mesh)?
    };
    let scene = Scene::scan_mesh(mesh, scanner)?;
    scene.prepare()?;
    Ok(scene)
}

fn serve(ctx: Arc<NodeContext>, args: ScannerArgs, scene: Scene) -> Result<()> {
    // Room for a few frames in flight: 12 bytes a point plus the header.
    let points = scene.points();
    let output = ctx.output_shared::<CloudMessage>(&args.stream, 4 * (points * 12 + 4096))?;
    let key = output.key();
    tracing::info!(%key, scene = scene.name(), points, rate = args.rate, shm = output.uses_shm(), "scanning");
    let patience = Duration::from_secs_f64(args.wait_subscribers);
    if args.wait_subscribers > 0.0 && !ctx.wait_for_subscriber(output.publisher(), patience) {
        tracing::warn!(%key, "no subscriber after --wait-subscribers: publishing anyway");
    }
    let period = Duration::from_secs_f64(1.0 / args.rate);
    let start = Instant::now();
    let mut next = start;
    let mut sequence = 0u64;
    let source = format!("{}/{}", ctx.name, scene.name());
    while !ctx.stopping() && (args.frames == 0 || sequence < args.frames) {
        let now = Instant::now();
        if now < next {
            std::thread::sleep((next - now).min(Duration::from_millis(50)));
            continue;
        }
        let behind = ((now - next).as_secs_f64() / period.as_secs_f64()) as u64;
        if behind > 0 {
            ctx.metrics.add(metric::MISSED_TICKS, behind);
        }
        next += period * (behind as u32 + 1);
        // The simulator is the sensor: the cloud shows the scene at the time
        // read here, so its age counts from now (generation included).
        let sampled = Instant::now();
        let time = start.elapsed().as_secs_f64() * args.time_scale;
        let (points, no_return) = scene.generate_with_no_return(time)?;
        let mut msg = CloudView::new(unix_ns(), sequence, &source, SensorPose::default(), &points)
            .with_pipeline_ns(sampled.elapsed().as_nanos() as u64);
        // A scan scene's scanner states where it looked; a sampled scene
        // (the moving spheres) has no sensor and states nothing.
        if let Some(fov) = scene.field_of_view(time)? {
            msg = msg.with_field_of_view(fov)?;
        }
        // So does it where its rays came back empty: a black object there
        // would look like empty space.
        if let Some(no_return) = no_return {
            msg = msg.with_no_return(no_return)?;
        }
        output.put(&msg.aligned()?);
        ctx.metrics.set(metric::POINTS, points.len() as f64);
        sequence += 1;
    }
    Ok(())
}
