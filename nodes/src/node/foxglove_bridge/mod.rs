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
use crate::args::take_web_listen;
use crate::arm_file::read_arm_file;
use crate::runtime::{run_node, NodeCommon, NodeContext};
use crate::to_foxglove::SURFACE_PER_CELL;
use anyhow::{Context as _, Result};
use bridge::{Bridge, BridgeConfig};
use clap::Args;
use foxglove::websocket::Capability;
use foxglove::{Context, WebSocketServer};
use listener::{Listener, Shared};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;

#[derive(Debug, Clone, Args)]
pub struct FoxgloveArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// Most points of each cloud sent to a client.
    #[arg(long, default_value_t = 50_000)]
    pub points_budget: usize,
    /// Most messages a second of each cloud, surrogate and arm (the latest
    /// waits; clients' queues count messages, not bytes).
    #[arg(long, default_value_t = 10.0)]
    pub max_rate: f64,
    /// Messages queued per client before the oldest is dropped (the
    /// `foxglove` crate's backlog).
    #[arg(long, default_value_t = 16)]
    pub backlog: usize,
    /// An arm file (as the guard's) whose arm is drawn at its joint states. Repeatable.
    #[arg(long = "arm-file", value_name = "FILE")]
    pub arm_files: Vec<PathBuf>,
    /// Seconds without a verdict after which an arm shows `no-verdict` (STOP).
    #[arg(long, default_value_t = 0.5)]
    pub verdict_timeout: f64,
    /// The blend node a client's `/shroud/blend` drives (its command stream);
    /// default: the first that announces itself in the namespace.
    #[arg(long)]
    pub blend_stream: Option<String>,
}

/// Where `--listen` serves unless told otherwise (Foxglove's usual port).
const DEFAULT_LISTEN: &str = "127.0.0.1:8765";

pub fn run(mut args: FoxgloveArgs) -> Result<()> {
    let listen = take_web_listen(&mut args.common.zenoh, DEFAULT_LISTEN)?;
    anyhow::ensure!(
        (1000..=2_000_000).contains(&args.points_budget),
        "--points-budget must be 1000 to 2000000 points"
    );
    anyhow::ensure!(
        args.max_rate.is_finite() && args.max_rate > 0.0 && args.max_rate <= 1000.0,
        "--max-rate must be more than 0 and at most 1000 messages a second"
    );
    anyhow::ensure!(
        (1..=1024).contains(&args.backlog),
        "--backlog must be 1 to 1024 messages"
    );
    anyhow::ensure!(
        args.verdict_timeout.is_finite()
            && args.verdict_timeout > 0.0
            && args.verdict_timeout <= 3600.0,
        "--verdict-timeout must be more than 0 and at most 3600 seconds"
    );
    let arms = args
        .arm_files
        .iter()
        .map(|path| read_arm_file(path).map(|file| file.arm))
        .collect::<Result<Vec<_>>>()?;
    let config = BridgeConfig {
        point_budget: args.points_budget,
        per_cell: SURFACE_PER_CELL,
        pace_ns: (1e9 / args.max_rate) as u64,
        arms,
        verdict_timeout_ns: (args.verdict_timeout * 1e9) as u64,
        blend_stream: args.blend_stream.clone(),
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
