//! `shroud node list`: the nodes whose liveliness tokens are present in the
//! namespace, with the latest status each published.

use crate::introspect::ToolArgs;
use anyhow::Result;
use clap::Args;
use shroud_msg::{NodeStatusMessage, TopicKey, TopicKind};
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};
use std::time::Duration;

#[derive(Debug, Args)]
pub struct NodeListArgs {
    #[command(flatten)]
    pub tool: ToolArgs,
    /// Seconds to wait for status messages.
    #[arg(long, default_value_t = 1.5)]
    pub wait: f64,
}

pub fn run(args: NodeListArgs) -> Result<()> {
    anyhow::ensure!(
        args.wait.is_finite() && args.wait >= 0.0,
        "--wait must be >= 0"
    );
    args.tool.block_on(async {
        let topics = args.tool.zenoh.topics()?;
        let session = args.tool.zenoh.open().await?;
        let statuses: Arc<Mutex<BTreeMap<String, NodeStatusMessage>>> = Arc::default();
        let sink = statuses.clone();
        let _sub = session
            .declare_subscriber(topics.key(TopicKind::Status, "*")?)
            .callback(move |s| {
                if let Ok(msg) = NodeStatusMessage::from_bytes(&s.payload().to_bytes()) {
                    sink.lock()
                        .unwrap_or_else(|p| p.into_inner())
                        .insert(msg.node.clone(), msg);
                }
            })
            .await
            .map_err(|e| anyhow::anyhow!("subscribe status: {e}"))?;
        tokio::time::sleep(Duration::from_secs_f64(args.wait)).await;
        let alive_key = topics.key(TopicKind::Alive, "*")?;
        let replies = session
            .liveliness()
            .get(&alive_key)
            .timeout(Duration::from_secs(2))
            .await
            .map_err(|e| anyhow::anyhow!("liveliness query: {e}"))?;
        let mut alive = Vec::new();
        while let Ok(reply) = replies.recv_async().await {
            if let Ok(sample) = reply.into_result() {
                if let Some(key) = TopicKey::parse(sample.key_expr().as_str()) {
                    alive.push(key.name);
                }
            }
        }
        alive.sort();
        alive.dedup();
        let statuses = statuses.lock().unwrap_or_else(|p| p.into_inner());
        println!(
            "{:<16} {:<10} {:>8} {:>9}  counters",
            "node", "kind", "pid", "uptime s"
        );
        for name in &alive {
            match statuses.get(name) {
                Some(s) => {
                    let counters: Vec<String> =
                        s.counters.iter().map(|(k, v)| format!("{k}={v}")).collect();
                    println!(
                        "{name:<16} {:<10} {:>8} {:>9.1}  {}",
                        s.kind,
                        s.pid,
                        s.uptime_s,
                        counters.join(" ")
                    );
                    // A device's state, health and identity, one per line.
                    for (label, value) in &s.labels {
                        println!("{:<16} {label} = {value}", "");
                    }
                }
                None => println!(
                    "{name:<16} {:<10} {:>8} {:>9}  (no status yet)",
                    "?", "?", "?"
                ),
            }
        }
        if alive.is_empty() {
            println!("(no node alive in namespace {})", topics.namespace());
        }
        Ok(())
    })
}
