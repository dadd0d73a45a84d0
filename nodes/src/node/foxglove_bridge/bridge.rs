//! The bridge's loop: takes the graph's latest samples from the inbox, paces
//! the heavy streams (clouds, surrogates, arms) to `--max-rate` per stream,
//! converts what a client subscribes to (`crate::to_foxglove`) and logs it
//! to the Foxglove server; verdicts go out every 100 ms (a silent guard shows
//! as `no-verdict`), status as it arrives.

use super::channels::Channels;
use super::listener::Shared;
use crate::node::viewer::{Arrival, Inbox};
use crate::node::NodeContext;
use crate::to_foxglove::{
    arm_scene, arm_scene_topic, arm_transforms, arm_transforms_topic, certificate_topic,
    certificate_view, cloud_topic, point_cloud, status_topic, status_view, surrogate_scene,
    surrogate_topic, verdict_topic, verdict_view, vouched_bands, vouched_speed, CertificateView,
    StatusView, VerdictView, VERDICT_PERIOD_NS,
};
use crate::transport::monotonic_ns;
use foxglove::messages::{FrameTransforms, PointCloud, SceneUpdate};
use foxglove::Context;
use shroud_graph::metrics::names as metric;
use shroud_graph::pace::Paced;
use shroud_guard::{ArmModel, VerdictWatch};
use shroud_msg::{
    CloudView, CollisionMessage, JointStateMessage, NodeStatusMessage, SurrogateMessage, TopicKey,
    TopicKind,
};
use shroud_surrogate::SurrogateWire;
use shroud_viewers::dashboard::BlendPalette;
use shroud_viewers::scene::pose_arm;
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Duration;

/// How often the bridge's own gauges and counters are refreshed.
const METRICS_PERIOD_NS: u64 = 500_000_000;

/// The bridge's settings.
pub struct BridgeConfig {
    pub point_budget: usize,
    /// Subdivisions of each trim triangle of a surrogate's mesh.
    pub per_cell: usize,
    /// Least nanoseconds between two messages of one cloud, surrogate or arm.
    pub pace_ns: u64,
    pub arms: Vec<ArmModel>,
    pub verdict_timeout_ns: u64,
    pub blend_stream: Option<String>,
}

/// The channels, one set per schema.
struct Outputs {
    clouds: Channels<PointCloud>,
    scenes: Channels<SceneUpdate>,
    transforms: Channels<FrameTransforms>,
    certificates: Channels<CertificateView>,
    verdicts: Channels<VerdictView>,
    statuses: Channels<StatusView>,
}

pub struct Bridge {
    ctx: Arc<NodeContext>,
    inbox: Arc<Inbox>,
    shared: Arc<Shared>,
    config: BridgeConfig,
    out: Outputs,
    paced: Paced<String, (TopicKey, Arrival)>,
    /// The latest sample of every drawable stream, by its Foxglove topics,
    /// to send again to a client that subscribes.
    latest: BTreeMap<String, (TopicKey, Arrival)>,
    watches: BTreeMap<String, VerdictWatch>,
    logged: u64,
}

impl Bridge {
    pub fn new(
        ctx: Arc<NodeContext>,
        context: &Arc<Context>,
        inbox: Arc<Inbox>,
        shared: Arc<Shared>,
        config: BridgeConfig,
    ) -> Self {
        let watches = config
            .arms
            .iter()
            .map(|a| {
                let watch = VerdictWatch::new(config.verdict_timeout_ns);
                (a.name().to_string(), watch)
            })
            .collect();
        Self {
            ctx,
            inbox,
            shared,
            out: Outputs {
                clouds: Channels::new(context),
                scenes: Channels::new(context),
                transforms: Channels::new(context),
                certificates: Channels::new(context),
                verdicts: Channels::new(context),
                statuses: Channels::new(context),
            },
            paced: Paced::new(config.pace_ns),
            config,
            latest: BTreeMap::new(),
            watches,
            logged: 0,
        }
    }

    /// Runs until the node stops; `clients` counts the connected clients.
    pub fn run(mut self, clients: &dyn Fn() -> usize) {
        let (mut next_verdicts, mut next_metrics) = (0, 0);
        while !self.ctx.stopping() {
            for topic in self.shared.take_resends() {
                if let Some((key, arrival)) = self.latest.get(&topic).cloned() {
                    self.draw(&key, &arrival);
                }
            }
            if let Some((key, arrival)) = self.inbox.take(Duration::from_millis(20)) {
                self.on_arrival(key, arrival);
            }
            let now = monotonic_ns();
            for (_, (key, arrival)) in self.paced.release(now) {
                self.draw(&key, &arrival);
            }
            if now >= next_verdicts {
                self.log_verdicts(now);
                next_verdicts = now + VERDICT_PERIOD_NS;
            }
            if now >= next_metrics {
                self.refresh_metrics(clients());
                next_metrics = now + METRICS_PERIOD_NS;
            }
        }
    }

    fn on_arrival(&mut self, key: TopicKey, arrival: Arrival) {
        match key.kind {
            TopicKind::Status => self.on_status(&key, &arrival),
            TopicKind::Collision => self.on_collision(&key, &arrival),
            TopicKind::Cloud | TopicKind::Surrogate | TopicKind::Joints => {
                let stream = format!("{}/{}", key.kind, key.name);
                let at = arrival.received_ns;
                if let Some((key, arrival)) = self.paced.offer(stream, (key, arrival), at) {
                    self.draw(&key, &arrival);
                }
            }
            // Smooth fits are the web dashboard's; blend commands and
            // liveliness are not drawn.
            TopicKind::Smooth | TopicKind::Alive | TopicKind::Blend => {}
        }
    }

    /// Converts and logs a drawable sample to the channels a client wants;
    /// a sample that does not decode is counted as malformed and forgotten.
    fn draw(&mut self, key: &TopicKey, arrival: &Arrival) {
        let bytes = arrival.payload.to_bytes();
        let outcome = match key.kind {
            TopicKind::Cloud => self.draw_cloud(&key.name, &bytes),
            TopicKind::Surrogate => self.draw_surrogate(&key.name, &bytes),
            TopicKind::Joints => self.draw_arm(&bytes),
            _ => Ok(Vec::new()),
        };
        match outcome {
            Ok(topics) => {
                for topic in topics {
                    self.latest.insert(topic, (key.clone(), arrival.clone()));
                }
            }
            Err(e) => self
                .ctx
                .drop_malformed(&format!("{}/{}", key.kind, key.name), &e),
        }
    }

    /// Each `draw_*` returns the Foxglove topics the sample feeds.
    fn draw_cloud(&mut self, stream: &str, bytes: &[u8]) -> Result<Vec<String>, String> {
        let topic = cloud_topic(stream);
        let budget = self.config.point_budget;
        let logged = self.out.clouds.log_with(&topic, || {
            let view = CloudView::from_bytes(bytes).map_err(|e| e.to_string())?;
            point_cloud(&view, budget).map_err(|e| e.to_string())
        })?;
        self.count(logged);
        Ok(vec![topic])
    }

    fn draw_surrogate(&mut self, stream: &str, bytes: &[u8]) -> Result<Vec<String>, String> {
        let (scene, certificate) = (surrogate_topic(stream), certificate_topic(stream));
        if self.out.scenes.wanted(&scene) || self.out.certificates.wanted(&certificate) {
            let (msg, surrogate) =
                SurrogateMessage::from_bytes(bytes).map_err(|e| e.to_string())?;
            let per_cell = self.config.per_cell;
            let logged = self.out.scenes.log_with(&scene, || {
                Ok::<_, String>(surrogate_scene(stream, &msg, &surrogate, per_cell))
            })?;
            self.count(logged);
            let logged = self.out.certificates.log_with(&certificate, || {
                Ok::<_, String>(certificate_view(stream, &msg))
            })?;
            self.count(logged);
        }
        Ok(vec![scene, certificate])
    }

    fn draw_arm(&mut self, bytes: &[u8]) -> Result<Vec<String>, String> {
        let msg = JointStateMessage::from_bytes(bytes).map_err(|e| e.to_string())?;
        // Joint states of arms without a model are not drawn (nothing to pose).
        let Some(model) = self.config.arms.iter().find(|a| a.name() == msg.arm) else {
            return Ok(Vec::new());
        };
        let (scene, frames) = (arm_scene_topic(&msg.arm), arm_transforms_topic(&msg.arm));
        if self.out.scenes.wanted(&scene) || self.out.transforms.wanted(&frames) {
            let posed = pose_arm(model, &msg).map_err(|e| e.to_string())?;
            let now = monotonic_ns();
            let watch = self.watches.get(&msg.arm);
            let (bands, speed) = (vouched_bands(watch, now), vouched_speed(watch, now));
            let logged = self.out.scenes.log_with(&scene, || {
                Ok::<_, String>(arm_scene(&posed, &bands, &speed, msg.stamp_ns))
            })?;
            self.count(logged);
            let logged = self.out.transforms.log_with(&frames, || {
                Ok::<_, String>(arm_transforms(&posed, msg.stamp_ns))
            })?;
            self.count(logged);
        }
        Ok(vec![scene, frames])
    }

    fn on_collision(&mut self, key: &TopicKey, arrival: &Arrival) {
        match CollisionMessage::from_bytes(&arrival.payload.to_bytes()) {
            Ok(msg) => {
                let timeout = self.config.verdict_timeout_ns;
                self.watches
                    .entry(msg.arm.clone())
                    .or_insert_with(|| VerdictWatch::new(timeout))
                    .on_verdict(msg, arrival.received_ns);
            }
            Err(e) => self
                .ctx
                .drop_malformed(&format!("collision/{}", key.name), &e),
        }
    }

    fn on_status(&mut self, key: &TopicKey, arrival: &Arrival) {
        let msg = match NodeStatusMessage::from_bytes(&arrival.payload.to_bytes()) {
            Ok(msg) => msg,
            Err(e) => {
                self.ctx.drop_malformed(&format!("status/{}", key.name), &e);
                return;
            }
        };
        if let Some(palette) = BlendPalette::from_status(&msg) {
            let mut slot = self
                .shared
                .palette
                .lock()
                .unwrap_or_else(|p| p.into_inner());
            let stream = palette.stream.clone();
            if palette.adopt(&mut slot, self.config.blend_stream.as_deref()) {
                // Says which blend node `/shroud/blend` drives now.
                self.ctx.metrics.set_label("blend.drives".into(), stream);
            }
        }
        let topic = status_topic(&key.name);
        let logged = self
            .out
            .statuses
            .log_with(&topic, || Ok::<_, String>(status_view(&msg)));
        self.count(logged.unwrap_or(false));
    }

    fn log_verdicts(&mut self, now: u64) {
        for (arm, watch) in &self.watches {
            let topic = verdict_topic(arm);
            let logged = self.out.verdicts.log_with(&topic, || {
                Ok::<_, String>(verdict_view(arm, &watch.shown(now)))
            });
            if logged.unwrap_or(false) {
                self.logged += 1;
            }
        }
    }

    fn count(&mut self, logged: bool) {
        self.logged += u64::from(logged);
    }

    fn refresh_metrics(&self, clients: usize) {
        let m = &self.ctx.metrics;
        m.set(metric::CLIENTS, clients as f64);
        m.set_counter(metric::MESSAGES_LOGGED, self.logged);
        m.set_counter(metric::SAMPLES_SUPERSEDED, self.inbox.superseded());
        m.set_counter(metric::PACED_SUPERSEDED, self.paced.superseded());
    }
}
