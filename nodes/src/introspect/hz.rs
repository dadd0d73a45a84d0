//! `shroud topic hz`: message rate, size and bandwidth of a topic, once a second.

use super::tool::{resolve_topic, ToolArgs};
use anyhow::Result;
use clap::Args;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

#[derive(Debug, Args)]
pub struct HzArgs {
    /// `<kind>/<name>` (e.g. `cloud/sim`) or a full key.
    pub topic: String,
    #[command(flatten)]
    pub tool: ToolArgs,
    /// Seconds to measure (0: until Ctrl-C).
    #[arg(long, default_value_t = 0.0)]
    pub duration: f64,
}

pub fn run(args: HzArgs) -> Result<()> {
    anyhow::ensure!(
        args.duration.is_finite() && args.duration >= 0.0,
        "--duration must be >= 0"
    );
    args.tool.block_on(async {
        let key = resolve_topic(&args.tool.zenoh.topics()?, &args.topic)?;
        let session = args.tool.zenoh.open().await?;
        let (count, bytes) = (Arc::new(AtomicU64::new(0)), Arc::new(AtomicU64::new(0)));
        let (c, b) = (count.clone(), bytes.clone());
        let _sub = session
            .declare_subscriber(&key)
            .callback(move |s| {
                c.fetch_add(1, Ordering::Relaxed);
                b.fetch_add(s.payload().len() as u64, Ordering::Relaxed);
            })
            .await
            .map_err(|e| anyhow::anyhow!("subscribe {key}: {e}"))?;
        let start = Instant::now();
        let mut tick = tokio::time::interval(Duration::from_secs(1));
        tick.tick().await;
        let (mut last_n, mut last_b, mut total) = (0u64, 0u64, 0u64);
        // One wait for the whole loop, so a signal between turns is not missed.
        let stop_signal = crate::transport::shutdown_signal();
        tokio::pin!(stop_signal);
        loop {
            tokio::select! {
                _ = tick.tick() => {}
                _ = &mut stop_signal => break,
            }
            let (n, nb) = (count.load(Ordering::Relaxed), bytes.load(Ordering::Relaxed));
            let (dn, db) = (n - last_n, nb - last_b);
            (last_n, last_b, total) = (n, nb, n);
            println!(
                "{key}: {dn} Hz, mean {} bytes, {:.2} MB/s",
                db / dn.max(1),
                db as f64 / 1e6
            );
            if args.duration > 0.0 && start.elapsed().as_secs_f64() >= args.duration {
                break;
            }
        }
        println!(
            "{key}: {total} messages in {:.1} s",
            start.elapsed().as_secs_f64()
        );
        Ok(())
    })
}
