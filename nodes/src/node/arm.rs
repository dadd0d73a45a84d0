//! The `arm` node: a simulated manipulator that follows the trajectory of its
//! arm file, publishes its joint states, and halts while the guard says stop.

use super::arm_file::{joint_names, read_arm_file};
use super::runtime::{run_node, NodeCommon, NodeContext};
use crate::transport::unix_ns;
use anyhow::{Context, Result};
use clap::Args;
use shroud_core::guard::{ArmFile, Trajectory};
use shroud_core::message::{CollisionMessage, JointStateMessage, TopicKind};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use zenoh::qos::{CongestionControl, Priority};
use zenoh::Wait;

#[derive(Debug, Clone, Args)]
pub struct ArmArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The arm and its [trajectory] (TOML).
    #[arg(long)]
    pub arm_file: PathBuf,
    /// Joint and collision stream name (default: the arm file's name).
    #[arg(long)]
    pub arm: Option<String>,
    /// Joint states per second.
    #[arg(long, default_value_t = 50.0)]
    pub rate: f64,
    /// Keep moving whatever the guard says (to watch the guard's verdicts alone).
    #[arg(long)]
    pub ignore_guard: bool,
}

pub fn run(args: ArmArgs) -> Result<()> {
    let file = read_arm_file(&args.arm_file)?;
    anyhow::ensure!(
        args.rate.is_finite() && args.rate > 0.0 && args.rate <= 1000.0,
        "--rate must be in (0, 1000] per second"
    );
    let trajectory = file.trajectory.clone().with_context(|| {
        format!(
            "arm file {} has no [trajectory] to follow",
            args.arm_file.display()
        )
    })?;
    let common = args.common.clone();
    run_node(&common, "arm", move |ctx| {
        serve(ctx, args, file, trajectory)
    })
}

fn serve(
    ctx: Arc<NodeContext>,
    args: ArmArgs,
    file: ArmFile,
    trajectory: Trajectory,
) -> Result<()> {
    let arm_name = args
        .arm
        .clone()
        .unwrap_or_else(|| file.arm.name().to_string());
    let joints_key = ctx.key(TopicKind::Joints, &arm_name)?;
    let collision_key = ctx.key(TopicKind::Collision, &arm_name)?;
    // Halted until the guard first says clear: no surrogate, no motion.
    let halted = Arc::new(AtomicBool::new(!args.ignore_guard));
    let _verdicts = {
        let (c, halted) = (ctx.clone(), halted.clone());
        let obey = !args.ignore_guard;
        ctx.session
            .declare_subscriber(&collision_key)
            .callback(move |sample| {
                match CollisionMessage::from_bytes(&sample.payload().to_bytes()) {
                    Ok(msg) if obey => {
                        let was = halted.swap(msg.stop, Ordering::Relaxed);
                        if msg.stop && !was {
                            c.metrics.add("halts", 1);
                            tracing::warn!(
                                "halted by the guard: {:?} at {} ({:.3} m)",
                                msg.verdict,
                                msg.closest_link,
                                msg.min_clearance
                            );
                        }
                    }
                    Ok(_) => {}
                    Err(e) => c.drop_malformed(sample.key_expr().as_str(), &e),
                }
            })
            .wait()
            .map_err(|e| anyhow::anyhow!("subscribe {collision_key}: {e}"))?
    };
    let publisher = ctx
        .session
        .declare_publisher(joints_key.clone())
        .congestion_control(CongestionControl::Drop)
        .priority(Priority::RealTime)
        .express(true)
        .wait()
        .map_err(|e| anyhow::anyhow!("publisher {joints_key}: {e}"))?;
    let names = joint_names(&file);
    let period = Duration::from_secs_f64(1.0 / args.rate);
    let (mut motion_time, mut sequence) = (0.0f64, 0u64);
    let mut last = Instant::now();
    let mut positions = trajectory.positions_at(0.0)?;
    while !ctx.stopping() {
        let now = Instant::now();
        // Trajectory time advances only while the arm is allowed to move.
        if !halted.load(Ordering::Relaxed) {
            motion_time += (now - last).as_secs_f64();
            positions = trajectory.positions_at(motion_time)?;
        }
        last = now;
        let msg = JointStateMessage::new(
            unix_ns(),
            sequence,
            &arm_name,
            names.clone(),
            positions.clone(),
        );
        match publisher.put(msg.to_bytes()?).wait() {
            Ok(()) => ctx.metrics.add("published", 1),
            Err(e) => tracing::warn!("publish joints: {e}"),
        }
        ctx.metrics.set(
            "halted",
            if halted.load(Ordering::Relaxed) {
                1.0
            } else {
                0.0
            },
        );
        ctx.metrics.set("trajectory_s", motion_time);
        sequence += 1;
        std::thread::sleep(period.saturating_sub(now.elapsed()));
    }
    Ok(())
}
