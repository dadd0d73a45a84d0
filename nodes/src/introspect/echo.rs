//! `shroud topic echo`: prints each message of a topic as one JSON line, decoded
//! by the kind its key names; undecodable messages are reported, not fatal.

use super::tool::{resolve_topic, ToolArgs};
use anyhow::Result;
use clap::Args;
use shroud_msg::TopicKey;
use shroud_viewers::describe::describe;
use std::time::Duration;

#[derive(Debug, Args)]
pub struct EchoArgs {
    /// `<kind>/<name>` (e.g. `surrogate/sim`, `collision/*`) or a full key.
    pub topic: String,
    #[command(flatten)]
    pub tool: ToolArgs,
    /// Stop after this many messages (0: until Ctrl-C or --timeout).
    #[arg(long, default_value_t = 0)]
    pub count: u64,
    /// Give up after this many seconds (0: never); exits non-zero if nothing arrived.
    #[arg(long, default_value_t = 0.0)]
    pub timeout: f64,
}

pub fn run(args: EchoArgs) -> Result<()> {
    anyhow::ensure!(
        args.timeout.is_finite() && args.timeout >= 0.0,
        "--timeout must be >= 0"
    );
    args.tool.block_on(async {
        let key = resolve_topic(&args.tool.zenoh.topics()?, &args.topic)?;
        let session = args.tool.zenoh.open().await?;
        let sub = session
            .declare_subscriber(&key)
            .await
            .map_err(|e| anyhow::anyhow!("subscribe {key}: {e}"))?;
        let deadline = (args.timeout > 0.0).then(|| tokio::time::Instant::now() + Duration::from_secs_f64(args.timeout));
        let mut printed = 0u64;
        // One wait for the whole loop, so a signal between turns is not missed.
        let stop_signal = crate::transport::shutdown_signal();
        tokio::pin!(stop_signal);
        while args.count == 0 || printed < args.count {
            let next = sub.recv_async();
            let sample = match deadline {
                Some(d) => match tokio::time::timeout_at(d, next).await {
                    Ok(s) => s,
                    Err(_) => break,
                },
                None => tokio::select! {
                    s = next => s,
                    _ = &mut stop_signal => break,
                },
            };
            let Ok(sample) = sample else { break };
            let k = sample.key_expr().to_string();
            let line = match TopicKey::parse(&k) {
                Some(topic) => match describe(topic.kind, &sample.payload().to_bytes()) {
                    Ok(v) => serde_json::json!({ "key": k, "message": v }),
                    Err(e) => serde_json::json!({ "key": k, "error": e.to_string() }),
                },
                None => serde_json::json!({ "key": k, "error": "key outside the shroud convention", "bytes": sample.payload().len() }),
            };
            println!("{line}");
            printed += 1;
        }
        anyhow::ensure!(printed > 0 || deadline.is_none(), "no message on {key} within {} s", args.timeout);
        Ok(())
    })
}
