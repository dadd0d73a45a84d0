//! A node's life: open the session, announce the node, run its body on a
//! blocking thread, and stop on SIGINT/SIGTERM or when its launcher is gone,
//! within a hard deadline.

use super::context::{NodeCommon, NodeContext};
use super::metrics::NodeMetrics;
use super::status::{publish_final_status, publish_status};
use super::watchdog::Watchdog;
use crate::transport::{
    keep_outputs_writable, release_shm_segments, shutdown_signal, silence_broken_outputs,
    watch_parent,
};
use anyhow::{Context, Result};
use shroud_msg::{check_name, TopicKind};
use std::future::Future;
use std::panic::AssertUnwindSafe;
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::Notify;

/// How long the body has to return once asked to stop.
const BODY_GRACE: Duration = Duration::from_secs(5);
/// How long closing the zenoh session may take.
const CLOSE_GRACE: Duration = Duration::from_secs(2);
/// How long the runtime waits for its tasks once the node is done.
const RUNTIME_GRACE: Duration = Duration::from_secs(1);

/// Runs a node: opens the session, announces it, publishes status, runs `body`
/// on a blocking thread until it returns, a signal arrives or the launcher that
/// started it is gone, then shuts down within the watchdog's hard deadline.
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
    // The session is closed: no segment of ours is in use any more, and zenoh
    // would leave some behind (see `release_shm_segments`).
    if common.zenoh.shm.is_on() {
        watchdog.stage("removing shared-memory segments");
        release_shm_segments();
    }
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
    let topics = common.zenoh.topics()?;
    let alive = topics.key(TopicKind::Alive, name)?;
    // One stop request for the node's whole life: its signal handlers are
    // installed here, before anything can take a while, and a signal that
    // arrives between the two waits below is not lost.
    let stop_requested = stop_request(parent_gone);
    tokio::pin!(stop_requested);
    // Honoured while the session opens too (a router that never answers must
    // not keep an orphan alive).
    let opened = tokio::select! {
        opened = open_and_announce(common, &alive) => opened?,
        reason = &mut stop_requested => {
            begin_stop(stop, watchdog);
            tracing::info!(node = %name, "{reason} while starting: stopping");
            return Ok(());
        }
    };
    let (session, token) = opened;
    let ctx = Arc::new(NodeContext {
        session,
        topics,
        name: name.to_string(),
        metrics: Arc::new(NodeMetrics::default()),
        stop: stop.clone(),
        shm: common.zenoh.shm.is_on(),
    });
    tracing::info!(node = %name, kind, "started");
    let started = std::time::Instant::now();
    let status = tokio::spawn(publish_status(
        ctx.clone(),
        kind,
        common.status_period,
        started,
    ));
    let worker = {
        let ctx = ctx.clone();
        tokio::task::spawn_blocking(move || body(ctx))
    };
    let outcome = run_body(&ctx, worker, stop_requested.as_mut(), watchdog).await;
    ctx.stop.store(true, Ordering::Relaxed);
    watchdog.arm();
    status.abort();
    // A periodic publication under way lands before the final one.
    let _ = status.await;
    publish_final_status(&ctx, kind, started);
    drop(token);
    watchdog.stage("closing the zenoh session");
    match tokio::time::timeout(CLOSE_GRACE, ctx.session.close()).await {
        Ok(Ok(())) => {}
        Ok(Err(e)) => tracing::warn!("closing the zenoh session: {e}"),
        Err(_) => tracing::warn!("the zenoh session did not close within {CLOSE_GRACE:?}"),
    }
    outcome
}

/// The session, and the liveliness token that announces the node on it.
async fn open_and_announce(
    common: &NodeCommon,
    alive: &str,
) -> Result<(zenoh::Session, zenoh::liveliness::LivelinessToken)> {
    let session = common.zenoh.open().await?;
    let token = session
        .liveliness()
        .declare_token(alive)
        .await
        .map_err(|e| anyhow::anyhow!("liveliness token {alive}: {e}"))?;
    Ok((session, token))
}

/// Waits for the body to return, or for a stop request; then gives the body
/// [`BODY_GRACE`] to notice the stop flag.
async fn run_body(
    ctx: &NodeContext,
    worker: tokio::task::JoinHandle<Result<()>>,
    stop_requested: Pin<&mut impl Future<Output = &'static str>>,
    watchdog: &Watchdog,
) -> Result<()> {
    tokio::pin!(worker);
    tokio::select! {
        reason = stop_requested => {
            // The flag before the log line: if anything about logging goes
            // wrong, the body still stops.
            begin_stop(&ctx.stop, watchdog);
            tracing::info!(node = %ctx.name, "{reason}: stopping");
            match tokio::time::timeout(BODY_GRACE, &mut worker).await {
                Ok(joined) => joined.context("node body panicked")?,
                Err(_) => Err(anyhow::anyhow!("node body did not stop within {BODY_GRACE:?}")),
            }
        }
        joined = &mut worker => joined.context("node body panicked")?,
    }
}

/// What a stop request does first, before anything is logged: the body is
/// told, the hard deadline starts, and broken outputs stop being written to
/// (so that the log line that follows cannot fail).
fn begin_stop(stop: &AtomicBool, watchdog: &Watchdog) {
    stop.store(true, Ordering::Relaxed);
    watchdog.arm();
    silence_broken_outputs();
}

/// A signal, or the launcher that started this node gone. The signal
/// handlers are installed by this call, before the future is first polled.
fn stop_request(parent_gone: &Notify) -> impl Future<Output = &'static str> + '_ {
    let signal = shutdown_signal();
    async move {
        tokio::select! {
            signal = signal => signal,
            _ = parent_gone.notified() => "launcher gone",
        }
    }
}
