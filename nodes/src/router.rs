//! `shroud router`: a zenoh router (the engine `zenohd` runs) where a
//! graph's hosts meet, with its status on the bus like a node's. Given a
//! graph file and its host, it takes that host's endpoints and TLS files
//! and enforces the graph's access control (who may publish what).

use crate::runtime::{run_node, NodeCommon};
use anyhow::{Context, Result};
use clap::Args;
use shroud_graph::launch::LaunchFile;
use std::path::PathBuf;
use std::time::Duration;
use zenoh::Wait;

#[derive(Debug, Args)]
pub struct RouterArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// The graph file whose hosts meet here.
    #[arg(long, value_name = "FILE", requires = "host")]
    pub graph: Option<PathBuf>,
    /// This router's host in --graph (its endpoints, certificate and
    /// access control).
    #[arg(long, requires = "graph")]
    pub host: Option<String>,
}

/// How often the router looks at who is linked to it.
const WATCH_PERIOD: Duration = Duration::from_millis(500);

pub fn run(mut args: RouterArgs) -> Result<()> {
    if let (Some(path), Some(host)) = (&args.graph, &args.host) {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read graph file {}", path.display()))?;
        let file = LaunchFile::from_toml_str(&text)
            .with_context(|| format!("graph file {}", path.display()))?;
        args.common.zenoh.serve_host(&file, host)?;
        args.common
            .name
            .get_or_insert_with(|| format!("router.{host}"));
    } else {
        args.common.zenoh.mode = "router".into();
    }
    run_node(&args.common, "router", |ctx| {
        let locators: Vec<String> = (ctx.session.info().locators().wait().iter())
            .map(ToString::to_string)
            .collect();
        tracing::info!("router {} listening on {locators:?}", ctx.session.zid());
        while !ctx.stopping() {
            let links = linked(&ctx.session);
            ctx.metrics.set_label("links".into(), links.to_string());
            std::thread::sleep(WATCH_PERIOD);
        }
        Ok(())
    })
}

/// Routers and peers linked to this one (clients are not listed by zenoh's
/// session info).
fn linked(session: &zenoh::Session) -> usize {
    let info = session.info();
    info.routers_zid().wait().count() + info.peers_zid().wait().count()
}
