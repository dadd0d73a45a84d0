//! `shroud node foxglove`: the Foxglove WebSocket bridge. Serves the Foxglove
//! WebSocket protocol (the `foxglove` crate, subprotocol `foxglove.sdk.v1`) so
//! that Foxglove or Lichtblick shows the namespace's clouds, surrogates, arms,
//! verdicts, certificates and node status, and a client's JSON on
//! `/shroud/blend` drives a blend node (README, "Foxglove and Lichtblick").
//! Subscriptions drop (each sample supersedes the last); a message is
//! converted only for a channel some client subscribes to.

mod bridge;
mod channels;
mod listener;

use super::viewer::{subscribe_drawables, BlendSender, Inbox};
use crate::args::{take_web_listen, ViewerArgs};
use crate::runtime::{run_node, NodeCommon, NodeContext};
use crate::to_foxglove::SURFACE_PER_CELL;
use anyhow::{Context as _, Result};
use bridge::{Bridge, BridgeConfig};
use clap::Args;
use foxglove::websocket::Capability;
use foxglove::{Context, WebSocketServer};
use listener::{Listener, Shared};
use std::net::SocketAddr;
use std::sync::Arc;

#[derive(Debug, Clone, Args)]
pub struct FoxgloveArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    #[command(flatten)]
    pub viewer: ViewerArgs,
    /// Messages queued per client before the oldest is dropped (the
    /// `foxglove` crate's backlog).
    #[arg(long, default_value_t = 16)]
    pub backlog: usize,
}

/// Where `--listen` serves unless told otherwise (Foxglove's usual port).
const DEFAULT_LISTEN: &str = "127.0.0.1:8765";

/// `--point-budget` unless told otherwise (as `shroud record`'s `--points-budget`).
const DEFAULT_POINT_BUDGET: usize = 50_000;

pub fn run(mut args: FoxgloveArgs) -> Result<()> {
    let listen = take_web_listen(&mut args.common.zenoh, DEFAULT_LISTEN)?;
    anyhow::ensure!(
        (1..=1024).contains(&args.backlog),
        "--backlog must be 1 to 1024 messages"
    );
    let viewer = args.viewer.settings(DEFAULT_POINT_BUDGET)?;
    let config = BridgeConfig {
        point_budget: viewer.point_budget,
        per_cell: SURFACE_PER_CELL,
        pace_ns: viewer.pace_ns,
        arms: viewer.arms,
        verdict_timeout_ns: viewer.verdict_timeout_ns,
        blend_stream: viewer.blend_stream,
    };
    let backlog = args.backlog;
    run_node(&args.common.clone(), "foxglove", move |ctx| {
        serve(ctx, listen, backlog, config)
    })
}

fn serve(
    ctx: Arc<NodeContext>,
    listen: SocketAddr,
    backlog: usize,
    config: BridgeConfig,
) -> Result<()> {
    let runtime = tokio::runtime::Handle::current();
    // One context per bridge: the crate's default one is process-wide.
    let context = Context::new();
    let shared = Arc::new(Shared::default());
    let listener = Listener {
        ctx: ctx.clone(),
        shared: shared.clone(),
        blend: BlendSender::default(),
    };
    let server = WebSocketServer::new()
        .name(format!("shroud {}", ctx.name))
        .bind(listen.ip().to_string(), listen.port())
        .context(&context)
        .tokio_runtime(&runtime)
        .capabilities([Capability::ClientPublish])
        .supported_encodings(["json"])
        .listener(Arc::new(listener))
        .message_backlog_size(backlog);
    let server = runtime.block_on(server.start()).with_context(|| {
        format!("cannot serve Foxglove on {listen} (is the port taken? --listen 127.0.0.1:0 picks a free one)")
    })?;
    let url = format!("ws://{}:{}", listen.ip(), server.port());
    ctx.metrics.set_label("foxglove.url".into(), url.clone());
    tracing::info!("serving Foxglove at {url}");
    let inbox = Arc::new(Inbox::new());
    let subscribed = subscribe_drawables(&ctx, &inbox);
    let ran = subscribed.map(|_subscribers| {
        Bridge::new(ctx.clone(), &context, inbox, shared, config).run(&|| server.client_count());
    });
    runtime.block_on(server.stop().wait());
    ran
}
