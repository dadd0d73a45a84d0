//! The node's status message, published every `--status-period`, and once
//! more as the node stops (so that a node whose work ends, a replayed log,
//! leaves its final counters behind).

use super::context::NodeContext;
use crate::transport::{session_drops, unix_ns};
use shroud_msg::{NodeStatusMessage, TopicKind};
use std::sync::Arc;
use std::time::{Duration, Instant};
use zenoh::Wait;

pub(super) async fn publish_status(
    ctx: Arc<NodeContext>,
    kind: &'static str,
    period: f64,
    start: Instant,
) {
    let mut tick = tokio::time::interval(Duration::from_secs_f64(period));
    let Some(mut writer) = StatusWriter::new(&ctx, kind, start) else {
        return;
    };
    loop {
        tick.tick().await;
        if let Some(drops) = session_drops(&ctx.session).await {
            for (counter, value) in drops.counters() {
                ctx.metrics.set_counter(counter, value);
            }
        }
        writer.publish(&ctx);
    }
}

/// One last status, with the counters as the node leaves them.
pub(super) fn publish_final_status(ctx: &NodeContext, kind: &'static str, start: Instant) {
    if let Some(mut writer) = StatusWriter::new(ctx, kind, start) {
        writer.publish(ctx);
    }
}

struct StatusWriter {
    publisher: zenoh::pubsub::Publisher<'static>,
    msg: NodeStatusMessage,
    start: Instant,
}

impl StatusWriter {
    fn new(ctx: &NodeContext, kind: &'static str, start: Instant) -> Option<Self> {
        let publisher = match ctx.publisher(TopicKind::Status, &ctx.name) {
            Ok(publisher) => publisher,
            Err(e) => {
                tracing::error!("no status messages: {e:#}");
                return None;
            }
        };
        let msg = NodeStatusMessage::new(&ctx.name, kind, std::process::id());
        Some(Self {
            publisher,
            msg,
            start,
        })
    }

    fn publish(&mut self, ctx: &NodeContext) {
        let msg = &mut self.msg;
        msg.stamp_ns = unix_ns();
        msg.uptime_s = self.start.elapsed().as_secs_f64();
        ctx.metrics.fill(msg);
        match msg.to_bytes() {
            Ok(bytes) => {
                if let Err(e) = self.publisher.put(bytes).wait() {
                    tracing::warn!("status publish failed: {e}");
                }
            }
            Err(e) => tracing::warn!("status encode failed: {e}"),
        }
    }
}
