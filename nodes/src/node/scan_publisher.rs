//! What the sensor nodes do with each cloud they make: publish it (with its
//! time in shroud so far, and its device stamp checked for skew), and mirror
//! the protocol reader's counters (decode errors, disconnects, reopenings)
//! into the node's status.

use crate::ingest::ReaderStats;
use crate::runtime::{NodeContext, Output};
use crate::transport::unix_ns;
use anyhow::Result;
use shroud_drivers::Scan;
use shroud_graph::metrics::names as metric;
use shroud_msg::{check_stamp_skew, max_skew_ns_from_secs, CloudMessage, SensorPose};
use std::sync::Arc;
use std::time::Instant;

/// `--max-skew` in seconds (`inf`: no check) as nanoseconds, or a named error.
pub(super) fn max_skew_ns(seconds: f64) -> Result<u64> {
    max_skew_ns_from_secs(seconds)
        .ok_or_else(|| anyhow::anyhow!("--max-skew must be positive (inf: no check)"))
}

/// Publishes clouds on `cloud/<stream>`, counting `published`,
/// `publish_errors` and `clock_skew`.
pub(super) struct CloudOut<'a> {
    ctx: &'a Arc<NodeContext>,
    output: Output<CloudMessage>,
    device: String,
    source: String,
    max_skew_ns: u64,
    sequence: u64,
}

impl<'a> CloudOut<'a> {
    pub fn new(
        ctx: &'a Arc<NodeContext>,
        stream: &str,
        device: &str,
        max_skew_ns: u64,
    ) -> Result<Self> {
        Ok(Self {
            output: ctx.output_shared::<CloudMessage>(stream, 16 << 20)?,
            device: device.to_owned(),
            source: format!("{}/{device}", ctx.name),
            ctx,
            max_skew_ns,
            sequence: 0,
        })
    }

    /// Publishes `scan` (points in the robot's frame), `pipeline_ns` after
    /// its data reached this host.
    pub fn publish(&mut self, scan: &Scan, since_receipt: impl Fn() -> u64) {
        self.publish_bounded(scan, 0.0, since_receipt);
    }

    /// [`Self::publish`] stating how far its points may be from where they
    /// were measured (`position_error_m`, metres).
    pub fn publish_bounded(
        &mut self,
        scan: &Scan,
        position_error_m: f64,
        since_receipt: impl Fn() -> u64,
    ) {
        if let Err(skew) = check_stamp_skew(scan.stamp_ns, unix_ns(), self.max_skew_ns) {
            self.ctx.metrics.add(metric::CLOCK_SKEW, 1);
            tracing::warn!(device = %self.device, "device {skew}");
        }
        let view = scan
            .to_view(self.sequence, &self.source, SensorPose::default())
            .and_then(|view| view.with_position_error_m(position_error_m))
            .map(|view| view.with_pipeline_ns(since_receipt()));
        match view {
            Ok(view) => {
                self.output.put(&view);
            }
            Err(e) => {
                self.ctx.metrics.add(metric::PUBLISH_ERRORS, 1);
                tracing::warn!("publish {}: {e}", self.output.key());
            }
        }
        self.sequence += 1;
    }
}

/// The `on_scan` callback of the protocol readers: publish each scan as a
/// cloud and mirror the reader's counters into the node's status.
pub(super) fn cloud_publisher<'a>(
    ctx: &'a Arc<NodeContext>,
    stream: &str,
    device: &str,
    max_skew_ns: u64,
) -> Result<impl FnMut(Scan, &ReaderStats) + 'a> {
    let mut out = CloudOut::new(ctx, stream, device, max_skew_ns)?;
    Ok(move |scan: Scan, stats: &ReaderStats| {
        // The scan's last byte has just been read: it enters shroud now.
        let received = Instant::now();
        out.publish(&scan, || received.elapsed().as_nanos() as u64);
        mirror_reader_counters(ctx, stats);
    })
}

/// A protocol reader's counters into the node's status.
pub(super) fn mirror_reader_counters(ctx: &NodeContext, stats: &ReaderStats) {
    let m = &ctx.metrics;
    m.set_counter(
        metric::DROPPED_MALFORMED,
        stats.decoder.total_errors() + stats.transport.total_errors(),
    );
    m.set_counter(metric::DISCONNECTS, stats.disconnects);
    m.set_counter(metric::OPEN_FAILURES, stats.open_failures);
    m.set_counter(metric::SCANS, stats.scans);
}
