//! The frame builder: one thread that takes what the inbox holds, keeps the
//! graph's state (node health, verdicts, arm poses, the blend palette) and
//! turns it into frames for the browsers. Frames are built only while a
//! browser is connected; with none, the dashboard costs the graph nothing but
//! its subscriptions.

use super::hub::Hub;
use crate::node::viewer::{Arrival, Inbox};
use crate::node::NodeContext;
use crate::transport::monotonic_ns;
use shroud_graph::metrics::names as metric;
use shroud_graph::metrics::NodeHealth;
use shroud_graph::pace::Paced;
use shroud_guard::{ArmModel, VerdictWatch};
use shroud_msg::{
    CloudView, CollisionMessage, JointStateMessage, NodeStatusMessage, SmoothPatchesMessage,
    SurrogateMessage, TopicKey, TopicKind,
};
use shroud_surrogate::SurrogateWire;
use shroud_viewers::dashboard::{
    arm_frame, cloud_frame, hello_frame, nodes_frame, smooth_frame, surrogate_frame, verdict_frame,
    BlendPalette, CloudFrameInput, DashboardCounts, Hello,
};
use shroud_viewers::scene::pose_arm;
use std::collections::BTreeMap;
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// How often verdict frames are refreshed (a silent guard shows within this).
const VERDICT_PERIOD_NS: u64 = 100_000_000;
/// How often the nodes table is sent.
const NODES_PERIOD_NS: u64 = 500_000_000;
/// Subdivisions of each trim triangle of a surrogate's mesh.
const SURFACE_PER_CELL: usize = 2;
/// Quads along each side of a smooth patch.
const SMOOTH_PER_PATCH: usize = 6;

/// The builder's settings.
pub struct BuilderConfig {
    pub namespace: String,
    pub node: String,
    pub point_budget: usize,
    pub arms: Vec<ArmModel>,
    pub verdict_timeout_ns: u64,
    /// `--blend-stream`: the blend node to drive; `None`: the first that
    /// announces itself.
    pub blend_stream: Option<String>,
    /// Nanoseconds between two frames of one cloud, surrogate or smooth
    /// stream (`--max-rate`).
    pub pace_ns: u64,
}

/// State shared with the browser handlers (they read the palette to route
/// blend commands and the hello frame to greet).
#[derive(Default)]
pub struct Shared {
    pub palette: Mutex<Option<BlendPalette>>,
    pub hello: Mutex<Vec<u8>>,
}

pub struct FrameBuilder {
    ctx: Arc<NodeContext>,
    hub: Arc<Hub>,
    inbox: Arc<Inbox>,
    shared: Arc<Shared>,
    config: BuilderConfig,
    health: NodeHealth,
    watches: BTreeMap<String, VerdictWatch>,
    restarts: BTreeMap<String, u64>,
    /// The latest payload of every drawable key, to greet a new browser.
    latest: BTreeMap<String, (TopicKey, Arrival)>,
    /// The heavy streams' samples waiting for their stream's next frame.
    paced: Paced<String, (TopicKey, Arrival)>,
    started_ns: u64,
}

impl FrameBuilder {
    pub fn new(
        ctx: Arc<NodeContext>,
        hub: Arc<Hub>,
        inbox: Arc<Inbox>,
        shared: Arc<Shared>,
        config: BuilderConfig,
    ) -> Self {
        let pace_ns = config.pace_ns;
        let watches = config
            .arms
            .iter()
            .map(|a| {
                (
                    a.name().to_string(),
                    VerdictWatch::new(config.verdict_timeout_ns),
                )
            })
            .collect();
        let builder = Self {
            ctx,
            hub,
            inbox,
            shared,
            config,
            health: NodeHealth::default(),
            watches,
            restarts: BTreeMap::new(),
            latest: BTreeMap::new(),
            paced: Paced::new(pace_ns),
            started_ns: monotonic_ns(),
        };
        builder.refresh_hello();
        builder
    }

    /// A node's liveliness token appeared or went.
    pub fn on_token(&mut self, node: &str, present: bool) {
        self.health.on_token(node, present);
    }

    /// Runs until the node stops; `tokens` carries liveliness changes.
    pub fn run(mut self, tokens: &std::sync::mpsc::Receiver<(String, bool)>) {
        let (mut next_verdicts, mut next_nodes) = (0, 0);
        while !self.ctx.stopping() {
            while let Ok((node, present)) = tokens.try_recv() {
                self.on_token(&node, present);
            }
            if self.hub.take_joined() {
                self.greet();
            }
            if let Some((key, arrival)) = self.inbox.take(Duration::from_millis(20)) {
                self.on_arrival(key, arrival);
            }
            let now = monotonic_ns();
            for (_, (key, arrival)) in self.paced.release(now) {
                self.keep_drawn(key, arrival);
            }
            if now >= next_verdicts {
                self.send_verdicts(now);
                next_verdicts = now + VERDICT_PERIOD_NS;
            }
            if now >= next_nodes {
                self.send_nodes(now);
                next_nodes = now + NODES_PERIOD_NS;
            }
        }
    }

    fn browsers(&self) -> bool {
        self.hub.count() > 0
    }

    /// A new browser: the hello, then the latest of everything. A latest
    /// sample that does not decode is counted now and forgotten, so that the
    /// next browser does not count it again.
    fn greet(&mut self) {
        self.hub.broadcast("hello", self.shared_hello());
        let latest: Vec<(String, TopicKey, Arrival)> = self
            .latest
            .iter()
            .map(|(name, (k, a))| (name.clone(), k.clone(), a.clone()))
            .collect();
        for (name, key, arrival) in latest {
            if !self.draw(&key, &arrival) {
                self.latest.remove(&name);
            }
        }
        self.send_verdicts(monotonic_ns());
        self.send_nodes(monotonic_ns());
    }

    fn shared_hello(&self) -> Vec<u8> {
        self.shared
            .hello
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .clone()
    }

    fn on_arrival(&mut self, key: TopicKey, arrival: Arrival) {
        match key.kind {
            TopicKind::Status => self.on_status(&key, &arrival),
            TopicKind::Collision => self.on_collision(&key, &arrival),
            TopicKind::Joints => self.keep_drawn(key, arrival),
            TopicKind::Cloud | TopicKind::Surrogate | TopicKind::Smooth => {
                let stream = format!("{}/{}", key.kind, key.name);
                let at = arrival.received_ns;
                if let Some((key, arrival)) = self.paced.offer(stream, (key, arrival), at) {
                    self.keep_drawn(key, arrival);
                }
            }
            TopicKind::Alive | TopicKind::Blend => {}
        }
    }

    /// Draws a sample for the browsers and keeps it for the next browser,
    /// unless it was decoded and found malformed (counted once, here).
    fn keep_drawn(&mut self, key: TopicKey, arrival: Arrival) {
        if !self.browsers() || self.draw(&key, &arrival) {
            let name = format!("{}/{}", key.kind, key.name);
            self.latest.insert(name, (key, arrival));
        }
    }

    /// Builds and sends the frame of a drawable sample; false (and counted
    /// as malformed) when it does not decode.
    fn draw(&mut self, key: &TopicKey, arrival: &Arrival) -> bool {
        let bytes = arrival.payload.to_bytes();
        let outcome = match key.kind {
            TopicKind::Cloud => self.draw_cloud(key, &bytes),
            TopicKind::Surrogate => SurrogateMessage::from_bytes(&bytes)
                .map(|(msg, s)| surrogate_frame(&key.name, &msg, &s, SURFACE_PER_CELL))
                .map_err(|e| e.to_string())
                .map(|f| self.hub.broadcast(&format!("surrogate/{}", key.name), f)),
            TopicKind::Smooth => SmoothPatchesMessage::from_bytes(&bytes)
                .map_err(|e| e.to_string())
                .and_then(|m| {
                    smooth_frame(&key.name, &m, SMOOTH_PER_PATCH).map_err(|e| e.to_string())
                })
                .map(|f| self.hub.broadcast(&format!("smooth/{}", key.name), f)),
            TopicKind::Joints => self.draw_arm(&bytes),
            _ => Ok(()),
        };
        match outcome {
            Ok(()) => true,
            Err(e) => {
                self.ctx
                    .drop_malformed(&format!("{}/{}", key.kind, key.name), &e);
                false
            }
        }
    }

    fn draw_cloud(&self, key: &TopicKey, bytes: &[u8]) -> Result<(), String> {
        let view = CloudView::from_bytes(bytes).map_err(|e| e.to_string())?;
        let blend_sources = self
            .shared
            .palette
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .as_ref()
            .is_some_and(|p| p.output == key.name);
        for budget in self.hub.budgets() {
            let frame = cloud_frame(CloudFrameInput {
                stream: &key.name,
                view: &view,
                budget,
                blend_sources,
            })
            .map_err(|e| e.to_string())?;
            self.hub
                .broadcast_to_budget(&format!("cloud/{}", key.name), budget, frame);
        }
        Ok(())
    }

    fn draw_arm(&self, bytes: &[u8]) -> Result<(), String> {
        let msg = JointStateMessage::from_bytes(bytes).map_err(|e| e.to_string())?;
        // Joint states of arms without a model are not drawn (nothing to pose).
        let Some(model) = self.config.arms.iter().find(|a| a.name() == msg.arm) else {
            return Ok(());
        };
        let posed = pose_arm(model, &msg).map_err(|e| e.to_string())?;
        self.hub
            .broadcast(&format!("arm/{}", msg.arm), arm_frame(&posed));
        Ok(())
    }

    fn on_collision(&mut self, key: &TopicKey, arrival: &Arrival) {
        match CollisionMessage::from_bytes(&arrival.payload.to_bytes()) {
            Ok(msg) => {
                let watch = self
                    .watches
                    .entry(msg.arm.clone())
                    .or_insert_with(|| VerdictWatch::new(self.config.verdict_timeout_ns));
                watch.on_verdict(msg, arrival.received_ns);
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
        if msg.kind == "launch" {
            self.restarts = msg
                .counters
                .iter()
                .filter_map(|(k, v)| Some((k.strip_prefix("restarts.")?.to_string(), *v)))
                .collect();
        }
        if let Some(palette) = BlendPalette::from_status(&msg) {
            self.on_palette(palette);
        }
        self.health.on_status(msg, arrival.received_ns);
    }

    /// A blend node announced its palette: adopt it if it is the one to drive
    /// and it changed, and greet every browser again with it.
    fn on_palette(&mut self, palette: BlendPalette) {
        let changed = palette.adopt(
            &mut self
                .shared
                .palette
                .lock()
                .unwrap_or_else(|p| p.into_inner()),
            self.config.blend_stream.as_deref(),
        );
        if changed {
            self.refresh_hello();
            self.hub.broadcast("hello", self.shared_hello());
        }
    }

    fn refresh_hello(&self) {
        let palette = self
            .shared
            .palette
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .clone();
        let arms: Vec<&str> = self.config.arms.iter().map(|a| a.name()).collect();
        let frame = hello_frame(&Hello {
            namespace: &self.config.namespace,
            node: &self.config.node,
            point_budget: self.config.point_budget,
            blend: palette.as_ref(),
            arms,
            stop_banner_after_ms: self.config.verdict_timeout_ns as f64 / 1e6,
        });
        *self.shared.hello.lock().unwrap_or_else(|p| p.into_inner()) = frame;
    }

    fn send_verdicts(&self, now: u64) {
        if !self.browsers() {
            return;
        }
        for (arm, watch) in &self.watches {
            self.hub.broadcast(
                &format!("verdict/{arm}"),
                verdict_frame(arm, &watch.shown(now)),
            );
        }
    }

    fn send_nodes(&self, now: u64) {
        let m = &self.ctx.metrics;
        m.set(metric::BROWSERS, self.hub.count() as f64);
        m.set_counter(
            metric::FRAMES_SENT,
            self.hub.frames_sent.load(Ordering::Relaxed),
        );
        m.set_counter(
            metric::FRAMES_SUPERSEDED,
            self.hub.frames_superseded.load(Ordering::Relaxed),
        );
        m.set_counter(metric::SAMPLES_SUPERSEDED, self.inbox.superseded());
        m.set_counter(metric::PACED_SUPERSEDED, self.paced.superseded());
        let rates = self.inbox.rates(now);
        if !self.browsers() {
            return;
        }
        let counts = DashboardCounts {
            clients: self.hub.count(),
            frames_sent: self.hub.frames_sent.load(Ordering::Relaxed),
            frames_superseded: self.hub.frames_superseded.load(Ordering::Relaxed),
            dropped_malformed: m.counter(metric::DROPPED_MALFORMED),
        };
        let uptime = now.saturating_sub(self.started_ns) as f64 / 1e9;
        let frame = nodes_frame(
            uptime,
            &self.health.rows(now),
            &self.restarts,
            &rates,
            counts,
        );
        self.hub.broadcast("nodes", frame);
    }
}
