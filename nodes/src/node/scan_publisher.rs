//! What the sensor nodes do with each decoded scan: publish it as a cloud
//! (with its time in shroud so far, and its device stamp checked for skew)
//! and mirror the reader's counters (decode errors, disconnects, reopenings)
//! into the node's status.

use super::runtime::NodeContext;
use crate::ingest::ReaderStats;
use crate::transport::unix_ns;
use anyhow::Result;
use shroud_core::ingest::Scan;
use shroud_core::message::{check_stamp_skew, max_skew_ns_from_secs, SensorPose, TopicKind};

/// `--max-skew` in seconds (`inf`: no check) as nanoseconds, or a named error.
pub(super) fn max_skew_ns(seconds: f64) -> Result<u64> {
    max_skew_ns_from_secs(seconds)
        .ok_or_else(|| anyhow::anyhow!("--max-skew must be positive (inf: no check)"))
}
use std::sync::Arc;
use std::time::Instant;
use zenoh::Wait;

/// The `on_scan` callback: publish each scan as a cloud and mirror the reader's
/// counters into the node's status.
pub(super) fn cloud_publisher<'a>(
    ctx: &'a Arc<NodeContext>,
    stream: &str,
    device: &str,
    max_skew_ns: u64,
) -> Result<impl FnMut(Scan, &ReaderStats) + 'a> {
    let device = device.to_owned();
    let publisher = ctx.publisher(TopicKind::Cloud, stream)?;
    let key = publisher.key_expr().to_string();
    let writer = ctx.payload_writer(16 << 20);
    let source = format!("{}/{device}", ctx.name);
    let mut sequence = 0u64;
    Ok(move |scan: Scan, stats: &ReaderStats| {
        // The scan's last byte has just been read: it enters shroud now.
        let received = Instant::now();
        if let Err(skew) = check_stamp_skew(scan.stamp_ns, unix_ns(), max_skew_ns) {
            ctx.metrics.add("clock_skew", 1);
            tracing::warn!(%device, "device {skew}");
        }
        let published = scan
            .to_view(sequence, &source, SensorPose::default())
            .map(|view| view.with_pipeline_ns(received.elapsed().as_nanos() as u64))
            .and_then(|view| writer.encode(&view))
            .map_err(anyhow::Error::from)
            .and_then(|b| publisher.put(b).wait().map_err(|e| anyhow::anyhow!("{e}")));
        match published {
            Ok(()) => ctx.metrics.add("published", 1),
            Err(e) => {
                ctx.metrics.add("publish_errors", 1);
                tracing::warn!("publish {key}: {e}");
            }
        }
        sequence += 1;
        ctx.metrics.set_counter(
            "dropped_malformed",
            stats.decoder.total_errors() + stats.transport.total_errors(),
        );
        ctx.metrics.set_counter("disconnects", stats.disconnects);
        ctx.metrics
            .set_counter("open_failures", stats.open_failures);
        ctx.metrics.set_counter("scans", stats.scans);
    })
}
