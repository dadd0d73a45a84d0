//! What every node process shares: the zenoh session, the liveliness token that
//! announces it, the status publisher, and a stop on SIGINT/SIGTERM or when its
//! launcher is gone that finishes within a hard deadline.

use super::metrics::NodeMetrics;
use crate::transport::{
    keep_outputs_writable, prepare_last_words, shutdown_signal, silence_broken_outputs, unix_ns,
    watch_parent, Mailbox, ZenohArgs,
};
use anyhow::{Context, Result};
use clap::Args;
use shroud_core::message::{check_name, NodeStatusMessage, TopicKind, Topics};
use std::panic::AssertUnwindSafe;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, Once};
use std::time::{Duration, Instant};
use tokio::sync::Notify;
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

/// How long the body has to return once asked to stop.
const BODY_GRACE: Duration = Duration::from_secs(5);
/// How long closing the zenoh session may take.
const CLOSE_GRACE: Duration = Duration::from_secs(2);
/// How long the runtime waits for its tasks once the node is done.
const RUNTIME_GRACE: Duration = Duration::from_secs(1);
/// After a stop request the process exits by this deadline, whatever is stuck.
const HARD_DEADLINE: Duration = Duration::from_secs(10);

/// Runs a node: opens the session, announces it, publishes status, runs `body`
/// on a blocking thread until it returns, a signal arrives or the launcher that
/// started it is gone, then shuts down within [`HARD_DEADLINE`].
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
    // Before anything logs: a node whose launcher died must not panic on its
    // next log line.
    keep_outputs_writable();
    let parent_gone = launcher_gone();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("cannot start the async runtime")?;
    let stop = Arc::new(AtomicBool::new(false));
    let watchdog = Watchdog::new(&name);
    let served = std::panic::catch_unwind(AssertUnwindSafe(|| {
        runtime.block_on(serve(
            common,
            kind,
            &name,
            body,
            &stop,
            &parent_gone,
            &watchdog,
        ))
    }));
    // Whatever happened (even a panic), the body is told to stop, and dropping
    // the runtime does not wait for a body that keeps looping.
    stop.store(true, Ordering::Relaxed);
    watchdog.arm();
    watchdog.stage("the runtime's tasks");
    runtime.shutdown_timeout(RUNTIME_GRACE);
    served.unwrap_or_else(|_| Err(anyhow::anyhow!("node {name} panicked")))
}

/// Notified once the launcher that started this node is gone (never if no
/// launcher started it).
fn launcher_gone() -> Arc<Notify> {
    let gone = Arc::new(Notify::new());
    let notify = gone.clone();
    watch_parent(move || notify.notify_one());
    gone
}

/// The node's life inside the runtime: set up, run the body, shut down.
async fn serve<F>(
    common: &NodeCommon,
    kind: &'static str,
    name: &str,
    body: F,
    stop: &Arc<AtomicBool>,
    parent_gone: &Notify,
    watchdog: &Watchdog,
) -> Result<()>
where
    F: FnOnce(Arc<NodeContext>) -> Result<()> + Send + 'static,
{
    let session = common.zenoh.open().await?;
    let topics = common.zenoh.topics()?;
    let alive = topics.key(TopicKind::Alive, name)?;
    let token = session
        .liveliness()
        .declare_token(&alive)
        .await
        .map_err(|e| anyhow::anyhow!("liveliness token {alive}: {e}"))?;
    let ctx = Arc::new(NodeContext {
        session,
        topics,
        name: name.to_string(),
        metrics: Arc::new(NodeMetrics::default()),
        stop: stop.clone(),
    });
    tracing::info!(node = %name, kind, "started");
    let status = tokio::spawn(publish_status(ctx.clone(), kind, common.status_period));
    let worker = {
        let ctx = ctx.clone();
        tokio::task::spawn_blocking(move || body(ctx))
    };
    let outcome = run_body(&ctx, worker, parent_gone, watchdog).await;
    ctx.stop.store(true, Ordering::Relaxed);
    watchdog.arm();
    status.abort();
    drop(token);
    watchdog.stage("closing the zenoh session");
    match tokio::time::timeout(CLOSE_GRACE, ctx.session.close()).await {
        Ok(Ok(())) => {}
        Ok(Err(e)) => tracing::warn!("closing the zenoh session: {e}"),
        Err(_) => tracing::warn!("the zenoh session did not close within {CLOSE_GRACE:?}"),
    }
    outcome
}

/// Waits for the body to return, or for a stop request; then gives the body
/// [`BODY_GRACE`] to notice the stop flag.
async fn run_body(
    ctx: &NodeContext,
    worker: tokio::task::JoinHandle<Result<()>>,
    parent_gone: &Notify,
    watchdog: &Watchdog,
) -> Result<()> {
    tokio::pin!(worker);
    tokio::select! {
        reason = stop_request(parent_gone) => {
            // The flag before the log line: if anything about logging goes
            // wrong, the body still stops.
            ctx.stop.store(true, Ordering::Relaxed);
            watchdog.arm();
            silence_broken_outputs();
            tracing::info!(node = %ctx.name, "{reason}: stopping");
            match tokio::time::timeout(BODY_GRACE, &mut worker).await {
                Ok(joined) => joined.context("node body panicked")?,
                Err(_) => Err(anyhow::anyhow!("node body did not stop within {BODY_GRACE:?}")),
            }
        }
        joined = &mut worker => joined.context("node body panicked")?,
    }
}

/// A signal, or the launcher that started this node gone.
async fn stop_request(parent_gone: &Notify) -> &'static str {
    tokio::select! {
        signal = shutdown_signal() => signal,
        _ = parent_gone.notified() => "launcher gone",
    }
}

/// The hard deadline of a node's shutdown: once armed, exits the process after
/// [`HARD_DEADLINE`] with an error naming the stage that did not finish, so that
/// nothing (a looping body, a hung session close) keeps a node alive.
struct Watchdog {
    name: String,
    stage: Arc<Mutex<&'static str>>,
    armed: Once,
}

impl Watchdog {
    fn new(name: &str) -> Self {
        Watchdog {
            name: name.to_string(),
            stage: Arc::new(Mutex::new("the node body")),
            armed: Once::new(),
        }
    }

    /// Names what the shutdown waits for now.
    fn stage(&self, stage: &'static str) {
        *self.stage.lock().unwrap_or_else(|p| p.into_inner()) = stage;
    }

    fn arm(&self) {
        self.armed.call_once(|| {
            let (name, stage) = (self.name.clone(), self.stage.clone());
            let expire = move || {
                std::thread::sleep(HARD_DEADLINE);
                let stage = *stage.lock().unwrap_or_else(|p| p.into_inner());
                prepare_last_words();
                // Exiting matters more than the line: never let it panic here.
                let _ = std::panic::catch_unwind(|| {
                    tracing::error!(node = %name, "{stage} did not stop within {HARD_DEADLINE:?} of the stop request; exiting");
                });
                std::process::exit(2);
            };
            let _ = std::thread::Builder::new()
                .name("stop-deadline".into())
                .spawn(expire);
        });
    }
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
