//! The node's status message, published every `--status-period`.

use super::context::NodeContext;
use crate::transport::unix_ns;
use shroud_core::message::{NodeStatusMessage, TopicKind};
use std::sync::Arc;
use std::time::{Duration, Instant};
use zenoh::Wait;

pub(super) async fn publish_status(ctx: Arc<NodeContext>, kind: &'static str, period: f64) {
    let publisher = match ctx.publisher(TopicKind::Status, &ctx.name) {
        Ok(publisher) => publisher,
        Err(e) => return tracing::error!("no status messages: {e:#}"),
    };
    let start = Instant::now();
    let mut msg = NodeStatusMessage::new(&ctx.name, kind, std::process::id());
    let mut tick = tokio::time::interval(Duration::from_secs_f64(period));
    loop {
        tick.tick().await;
        msg.stamp_ns = unix_ns();
        msg.uptime_s = start.elapsed().as_secs_f64();
        ctx.metrics.fill(&mut msg);
        match msg.to_bytes() {
            Ok(bytes) => {
                if let Err(e) = publisher.put(bytes).wait() {
                    tracing::warn!("status publish failed: {e}");
                }
            }
            Err(e) => tracing::warn!("status encode failed: {e}"),
        }
    }
}
