//! The `guard` node: the onboard conservative collision envelope. It feeds the
//! latest certified surrogate of each view into a [`CollisionGuard`] and answers
//! every joint state, usable or not, with a verdict: silence always means
//! trouble to the consumer's deadman.

use crate::arm_file::{joint_names, read_arm_file};
use crate::runtime::{run_node, Arrival, NodeCommon, NodeContext, NodeMetrics, OnMessage, Output};
use crate::transport::monotonic_ns;
use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use shroud_geometry::cloud::MAX_SECTOR_GRID;
use shroud_graph::metrics::names::{self as metric, Counter};
use shroud_guard::{
    ArmFile, ArmMotion, CollisionGuard, Decision, Envelope, GuardPolicy, JointMotionSample,
    SpeedMonitor, StoppingModel, SurrogateInput, UnobservedPolicy,
};
use shroud_msg::{
    is_sector_stream, max_skew_ns_from_secs, sector_stream, CollisionMessage, JointStateMessage,
    MessageError, SurrogateMessage,
};
use shroud_surrogate::SurrogateWire;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

#[derive(Debug, Clone, Args)]
pub struct GuardArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The arm: joints, links and collision spheres (TOML).
    #[arg(long)]
    pub arm_file: PathBuf,
    /// Surrogate stream to guard against (`shroud/<ns>/surrogate/<name>`).
    /// Repeat for several views of the same cloud (fit nodes with different
    /// `--dir`): per shape the best of the views' bounds counts.
    #[arg(long = "surrogate", default_value = "sim")]
    pub surrogates: Vec<String>,
    /// Also read the N x N sectors of each surrogate stream
    /// (`<name>.s<k>`, from a fit node with the same `sectors`), each a view
    /// of its own (0: the streams alone; needs `--unobserved stop`).
    #[arg(long, default_value_t = 0, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(0..=8))]
    pub sectors: usize,
    /// Joint and collision stream name (default: the arm file's name).
    #[arg(long)]
    pub arm: Option<String>,
    /// Stop below this clearance in metres (default: the arm file's [guard] table).
    #[arg(long)]
    pub stop_distance: Option<f64>,
    /// A surrogate older than this (seconds: time since it reached the guard
    /// plus the pipeline delay the upstream nodes measured) vouches for nothing.
    #[arg(long, default_value_t = 1.0)]
    pub max_age: f64,
    /// A surrogate whose source stamp is further than this (seconds) from this
    /// node's clock is refused and counted as `clock_skew` (`inf`: no check,
    /// e.g. for replays of old logs).
    #[arg(long, default_value_t = 5.0)]
    pub max_skew: f64,
    /// Bound (seconds) on how far the fit nodes' wall clocks and this node's
    /// may disagree: added to every surrogate's measured transit, and a
    /// surrogate that seems to come from further in the future is refused
    /// (`clock_offset`). One host: the default; across hosts: the clock
    /// synchronisation's bound.
    #[arg(long, default_value_t = 0.001)]
    pub max_clock_offset: f64,
    /// Bound on obstacle speed (m/s): clearances shrink by this times the
    /// surrogate's age (default: the arm file's [guard] table, else 0).
    #[arg(long)]
    pub max_obstacle_speed: Option<f64>,
    /// Space no fresh view saw (outside its domain, over trimmed cells):
    /// `stop` counts it as occupied (verdict `unobserved` when a link comes
    /// within the stop distance of it); `ignore` judges by the occupied space
    /// seen alone, as if the sensors had seen everything.
    #[arg(long, value_enum, default_value_t = Unobserved::Stop)]
    pub unobserved: Unobserved,
}

/// `--unobserved` on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Unobserved {
    Stop,
    Ignore,
}

pub fn run(args: GuardArgs) -> Result<()> {
    let mut file = read_arm_file(&args.arm_file)?;
    if let Some(d) = args.stop_distance {
        file.guard.stop_distance = d;
        file.guard.max_report = file.guard.max_report.max(d);
    }
    if let Some(v) = args.max_obstacle_speed {
        file.guard.max_obstacle_speed = v;
    }
    let policy = policy(&args)?;
    anyhow::ensure!(
        args.sectors <= MAX_SECTOR_GRID,
        "--sectors must be 0 to {MAX_SECTOR_GRID}"
    );
    // A sector vouches only for its cone: judged by occupied space alone, it
    // would call free a shape beside it that another view saw blocked.
    anyhow::ensure!(
        args.sectors == 0 || args.unobserved == Unobserved::Stop,
        "--sectors needs --unobserved stop: a sector says nothing outside its cone"
    );
    if let Some(name) = args.surrogates.iter().find(|n| is_sector_stream(n)) {
        anyhow::ensure!(
            args.unobserved == Unobserved::Stop,
            "--surrogate {name} is a sector's stream: it needs --unobserved stop (a sector says nothing outside its cone)"
        );
    }
    let views = view_names(&args);
    if views.len() > 1 && file.guard.max_obstacle_speed == 0.0 {
        tracing::warn!(
            "several views and --max-obstacle-speed 0: views of different ages combine soundly only if nothing in the scene moves"
        );
    }
    let links = file.arm.links().iter().map(|l| l.name.clone()).collect();
    let mut guard = CollisionGuard::new(views, links, policy, file.guard)?;
    match &file.motion {
        Some(motion) => {
            announce_speed_monitoring(&file, motion);
            guard = guard.with_speed_monitor(SpeedMonitor::new(&file.arm, motion.clone())?);
        }
        None => tracing::info!(
            "the arm file has no [motion] table: no speed scaling (clear at full speed or stop; the stop distance must cover the arm's own motion)"
        ),
    }
    let common = args.common.clone();
    run_node(&common, "guard", move |ctx| serve(ctx, args, file, guard))
}

/// Says at start what speed monitoring assumes, and which terms are taken
/// as 0 for want of a value.
fn announce_speed_monitoring(file: &ArmFile, motion: &ArmMotion) {
    let joints: Vec<String> = file
        .arm
        .actuated_joints()
        .zip(&motion.joints)
        .map(|(j, m)| {
            let stop = match &m.stopping {
                StoppingModel::Deceleration(a) => format!("braking {a}/s²"),
                StoppingModel::Measured(t) => format!("{} measured stops", t.len()),
            };
            format!("{} <= {}/s, {stop}", j.name(), m.max_velocity)
        })
        .collect();
    tracing::info!(
        reaction_time_s = motion.reaction_time,
        position_uncertainty_m = motion.position_uncertainty,
        scale_rise_per_s = motion.scale_rise_per_second,
        max_obstacle_speed = file.guard.max_obstacle_speed,
        horizon_s = file.guard.horizon,
        "speed and separation monitoring (ISO/TS 15066): joints {}",
        joints.join("; ")
    );
    if motion.position_uncertainty == 0.0 {
        tracing::warn!("[motion] position_uncertainty (Z_r) is 0: the stop distance must cover the arm's position error");
    }
    if file.guard.max_obstacle_speed == 0.0 {
        tracing::warn!("max_obstacle_speed is 0: nothing may move in the cell (ISO 13855 takes 1.6 m/s for a walking person)");
    }
}

fn policy(args: &GuardArgs) -> Result<GuardPolicy> {
    anyhow::ensure!(
        args.max_age.is_finite() && args.max_age > 0.0,
        "--max-age must be positive"
    );
    anyhow::ensure!(
        args.max_clock_offset.is_finite() && (0.0..=10.0).contains(&args.max_clock_offset),
        "--max-clock-offset must be in [0, 10] seconds"
    );
    let max_skew_ns = max_skew_ns_from_secs(args.max_skew)
        .ok_or_else(|| anyhow::anyhow!("--max-skew must be positive (inf: no check)"))?;
    Ok(GuardPolicy {
        max_age_ns: (args.max_age * 1e9) as u64,
        max_skew_ns,
        max_clock_offset_ns: (args.max_clock_offset * 1e9) as u64,
        unobserved: match args.unobserved {
            Unobserved::Stop => UnobservedPolicy::Stop,
            Unobserved::Ignore => UnobservedPolicy::Ignore,
        },
    })
}

fn serve(
    ctx: Arc<NodeContext>,
    args: GuardArgs,
    file: ArmFile,
    guard: CollisionGuard,
) -> Result<()> {
    let arm_name = args
        .arm
        .clone()
        .unwrap_or_else(|| file.arm.name().to_string());
    let guard = Arc::new(Mutex::new(guard));
    let mut views = Vec::new();
    let names = view_names(&args);
    for (view, name) in names.iter().enumerate() {
        let feed = ViewFeed {
            metrics: ctx.metrics.clone(),
            guard: guard.clone(),
            view,
        };
        let listener = ctx.listen::<SurrogateMessage>(name, feed);
        views.push(listener.with_context(|| format!("view {name:?}"))?);
    }
    // A stop must not be lost to congestion: the collision topic blocks
    // rather than drops, at real-time priority.
    let verdicts = ctx.output::<CollisionMessage>(&arm_name)?;
    let collision_key = verdicts.key().to_owned();
    let checker = Checker {
        metrics: ctx.metrics.clone(),
        names: joint_names(&file),
        file,
        arm_name: arm_name.clone(),
        guard,
        verdicts,
    };
    let joints = ctx.listen::<JointStateMessage>(&arm_name, checker)?;
    tracing::info!(views = ?args.surrogates, sectors = args.sectors, joints = joints.key(), %collision_key, "guarding");
    while !ctx.stopping() {
        std::thread::sleep(Duration::from_millis(100));
    }
    drop(views);
    Ok(())
}

/// The streams the guard reads, one view each: every surrogate stream, then
/// its sectors' streams.
fn view_names(args: &GuardArgs) -> Vec<String> {
    let sectors = args.sectors * args.sectors;
    let mut names = args.surrogates.clone();
    for name in &args.surrogates {
        names.extend((0..sectors).map(|k| sector_stream(name, k)));
    }
    names
}

fn lock(guard: &Mutex<CollisionGuard>) -> MutexGuard<'_, CollisionGuard> {
    guard.lock().unwrap_or_else(|p| p.into_inner())
}

/// Feeds one view's surrogates into the guard, stamped with their arrival on
/// this node's clocks (before the envelope is built, so that the building
/// counts toward their age) and their publication's zenoh timestamp. A
/// surrogate that cannot be used withdraws the view's older one: newer data
/// exists that the guard cannot read, so the older no longer vouches.
struct ViewFeed {
    metrics: Arc<NodeMetrics>,
    guard: Arc<Mutex<CollisionGuard>>,
    view: usize,
}

impl OnMessage<SurrogateMessage> for ViewFeed {
    fn on_message(&self, arrival: &Arrival, msg: SurrogateMessage) {
        let key = &arrival.key;
        let Some(published_ns) = arrival.published_ns else {
            lock(&self.guard).invalidate(self.view);
            self.metrics.add(metric::NO_PUBLISH_STAMP, 1);
            return tracing::warn!(%key, "surrogate without a zenoh timestamp: its transit is unknown");
        };
        let envelope = msg
            .to_surrogate()
            .map_err(anyhow::Error::from)
            .and_then(|s| {
                Ok(Envelope::new(&s)?
                    .with_field_of_view(msg.field_of_view)?
                    .with_no_return(msg.no_return.as_ref())?)
            });
        let envelope = match envelope {
            Ok(envelope) => envelope,
            Err(e) => {
                lock(&self.guard).invalidate(self.view);
                return self.metrics.drop_malformed(key, &e);
            }
        };
        let input = SurrogateInput {
            envelope,
            stamp_ns: msg.source_stamp_ns,
            sequence: msg.source_sequence,
            pipeline_ns: msg.pipeline_ns,
            published_ns,
            position_error: msg.position_error_m,
        };
        let arrived = (arrival.received_ns, arrival.received_wall_ns);
        // Not under the lock: a log line may block on a slow stderr.
        let accepted = lock(&self.guard).accept(self.view, input, arrived.0, arrived.1);
        match accepted {
            Ok(()) => self.metrics.add(metric::SURROGATES, 1),
            Err(refused) => {
                self.metrics.add(Counter::of(refused.counter()), 1);
                tracing::warn!(%key, "surrogate refused: {refused}");
            }
        }
    }

    fn on_malformed(&self, metrics: &NodeMetrics, arrival: &Arrival, error: &MessageError) {
        lock(&self.guard).invalidate(self.view);
        metrics.drop_malformed(&arrival.key, error);
    }
}

/// Answers every joint state, usable or not, with a verdict.
struct Checker {
    metrics: Arc<NodeMetrics>,
    file: ArmFile,
    names: Vec<String>,
    arm_name: String,
    guard: Arc<Mutex<CollisionGuard>>,
    verdicts: Output<CollisionMessage>,
}

impl OnMessage<JointStateMessage> for Checker {
    /// A verdict when the joint state can be checked, else a stop that says
    /// why (and the message is counted as malformed).
    fn on_message(&self, arrival: &Arrival, msg: JointStateMessage) {
        let id = (msg.stamp_ns, msg.sequence);
        let decision = match self.decide(&msg, arrival) {
            Ok(d) => d,
            Err(e) => {
                self.metrics.drop_malformed(&arrival.key, &e);
                Decision::refused(format!("joint state not checked: {e:#}"))
            }
        };
        self.publish(&decision, id, arrival);
    }

    fn on_malformed(&self, metrics: &NodeMetrics, arrival: &Arrival, error: &MessageError) {
        metrics.drop_malformed(&arrival.key, error);
        let refused = Decision::refused(format!("undecodable joint state: {error}"));
        // It answers no joint state: no sequence a consumer sent.
        self.publish(&refused, (0, u64::MAX), arrival);
    }
}

impl Checker {
    fn decide(&self, joints: &JointStateMessage, arrival: &Arrival) -> Result<Decision> {
        anyhow::ensure!(
            joints.arm == self.arm_name,
            "joint state of arm {:?}, not {:?}",
            joints.arm,
            self.arm_name
        );
        anyhow::ensure!(
            joints.names == self.names,
            "joint names {:?} are not the arm's {:?}",
            joints.names,
            self.names
        );
        // A pose outside the joints' limits is a glitch, not a pose to judge.
        self.file.arm.check_limits(&joints.positions)?;
        let pose = self.file.arm.forward(&joints.positions)?;
        let mut guard = lock(&self.guard);
        let now_ns = monotonic_ns();
        let age_ns = if guard.monitors_speed() {
            guard.joint_state_age_ns(
                arrival.published_ns,
                arrival.received_wall_ns,
                arrival.received_ns,
                now_ns,
            )?
        } else {
            0
        };
        let sample = JointMotionSample {
            velocities: (!joints.velocities.is_empty()).then_some(joints.velocities.as_slice()),
            age_ns,
        };
        Ok(guard.decide_moving(&pose.shapes, sample, now_ns)?)
    }

    /// The check's time counts from the joint state's arrival (its decoding
    /// included).
    fn publish(&self, decision: &Decision, joints: (u64, u64), arrival: &Arrival) {
        let check_ns = monotonic_ns().saturating_sub(arrival.received_ns);
        let out: CollisionMessage =
            lock(&self.guard).message(decision, &self.arm_name, joints, check_ns);
        let m = &self.metrics;
        m.add(Counter::of(out.verdict.verdict_counter()), 1);
        if out.stop {
            m.add(metric::STOPS, 1);
        }
        m.set(metric::MIN_CLEARANCE, out.min_clearance);
        m.set(metric::SPEED_SCALE, out.speed_scale);
        m.set(metric::SURROGATE_AGE_MS, out.surrogate_age_ns as f64 / 1e6);
        m.set(metric::CHECK_US, check_ns as f64 / 1e3);
        self.verdicts.put(&out);
    }
}
