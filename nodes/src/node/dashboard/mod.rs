//! `shroud node dashboard`: the live monitoring page. It serves a page built
//! into the binary (no file on disk, nothing from the internet) and one
//! WebSocket per browser (docs/dashboard-protocol.md), and draws the namespace's clouds,
//! surrogates, smooth fits, arms, verdicts and nodes. Subscriptions drop
//! (each sample supersedes the last), frames are built only while a browser
//! is connected, and each browser gets only the latest frame of each stream.

mod assets;
mod builder;
mod http;
mod hub;

use super::viewer::{subscribe_drawables, watch_tokens, BlendSender, Inbox};
use crate::args::take_web_listen;
use crate::arm_file::read_arm_file;
use crate::runtime::{run_node, NodeCommon, NodeContext};
use anyhow::{Context, Result};
use builder::{BuilderConfig, FrameBuilder, Shared};
use clap::Args;
use http::Http;
use hub::Hub;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::mpsc;
use std::sync::Arc;
use std::time::Duration;

#[derive(Debug, Clone, Args)]
pub struct DashboardArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// Most points of each cloud sent to a browser (a browser may ask for fewer).
    #[arg(long, default_value_t = 60_000)]
    pub point_budget: usize,
    /// An arm file (as the guard's) whose arm is drawn at its joint states. Repeatable.
    #[arg(long = "arm-file", value_name = "FILE")]
    pub arm_files: Vec<PathBuf>,
    /// Seconds without a verdict after which an arm shows `no-verdict` (STOP).
    #[arg(long, default_value_t = 0.5)]
    pub verdict_timeout: f64,
    /// The blend node to drive (its command stream); default: the first that
    /// announces itself in the namespace.
    #[arg(long)]
    pub blend_stream: Option<String>,
    /// Most frames a second of each cloud, surrogate and smooth fit sent to
    /// the browsers (the latest waits; arms, verdicts and nodes are not
    /// paced): what a viewer needs, and what keeps a 30 Hz 300K-point stream
    /// from costing the robot's cores.
    #[arg(long, default_value_t = 10.0)]
    pub max_rate: f64,
}

/// Where `--listen` serves unless told otherwise.
const DEFAULT_LISTEN: &str = "127.0.0.1:8080";

pub fn run(mut args: DashboardArgs) -> Result<()> {
    let listen = take_web_listen(&mut args.common.zenoh, DEFAULT_LISTEN)?;
    anyhow::ensure!(
        (1000..=2_000_000).contains(&args.point_budget),
        "--point-budget must be 1000 to 2000000 points"
    );
    anyhow::ensure!(
        args.verdict_timeout.is_finite() && args.verdict_timeout > 0.0,
        "--verdict-timeout must be a positive number of seconds"
    );
    anyhow::ensure!(
        args.max_rate.is_finite() && args.max_rate > 0.0 && args.max_rate <= 1000.0,
        "--max-rate must be more than 0 and at most 1000 frames a second"
    );
    let arms = args
        .arm_files
        .iter()
        .map(|path| read_arm_file(path).map(|file| file.arm))
        .collect::<Result<Vec<_>>>()?;
    // Bound before the node joins the graph: a taken port is an error now,
    // not a node that runs without its page.
    let listener = std::net::TcpListener::bind(listen).with_context(|| {
        format!("cannot serve the dashboard on {listen} (is the port taken? --listen 127.0.0.1:0 picks a free one)")
    })?;
    listener.set_nonblocking(true)?;
    let common = args.common.clone();
    let config = BuilderConfig {
        namespace: common.zenoh.namespace.clone(),
        node: String::new(),
        point_budget: args.point_budget,
        arms,
        verdict_timeout_ns: (args.verdict_timeout * 1e9) as u64,
        blend_stream: args.blend_stream.clone(),
        pace_ns: (1e9 / args.max_rate) as u64,
    };
    run_node(&common, "dashboard", move |ctx| {
        serve(ctx, listener, config)
    })
}

fn serve(
    ctx: Arc<NodeContext>,
    listener: std::net::TcpListener,
    mut config: BuilderConfig,
) -> Result<()> {
    config.node = ctx.name.clone();
    let point_budget = config.point_budget;
    let (hub, inbox, shared) = (
        Arc::new(Hub::default()),
        Arc::new(Inbox::new()),
        Arc::new(Shared::default()),
    );
    let _subscribers = subscribe_drawables(&ctx, &inbox)?;
    let (tokens_tx, tokens) = mpsc::channel();
    let _tokens = watch_tokens(&ctx, tokens_tx)?;
    let builder = FrameBuilder::new(ctx.clone(), hub.clone(), inbox, shared.clone(), config);
    let building = std::thread::Builder::new()
        .name("frames".into())
        .spawn(move || builder.run(&tokens))
        .context("cannot start the frame builder")?;
    let http = Http {
        ctx: ctx.clone(),
        hub: hub.clone(),
        shared,
        point_budget,
        blend: Arc::new(BlendSender::default()),
    };
    let served = tokio::runtime::Handle::current().block_on(serve_http(listener, http));
    hub.close_all();
    let _ = building.join();
    served
}

/// Serves the page until the node stops.
async fn serve_http(listener: std::net::TcpListener, http: Http) -> Result<()> {
    let ctx = http.ctx.clone();
    let listener = tokio::net::TcpListener::from_std(listener)?;
    let address: SocketAddr = listener.local_addr()?;
    let url = format!("http://{address}/");
    ctx.metrics.set_label("dashboard.url".into(), url.clone());
    tracing::info!("serving the dashboard at {url}");
    let stop = ctx.clone();
    axum::serve(listener, http::router(http))
        .with_graceful_shutdown(async move {
            while !stop.stopping() {
                tokio::time::sleep(Duration::from_millis(50)).await;
            }
        })
        .await
        .context("the dashboard's HTTP server failed")
}
