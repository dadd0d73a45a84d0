//! `shroud topic list`: listens to `shroud/<ns>/**` for a while and reports every
//! key seen, with its message kind, count, rate and mean size.

use super::tool::ToolArgs;
use anyhow::Result;
use clap::Args;
use shroud_msg::TopicKey;
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};
use std::time::Duration;

#[derive(Debug, Args)]
pub struct TopicListArgs {
    #[command(flatten)]
    pub tool: ToolArgs,
    /// Seconds to listen.
    #[arg(long, default_value_t = 2.0)]
    pub duration: f64,
}

#[derive(Default)]
struct Seen {
    count: u64,
    bytes: u64,
}

pub fn run(args: TopicListArgs) -> Result<()> {
    anyhow::ensure!(
        args.duration.is_finite() && args.duration > 0.0,
        "--duration must be positive"
    );
    args.tool.block_on(async {
        let topics = args.tool.zenoh.topics()?;
        let session = args.tool.zenoh.open().await?;
        let seen: Arc<Mutex<BTreeMap<String, Seen>>> = Arc::default();
        let sink = seen.clone();
        let _sub = session
            .declare_subscriber(topics.all())
            .callback(move |sample| {
                let mut map = sink.lock().unwrap_or_else(|p| p.into_inner());
                let entry = map.entry(sample.key_expr().to_string()).or_default();
                entry.count += 1;
                entry.bytes += sample.payload().len() as u64;
            })
            .await
            .map_err(|e| anyhow::anyhow!("subscribe: {e}"))?;
        tokio::time::sleep(Duration::from_secs_f64(args.duration)).await;
        let map = seen.lock().unwrap_or_else(|p| p.into_inner());
        println!(
            "{:<48} {:<10} {:>8} {:>9} {:>12}",
            "topic", "kind", "count", "rate Hz", "mean bytes"
        );
        for (key, s) in map.iter() {
            let kind = TopicKey::parse(key)
                .map(|k| k.kind.to_string())
                .unwrap_or_else(|| "foreign".into());
            println!(
                "{key:<48} {kind:<10} {:>8} {:>9.1} {:>12}",
                s.count,
                s.count as f64 / args.duration,
                s.bytes / s.count.max(1)
            );
        }
        if map.is_empty() {
            println!("(no messages in {} s on {})", args.duration, topics.all());
        }
        Ok(())
    })
}
