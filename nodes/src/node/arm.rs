//! The `arm` node: a simulated manipulator that follows the trajectory of its
//! arm file, publishes its joint states, and moves only while its [`Deadman`]
//! allows: a fresh `clear` for one of its own recent joint states. A stop, a
//! stale surrogate, or a guard that falls silent halts it; it resumes where it
//! stopped once the guard clears it again (wait and resume). A `clear` with a
//! speed scale below 1 slows it: its trajectory's time runs at that fraction
//! of real time, and its joint states carry the velocities it moves at.

use crate::arm_file::{joint_names, read_arm_file};
use crate::runtime::{run_node, Arrival, NodeCommon, NodeContext};
use crate::transport::{monotonic_ns, unix_ns};
use anyhow::{Context, Result};
use clap::Args;
use shroud_graph::metrics::names::{self as metric, Counter};
use shroud_guard::{ArmFile, Deadman, Motion, ResumeAfter, Trajectory, VerdictUse};
use shroud_msg::{CollisionMessage, GuardVerdict, JointStateMessage};
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

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
    /// The deadman's deadline in seconds: halt when no clear verdict for a
    /// joint state sent within this long has arrived (default: three periods,
    /// at most the arm file's `[guard] horizon`; a longer one is refused, since
    /// the guard's allowance covers only the horizon).
    #[arg(long)]
    pub deadline: Option<f64>,
    /// After a halt, resume once motion has been allowed for this long
    /// (seconds), so that a clearance hovering at the stop distance halts the
    /// arm once rather than in a stutter.
    #[arg(long, default_value_t = 0.3)]
    pub resume_after: f64,
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
    anyhow::ensure!(
        args.resume_after.is_finite() && (0.0..=60.0).contains(&args.resume_after),
        "--resume-after must be in [0, 60] seconds"
    );
    if let Some(d) = args.deadline {
        anyhow::ensure!(
            d.is_finite() && d > 0.0 && d <= 10.0,
            "--deadline must be in (0, 10] seconds"
        );
    }
    Deadman::deadline_for(1.0 / args.rate, args.deadline, file.guard.horizon)
        .with_context(|| format!("--deadline against {}", args.arm_file.display()))?;
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

/// The deadman and the reason of the last verdict that was not clear.
struct Verdicts {
    deadman: Deadman,
    last_reason: String,
}

fn lock(v: &Mutex<Verdicts>) -> MutexGuard<'_, Verdicts> {
    v.lock().unwrap_or_else(|p| p.into_inner())
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
    let period = Duration::from_secs_f64(1.0 / args.rate);
    let deadline = Deadman::deadline_for(1.0 / args.rate, args.deadline, file.guard.horizon)?;
    let verdicts = Arc::new(Mutex::new(Verdicts {
        deadman: Deadman::new((deadline * 1e9) as u64),
        last_reason: String::new(),
    }));
    let _verdicts = {
        let (c, verdicts) = (ctx.clone(), verdicts.clone());
        ctx.listen::<CollisionMessage>(&arm_name, move |_: &Arrival, msg: CollisionMessage| {
            on_verdict(&c, &verdicts, &msg)
        })?
    };
    let joints = ctx.output::<JointStateMessage>(&arm_name)?;
    let names = joint_names(&file);
    let (mut motion_time, mut sequence) = (0.0f64, 0u64);
    let mut last = Instant::now();
    let mut positions = trajectory.positions_at(0.0)?;
    let mut halt = HaltLog::default();
    let mut resume = ResumeAfter::new((args.resume_after * 1e9) as u64);
    while !ctx.stopping() {
        let now = Instant::now();
        let (motion, scale) = if args.ignore_guard {
            (Motion::Move, 1.0)
        } else {
            let now_ns = monotonic_ns();
            let v = lock(&verdicts);
            let allowed = v.deadman.motion(now_ns);
            (resume.motion(allowed, now_ns), v.deadman.scale(now_ns))
        };
        // Trajectory time advances only while the arm is allowed to move,
        // at the verdict's speed scale (a time-scaled trajectory: the same
        // path, never faster than nominal).
        let scale = if motion == Motion::Move { scale } else { 0.0 };
        if scale > 0.0 {
            motion_time += scale * (now - last).as_secs_f64();
            positions = trajectory.positions_at(motion_time)?;
        }
        let velocities: Vec<f64> = trajectory
            .velocities_at(motion_time)?
            .iter()
            .map(|v| v * scale)
            .collect();
        // Not under the lock: a log line may block on a slow stderr.
        let reason = lock(&verdicts).last_reason.clone();
        halt.update(&ctx, motion, &reason, now);
        last = now;
        let stamp_ns = unix_ns();
        let msg = JointStateMessage::new(
            stamp_ns,
            sequence,
            &arm_name,
            names.clone(),
            positions.clone(),
        )
        .with_velocities(velocities);
        lock(&verdicts)
            .deadman
            .sent(sequence, stamp_ns, monotonic_ns());
        joints.put(&msg);
        ctx.metrics.set(metric::TRAJECTORY_S, motion_time);
        ctx.metrics.set(metric::SPEED_SCALE, scale);
        sequence += 1;
        std::thread::sleep(period.saturating_sub(now.elapsed()));
    }
    Ok(())
}

fn on_verdict(ctx: &NodeContext, verdicts: &Mutex<Verdicts>, msg: &CollisionMessage) {
    let mut v = lock(verdicts);
    match v.deadman.scaled_verdict(
        msg.joints_sequence,
        msg.joints_stamp_ns,
        msg.verdict,
        msg.speed_scale,
    ) {
        VerdictUse::Applied => ctx.metrics.add(metric::VERDICTS, 1),
        VerdictUse::Unknown => ctx.metrics.add(metric::VERDICTS_UNKNOWN, 1),
        VerdictUse::Superseded => ctx.metrics.add(metric::VERDICTS_SUPERSEDED, 1),
    }
    if msg.stop {
        v.last_reason = format!("{}: {}", msg.verdict.name(), msg.reason);
    }
}

/// Halts as they happen: `halts` counts them, `halts_<cause>` counts each
/// halt once under every cause that held it, they are logged with their
/// reason and their length, and the time spent halted is in the status.
#[derive(Default)]
struct HaltLog {
    since: Option<(Instant, GuardVerdict)>,
    /// The causes of the current halt counted so far.
    counted: Vec<GuardVerdict>,
    halted_s: f64,
}

impl HaltLog {
    fn update(&mut self, ctx: &NodeContext, motion: Motion, reason: &str, now: Instant) {
        match (motion, self.since) {
            (Motion::Halt(v), None) => {
                ctx.metrics.add(metric::HALTS, 1);
                self.counted.clear();
                self.count_cause(ctx, v);
                tracing::warn!("halted: {}", Self::why(v, reason));
                self.since = Some((now, v));
            }
            // A halt whose cause changes (a stop that turns stale when the
            // sensor goes away) counts under its new cause too, once, so each
            // `halts_<cause>` says whether that cause ever held the arm.
            (Motion::Halt(v), Some((start, was))) if v != was => {
                self.count_cause(ctx, v);
                tracing::warn!("still halted, now {}", Self::why(v, reason));
                self.since = Some((start, v));
            }
            (Motion::Move, Some((start, v))) => {
                let held = (now - start).as_secs_f64();
                self.halted_s += held;
                tracing::info!("resumed after {held:.2} s halted ({})", v.name());
                self.since = None;
            }
            _ => {}
        }
        let current = self
            .since
            .map_or(0.0, |(start, _)| (now - start).as_secs_f64());
        let m = &ctx.metrics;
        m.set(metric::HALTED, if self.since.is_some() { 1.0 } else { 0.0 });
        m.set(metric::HALTED_S, self.halted_s + current);
        m.set(metric::HALT_CURRENT_S, current);
    }

    fn count_cause(&mut self, ctx: &NodeContext, v: GuardVerdict) {
        if !self.counted.contains(&v) {
            self.counted.push(v);
            ctx.metrics.add(Counter::of(v.halt_counter()), 1);
        }
    }

    fn why(v: GuardVerdict, reason: &str) -> &str {
        if v == GuardVerdict::NoVerdict {
            "no-verdict: no fresh clear verdict within the deadline"
        } else {
            reason
        }
    }
}
