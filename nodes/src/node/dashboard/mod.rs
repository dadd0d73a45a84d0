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
use crate::args::{take_web_listen, ViewerArgs};
use crate::runtime::{run_node, NodeCommon, NodeContext};
use anyhow::{Context, Result};
use builder::{BuilderConfig, FrameBuilder, Shared};
use clap::Args;
use http::Http;
use hub::Hub;
use std::net::SocketAddr;
use std::sync::mpsc;
use std::sync::Arc;
use std::time::Duration;

#[derive(Debug, Clone, Args)]
pub struct DashboardArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    #[command(flatten)]
    pub viewer: ViewerArgs,
}

/// Where `--listen` serves unless told otherwise.
const DEFAULT_LISTEN: &str = "127.0.0.1:8080";

/// `--point-budget` unless told otherwise.
const DEFAULT_POINT_BUDGET: usize = 60_000;

pub fn run(mut args: DashboardArgs) -> Result<()> {
    let listen = take_web_listen(&mut args.common.zenoh, DEFAULT_LISTEN)?;
    let viewer = args.viewer.settings(DEFAULT_POINT_BUDGET)?;
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
        point_budget: viewer.point_budget,
        arms: viewer.arms,
        verdict_timeout_ns: viewer.verdict_timeout_ns,
        blend_stream: viewer.blend_stream,
        pace_ns: viewer.pace_ns,
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
