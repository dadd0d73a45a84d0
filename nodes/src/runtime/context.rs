//! What a node's body is handed: the session, its topics and metrics, the stop
//! flag, its typed inputs and outputs (QoS by topic kind, shared memory by
//! the node's `--shm`), and raw publishers for what is not typed (a replay).

use super::arrival::Arrival;
use super::input::Input;
use super::listener::{Listener, OnMessage};
use super::metrics::NodeMetrics;
use super::output::Output;
use crate::transport::{topic_publisher, PayloadWriter, ZenohArgs};
use anyhow::Result;
use clap::Args;
use shroud_msg::{Message, TopicKind, Topics};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use zenoh::Wait;

/// How long [`NodeContext::wait_for_subscriber`] waits after the first
/// subscriber is known, for the declarations that arrived with it.
pub const DECLARATIONS_GRACE: std::time::Duration = std::time::Duration::from_millis(250);

/// Options every node takes.
#[derive(Debug, Clone, Args)]
pub struct NodeCommon {
    /// This node's instance name, unique in its namespace (default: its kind).
    #[arg(long)]
    pub name: Option<String>,
    /// Seconds between status messages.
    #[arg(long, default_value_t = 1.0)]
    pub status_period: f64,
    #[command(flatten)]
    pub zenoh: ZenohArgs,
}

/// Handed to a node's body.
pub struct NodeContext {
    pub session: zenoh::Session,
    pub topics: Topics,
    pub name: String,
    pub metrics: Arc<NodeMetrics>,
    pub(super) stop: Arc<AtomicBool>,
    /// `--shm`: large payloads through zenoh shared memory.
    pub(super) shm: bool,
}

impl NodeContext {
    /// Set once the node was asked to stop; bodies poll it between work items.
    pub fn stopping(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    /// The stop flag itself, for blocking readers that poll it.
    pub fn stop_flag(&self) -> &AtomicBool {
        &self.stop
    }

    pub fn key(&self, kind: TopicKind, name: &str) -> Result<String> {
        Ok(self.topics.key(kind, name)?)
    }

    /// A queued input of messages `M` from `shroud/<ns>/<M::KIND>/<name>`,
    /// keeping at most `queue` samples (the oldest dropped and counted).
    pub fn subscribe<M: Message>(self: &Arc<Self>, name: &str, queue: usize) -> Result<Input<M>> {
        let key = self.key(M::KIND, name)?;
        Input::new(
            &self.session,
            key,
            queue,
            self.metrics.clone(),
            self.stop.clone(),
        )
    }

    /// Messages `M` from `shroud/<ns>/<M::KIND>/<name>` handed to `handler`
    /// in zenoh's callback, as they arrive.
    pub fn listen<M: Message>(&self, name: &str, handler: impl OnMessage<M>) -> Result<Listener> {
        let key = self.key(M::KIND, name)?;
        Listener::new(&self.session, key, self.metrics.clone(), handler)
    }

    /// Every sample of the key expression `key` (wildcards allowed), raw, to
    /// `handler` in zenoh's callback: for a recorder or a viewer, which keep
    /// or forward payloads of many kinds.
    pub fn listen_raw(
        &self,
        key: &str,
        handler: impl Fn(Arrival) + Send + Sync + 'static,
    ) -> Result<Listener> {
        Listener::raw(&self.session, key.to_owned(), handler)
    }

    /// An output of messages `M` on `shroud/<ns>/<M::KIND>/<name>`.
    pub fn output<M: Message>(&self, name: &str) -> Result<Output<M>> {
        self.output_shared(name, 0)
    }

    /// [`Self::output`] for large messages: through a shared segment of
    /// `pool_bytes` (a few messages' worth) unless the node runs with
    /// `--shm off`.
    pub fn output_shared<M: Message>(&self, name: &str, pool_bytes: usize) -> Result<Output<M>> {
        let key = self.key(M::KIND, name)?;
        let writer = self.payload_writer(pool_bytes);
        Output::new(
            &self.session,
            key,
            writer,
            pool_bytes > 0,
            self.metrics.clone(),
        )
    }

    /// A publisher on `shroud/<ns>/<kind>/<name>` with the topic's documented
    /// quality of service ([`TopicKind::qos`]).
    pub fn publisher(
        &self,
        kind: TopicKind,
        name: &str,
    ) -> Result<zenoh::pubsub::Publisher<'static>> {
        topic_publisher(&self.session, self.key(kind, name)?, kind)
    }

    /// Waits until `publisher` has a subscriber, at most `patience` (or
    /// until the node stops), then [`DECLARATIONS_GRACE`]; whether one is
    /// there. A zenoh peer drops what
    /// it publishes before it has heard of any subscriber: a short run (a
    /// scanner's `--frames`, a replay) waits for its audience first.
    pub fn wait_for_subscriber(
        &self,
        publisher: &zenoh::pubsub::Publisher<'static>,
        patience: std::time::Duration,
    ) -> bool {
        let until = std::time::Instant::now() + patience;
        loop {
            let matched = publisher
                .matching_status()
                .wait()
                .map(|s| s.matching())
                .unwrap_or(true);
            if matched {
                // Peers learn of subscribers one declaration at a time: the
                // others that came with the first get a moment to land.
                std::thread::sleep(DECLARATIONS_GRACE);
                return true;
            }
            if std::time::Instant::now() >= until || self.stopping() {
                return false;
            }
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
    }

    /// A payload writer with a shared segment of `pool_bytes`, through shared
    /// memory unless the node runs with `--shm off`.
    pub fn payload_writer(&self, pool_bytes: usize) -> PayloadWriter {
        PayloadWriter::new(self.shm, pool_bytes)
    }

    /// A message that could not be used: logged with its key and counted.
    pub fn drop_malformed(&self, key: &str, error: &dyn std::fmt::Display) {
        self.metrics.drop_malformed(key, error);
    }
}
