//! What every node process shares: the zenoh session, the liveliness token that
//! announces it, the status publisher, and a clean stop on SIGINT/SIGTERM.

use super::metrics::NodeMetrics;
use crate::transport::{shutdown_signal, unix_ns, Mailbox, ZenohArgs};
use anyhow::{Context, Result};
use clap::Args;
use shroud_core::message::{check_name, NodeStatusMessage, TopicKind, Topics};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use zenoh::bytes::ZBytes;
use zenoh::Wait;

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
    stop: Arc<AtomicBool>,
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

    /// Subscribes to `key`, handing every sample's key and payload to
    /// `mailbox` (the worker thread decodes them, not zenoh's).
    pub fn subscribe_into(
        &self,
        key: &str,
        mailbox: &Arc<Mailbox<(String, ZBytes)>>,
    ) -> Result<zenoh::pubsub::Subscriber<()>> {
        let inbox = mailbox.clone();
        self.session
            .declare_subscriber(key.to_owned())
            .callback(move |sample| {
                inbox.push((sample.key_expr().to_string(), sample.payload().clone()));
            })
            .wait()
            .map_err(|e| anyhow::anyhow!("subscribe {key}: {e}"))
    }

    /// A publisher for messages that each supersede the last: a slow reader
    /// loses old ones rather than stalling the node (congestion control drop).
    pub fn latest_publisher(&self, key: &str) -> Result<zenoh::pubsub::Publisher<'static>> {
        self.session
            .declare_publisher(key.to_owned())
            .congestion_control(zenoh::qos::CongestionControl::Drop)
            .wait()
            .map_err(|e| anyhow::anyhow!("publisher {key}: {e}"))
    }

    /// A message that could not be used: logged with its key and counted.
    pub fn drop_malformed(&self, key: &str, error: &dyn std::fmt::Display) {
        self.metrics.add("dropped_malformed", 1);
        tracing::warn!(key, "dropped a malformed message: {error}");
    }
}

/// Runs a node: opens the session, announces it, publishes status, runs `body`
/// on a blocking thread until it returns or a signal arrives, then shuts down.
pub fn run_node<F>(common: &NodeCommon, kind: &'static str, body: F) -> Result<()>
where
    F: FnOnce(Arc<NodeContext>) -> Result<()> + Send + 'static,
{
    let name = common.name.clone().unwrap_or_else(|| kind.to_string());
    check_name("--name", &name)?;
    anyhow::ensure!(
        common.status_period.is_finite() && common.status_period >= 0.05,
        "--status-period must be at least 0.05 s"
    );
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("cannot start the async runtime")?;
    runtime.block_on(async move {
        let session = common.zenoh.open().await?;
        let topics = common.zenoh.topics()?;
        let alive = topics.key(TopicKind::Alive, &name)?;
        let token = session
            .liveliness()
            .declare_token(&alive)
            .await
            .map_err(|e| anyhow::anyhow!("liveliness token {alive}: {e}"))?;
        let ctx = Arc::new(NodeContext {
            session,
            topics,
            name: name.clone(),
            metrics: Arc::new(NodeMetrics::default()),
            stop: Arc::new(AtomicBool::new(false)),
        });
        tracing::info!(node = %name, kind, "started");
        let status = tokio::spawn(publish_status(ctx.clone(), kind, common.status_period));
        let worker = {
            let ctx = ctx.clone();
            tokio::task::spawn_blocking(move || body(ctx))
        };
        tokio::pin!(worker);
        let outcome = tokio::select! {
            signal = shutdown_signal() => {
                tracing::info!(node = %name, "{signal}: stopping");
                ctx.stop.store(true, Ordering::Relaxed);
                match tokio::time::timeout(Duration::from_secs(5), &mut worker).await {
                    Ok(joined) => joined.context("node body panicked")?,
                    Err(_) => Err(anyhow::anyhow!("node body did not stop within 5 s")),
                }
            }
            joined = &mut worker => joined.context("node body panicked")?,
        };
        ctx.stop.store(true, Ordering::Relaxed);
        status.abort();
        drop(token);
        if let Err(e) = ctx.session.close().await {
            tracing::warn!("closing the zenoh session: {e}");
        }
        outcome
    })
}

async fn publish_status(ctx: Arc<NodeContext>, kind: &'static str, period: f64) {
    let Ok(key) = ctx.key(TopicKind::Status, &ctx.name) else {
        return;
    };
    let start = Instant::now();
    let mut msg = NodeStatusMessage::new(&ctx.name, kind, std::process::id());
    let mut tick = tokio::time::interval(Duration::from_secs_f64(period));
    loop {
        tick.tick().await;
        msg.stamp_ns = unix_ns();
        msg.uptime_s = start.elapsed().as_secs_f64();
        ctx.metrics.fill(&mut msg);
        match msg.to_bytes() {
            Ok(bytes) => {
                if let Err(e) = ctx.session.put(&key, bytes).wait() {
                    tracing::warn!("status publish failed: {e}");
                }
            }
            Err(e) => tracing::warn!("status encode failed: {e}"),
        }
    }
}
