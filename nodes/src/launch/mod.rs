//! `shroud launch FILE`: starts every node of a launch file as a child process,
//! prefixes their logs, restarts failed nodes by policy, prints a live summary,
//! and stops them all on Ctrl-C or SIGTERM. Children stop with the launcher even
//! when it is killed outright: each gets a parent-death signal and watches the
//! launcher's pid itself (`SHROUD_LAUNCHER_PID`), which works whether or not the
//! dead launcher is reaped.

mod child;
mod monitor;
mod output;
mod plan;
mod roster;
mod supervise;

use anyhow::{Context, Result};
use clap::Args;
use shroud_graph::launch::{wiring_mermaid, wiring_text, LaunchFile};
use std::path::PathBuf;
use std::time::Duration;

#[derive(Debug, Args)]
pub struct LaunchArgs {
    /// The launch file (TOML; schema in launch/README.md).
    pub file: PathBuf,
    /// Stop the whole graph after this many seconds (0: run until Ctrl-C).
    #[arg(long, default_value_t = 0.0)]
    pub duration: f64,
    /// Log filter handed to every node.
    #[arg(long, default_value = "info,zenoh=warn")]
    pub node_log: String,
    /// Check the file and every node's settings, print each node's command
    /// line, and exit.
    #[arg(long)]
    pub check: bool,
    /// Check the file, print its wiring (text, then a Mermaid flowchart) and exit.
    #[arg(long, conflicts_with = "check")]
    pub graph: bool,
    /// Start only the nodes of this host of the file's `[hosts]`: the
    /// launcher runs the host's zenoh router (its endpoints, TLS and the
    /// graph's access control) and its nodes are that router's clients.
    #[arg(long)]
    pub host: Option<String>,
}

pub fn run(args: LaunchArgs) -> Result<()> {
    anyhow::ensure!(
        args.duration.is_finite() && args.duration >= 0.0,
        "--duration must be >= 0"
    );
    tracing_subscriber::EnvFilter::try_new(&args.node_log)
        .map_err(|e| anyhow::anyhow!("invalid --node-log filter {:?}: {e}", args.node_log))?;
    let text = std::fs::read_to_string(&args.file)
        .with_context(|| format!("cannot read launch file {}", args.file.display()))?;
    let context = || format!("launch file {}", args.file.display());
    let file = LaunchFile::from_toml_str(&text).with_context(context)?;
    if let Some(host) = &args.host {
        file.host(host).with_context(context)?;
    }
    anyhow::ensure!(
        args.host.is_some() || file.hosts.is_empty() || args.check || args.graph,
        "{} places its nodes on hosts ({}): start each host's with --host NAME",
        args.file.display(),
        file.host_names().join(", ")
    );
    // Every node's settings against its own parser, before anything runs.
    let nodes = plan::plan(&file).with_context(context)?;
    let nodes: Vec<_> = (nodes.into_iter())
        .filter(|n| args.host.is_none() || n.spec.host == args.host)
        .collect();
    if args.host.is_some() {
        refuse_own_links(&nodes)?;
    }
    if let (Some(host), true) = (&args.host, nodes.is_empty()) {
        anyhow::bail!(
            "host {host} runs no node of {}: for a host that only relays, run `shroud router --graph {} --host {host}`",
            args.file.display(),
            args.file.display()
        );
    }
    if args.check {
        for node in &nodes {
            let (name, kind) = (&node.spec.name, node.spec.kind);
            let host = node
                .spec
                .host
                .as_deref()
                .map(|h| format!(" (host {h})"))
                .unwrap_or_default();
            println!("{name}{host}: shroud node {kind} {}", node.args.join(" "));
        }
        return Ok(());
    }
    if args.graph {
        print!("{}", wiring_text(&file).with_context(context)?);
        println!(
            "\n```mermaid\n{}```",
            wiring_mermaid(&file).with_context(context)?
        );
        return Ok(());
    }
    // Our own prefixed lines must not panic if whoever reads them goes away.
    crate::transport::keep_outputs_writable();
    // One worker thread (zenoh needs the multi-thread scheduler): the children
    // are spawned from it, and the kernel's parent-death signal is tied to the
    // thread that forked them, which lives as long as the runtime.
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_all()
        .build()
        .context("cannot start the async runtime")?;
    let duration = (args.duration > 0.0).then(|| Duration::from_secs_f64(args.duration));
    let shm = file.zenoh.shm;
    let outcome = runtime.block_on(supervise::run_graph(
        file,
        args.host,
        nodes,
        args.node_log,
        duration,
    ));
    // The children have stopped and the session is closed: their segments and
    // ours are orphans now, which zenoh alone would leave in /dev/shm.
    if shm {
        crate::transport::release_shm_segments();
    }
    // Every queued line (the children's last words too) before we exit.
    output::flush(std::time::Duration::from_secs(2));
    outcome
}

/// A host's nodes link only to their host's router (which checks what other
/// hosts send): a node of its own endpoints or configuration could be
/// dialled, or dial, around it.
fn refuse_own_links(nodes: &[plan::PlannedNode]) -> Result<()> {
    for node in nodes {
        let spec = &node.spec;
        for key in ["listen", "zenoh_config", "zenoh-config"] {
            if spec.settings.contains_key(key) {
                return Err(spec
                    .error(format!(
                        "settings.{key}: a node of a host links only to its host's router"
                    ))
                    .into());
            }
        }
    }
    Ok(())
}
