//! The `guard` node: the onboard conservative collision envelope. It keeps the
//! latest certified surrogate as an [`Envelope`] and answers every joint state
//! with per-link clearances and a stop flag.

use super::arm_file::{joint_names, read_arm_file};
use super::runtime::{run_node, NodeCommon, NodeContext};
use crate::transport::unix_ns;
use anyhow::Result;
use clap::Args;
use shroud_core::guard::{check_arm, ArmFile, Envelope, GuardConfig, GuardReport};
use shroud_core::message::{
    CollisionMessage, GuardVerdict, JointStateMessage, LinkClearance, SurrogateMessage, TopicKind,
    SCHEMA_VERSION,
};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use zenoh::qos::{CongestionControl, Priority};
use zenoh::Wait;

#[derive(Debug, Clone, Args)]
pub struct GuardArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The arm: joints, links and collision spheres (TOML).
    #[arg(long)]
    pub arm_file: PathBuf,
    /// Surrogate stream to guard against (`shroud/<ns>/surrogate/<name>`).
    #[arg(long, default_value = "sim")]
    pub surrogate: String,
    /// Joint and collision stream name (default: the arm file's name).
    #[arg(long)]
    pub arm: Option<String>,
    /// Stop below this clearance in metres (default: the arm file's [guard] table).
    #[arg(long)]
    pub stop_distance: Option<f64>,
    /// A surrogate whose cloud is older than this (seconds) no longer vouches for
    /// anything: the verdict becomes `stale` and the arm is stopped.
    #[arg(long, default_value_t = 1.0)]
    pub max_age: f64,
}

/// The surrogate currently guarded against.
struct Latest {
    envelope: Envelope,
    stamp_ns: u64,
    sequence: u64,
}

pub fn run(args: GuardArgs) -> Result<()> {
    let mut file = read_arm_file(&args.arm_file)?;
    if let Some(d) = args.stop_distance {
        file.guard = GuardConfig {
            stop_distance: d,
            max_report: file.guard.max_report.max(d),
            ..file.guard
        };
        file.guard.validate()?;
    }
    anyhow::ensure!(
        args.max_age.is_finite() && args.max_age > 0.0,
        "--max-age must be positive"
    );
    let common = args.common.clone();
    run_node(&common, "guard", move |ctx| serve(ctx, args, file))
}

fn serve(ctx: Arc<NodeContext>, args: GuardArgs, file: ArmFile) -> Result<()> {
    let arm_name = args
        .arm
        .clone()
        .unwrap_or_else(|| file.arm.name().to_string());
    let surrogate_key = ctx.key(TopicKind::Surrogate, &args.surrogate)?;
    let joints_key = ctx.key(TopicKind::Joints, &arm_name)?;
    let collision_key = ctx.key(TopicKind::Collision, &arm_name)?;
    let latest: Arc<Mutex<Option<Latest>>> = Arc::default();
    let _surrogates = {
        let (c, latest) = (ctx.clone(), latest.clone());
        ctx.session
            .declare_subscriber(&surrogate_key)
            .callback(move |sample| {
                let key = sample.key_expr().to_string();
                let built = SurrogateMessage::from_bytes(&sample.payload().to_bytes())
                    .map_err(anyhow::Error::from)
                    .and_then(|(msg, s)| Ok((msg, Envelope::new(&s)?)));
                match built {
                    Ok((msg, envelope)) => {
                        c.metrics.add("surrogates", 1);
                        *latest.lock().unwrap_or_else(|p| p.into_inner()) = Some(Latest {
                            envelope,
                            stamp_ns: msg.source_stamp_ns,
                            sequence: msg.source_sequence,
                        });
                    }
                    Err(e) => c.drop_malformed(&key, &e),
                }
            })
            .wait()
            .map_err(|e| anyhow::anyhow!("subscribe {surrogate_key}: {e}"))?
    };
    // A stop must not be lost to congestion: collision messages block rather
    // than drop, at real-time priority.
    let publisher = ctx
        .session
        .declare_publisher(collision_key.clone())
        .congestion_control(CongestionControl::Block)
        .priority(Priority::RealTime)
        .express(true)
        .wait()
        .map_err(|e| anyhow::anyhow!("publisher {collision_key}: {e}"))?;
    let checker = Checker {
        ctx: ctx.clone(),
        names: joint_names(&file),
        file,
        arm_name,
        max_age_ns: (args.max_age * 1e9) as u64,
        latest,
        publisher,
    };
    let _joints = ctx
        .session
        .declare_subscriber(&joints_key)
        .callback(move |sample| {
            checker.on_joints(sample.key_expr().as_str(), &sample.payload().to_bytes())
        })
        .wait()
        .map_err(|e| anyhow::anyhow!("subscribe {joints_key}: {e}"))?;
    tracing::info!(%surrogate_key, %joints_key, %collision_key, "guarding");
    while !ctx.stopping() {
        std::thread::sleep(Duration::from_millis(100));
    }
    Ok(())
}

struct Checker {
    ctx: Arc<NodeContext>,
    file: ArmFile,
    names: Vec<String>,
    arm_name: String,
    max_age_ns: u64,
    latest: Arc<Mutex<Option<Latest>>>,
    publisher: zenoh::pubsub::Publisher<'static>,
}

impl Checker {
    fn on_joints(&self, key: &str, bytes: &[u8]) {
        let msg = match JointStateMessage::from_bytes(bytes) {
            Ok(m) if m.names == self.names => m,
            Ok(m) => {
                let e = format!(
                    "joint names {:?} are not the arm's {:?}",
                    m.names, self.names
                );
                return self.ctx.drop_malformed(key, &e);
            }
            Err(e) => return self.ctx.drop_malformed(key, &e),
        };
        let start = Instant::now();
        let out = match self.verdict(&msg) {
            Ok(out) => out,
            Err(e) => return self.ctx.drop_malformed(key, &e),
        };
        self.ctx.metrics.add("published", 1);
        if out.stop {
            self.ctx.metrics.add("stops", 1);
        }
        self.ctx.metrics.set("min_clearance", out.min_clearance);
        self.ctx
            .metrics
            .set("check_us", start.elapsed().as_secs_f64() * 1e6);
        match out.to_bytes() {
            Ok(bytes) => {
                if let Err(e) = self.publisher.put(bytes).wait() {
                    self.ctx.metrics.add("publish_errors", 1);
                    tracing::warn!("publish collision: {e}");
                }
            }
            Err(e) => tracing::error!("encode collision: {e}"),
        }
    }

    fn verdict(&self, joints: &JointStateMessage) -> Result<CollisionMessage> {
        let start = Instant::now();
        let pose = self.file.arm.forward(&joints.positions)?;
        let latest = self.latest.lock().unwrap_or_else(|p| p.into_inner());
        let (verdict, report, stamp, seq) = match latest.as_ref() {
            None => (GuardVerdict::NoSurrogate, None, 0, 0),
            Some(l) if unix_ns().saturating_sub(l.stamp_ns) > self.max_age_ns => {
                (GuardVerdict::Stale, None, l.stamp_ns, l.sequence)
            }
            Some(l) => {
                let report = check_arm(&l.envelope, &pose, &self.file.guard)?;
                let v = if report.stop {
                    GuardVerdict::Stop
                } else {
                    GuardVerdict::Clear
                };
                (v, Some(report), l.stamp_ns, l.sequence)
            }
        };
        drop(latest);
        Ok(self.message(joints, verdict, report.as_ref(), (stamp, seq), start))
    }

    fn message(
        &self,
        joints: &JointStateMessage,
        verdict: GuardVerdict,
        report: Option<&GuardReport>,
        (surrogate_stamp_ns, surrogate_sequence): (u64, u64),
        start: Instant,
    ) -> CollisionMessage {
        let links = self.file.arm.links();
        let (min_clearance, closest_link, link_clearances) = match report {
            Some(r) => (
                r.min_clearance,
                r.closest_link
                    .and_then(|i| links.get(i))
                    .map(|l| l.name.clone())
                    .unwrap_or_default(),
                links
                    .iter()
                    .zip(&r.links)
                    .map(|(l, &c)| LinkClearance {
                        link: l.name.clone(),
                        clearance: c,
                    })
                    .collect(),
            ),
            // Without a trustworthy surrogate nothing is known to be clear.
            None => (0.0, String::new(), Vec::new()),
        };
        CollisionMessage {
            version: SCHEMA_VERSION,
            joints_stamp_ns: joints.stamp_ns,
            joints_sequence: joints.sequence,
            arm: self.arm_name.clone(),
            surrogate_stamp_ns,
            surrogate_sequence,
            verdict,
            stop: verdict != GuardVerdict::Clear,
            stop_distance: self.file.guard.stop_distance,
            min_clearance,
            closest_link,
            links: link_clearances,
            check_ns: start.elapsed().as_nanos() as u64,
        }
    }
}
