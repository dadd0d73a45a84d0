//! The `serial` and `can` nodes: real range sensors. A blocking reader (from
//! `crate::ingest`) decodes scans; each scan is published as a cloud, and the
//! reader's counters (decode errors, disconnects, reopenings) go into the
//! node's status.

use super::runtime::{run_node, NodeCommon, NodeContext};
use crate::ingest::{
    run_can_reader, run_serial_reader, CanReaderConfig, CanSourceSpec, ReaderStats,
    SerialReaderConfig,
};
use crate::transport::{unix_ns, PayloadWriter};
use anyhow::Result;
use clap::Args;
use shroud_core::ingest::Scan;
use shroud_core::message::{check_stamp_skew, max_skew_ns_from_secs, SensorPose, TopicKind};
use std::sync::Arc;
use std::time::Instant;
use zenoh::qos::CongestionControl;
use zenoh::Wait;

#[derive(Debug, Clone, Args)]
pub struct SerialNodeArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// Serial device (`/dev/ttyUSB0`, `/dev/serial/by-id/...`, a pty).
    #[arg(long)]
    pub port: String,
    #[arg(long, default_value_t = 921_600)]
    pub baud: u32,
    /// Stream name: clouds go to `shroud/<ns>/cloud/<stream>`.
    #[arg(long, default_value = "serial")]
    pub stream: String,
    /// A device stamp further than this (seconds) from this node's clock is
    /// counted as `clock_skew` (stamps are kept, never used for decisions).
    #[arg(long, default_value_t = 5.0)]
    pub max_skew: f64,
}

#[derive(Debug, Clone, Args)]
pub struct CanNodeArgs {
    #[command(flatten)]
    pub common: NodeCommon,
    /// `socketcan:IFACE`, `slcan:PATH[@BAUD][:BITRATE]` or `candump:PATH[@SPEED|@max]`.
    #[arg(long)]
    pub source: String,
    /// Stream name: clouds go to `shroud/<ns>/cloud/<stream>`.
    #[arg(long, default_value = "can")]
    pub stream: String,
    /// A device (or log) stamp further than this (seconds) from this node's
    /// clock is counted as `clock_skew` (`inf`: no check, for old logs).
    #[arg(long, default_value_t = 5.0)]
    pub max_skew: f64,
}

pub fn run_serial(args: SerialNodeArgs) -> Result<()> {
    let config = SerialReaderConfig::new(&args.port, args.baud);
    let common = args.common.clone();
    run_node(&common, "serial", move |ctx| {
        let mut publish = cloud_publisher(&ctx, &args.stream, &args.port, args.max_skew)?;
        let stats = run_serial_reader(&config, &mut publish, ctx.stop_flag())?;
        tracing::info!("serial reader stopped: {stats}");
        Ok(())
    })
}

pub fn run_can(args: CanNodeArgs) -> Result<()> {
    let spec: CanSourceSpec = args
        .source
        .parse()
        .map_err(|e| anyhow::anyhow!("--source {:?}: {e}", args.source))?;
    let common = args.common.clone();
    run_node(&common, "can", move |ctx| {
        let mut publish = cloud_publisher(&ctx, &args.stream, &args.source, args.max_skew)?;
        let stats = run_can_reader(
            &mut || spec.open(),
            &CanReaderConfig::default(),
            &mut publish,
            ctx.stop_flag(),
        )?;
        tracing::info!("CAN reader stopped: {stats}");
        Ok(())
    })
}

/// The `on_scan` callback: publish each scan as a cloud and mirror the reader's
/// counters into the node's status.
fn cloud_publisher<'a>(
    ctx: &'a Arc<NodeContext>,
    stream: &str,
    device: &str,
    max_skew: f64,
) -> Result<impl FnMut(Scan, &ReaderStats) + 'a> {
    let max_skew_ns = max_skew_ns_from_secs(max_skew)
        .ok_or_else(|| anyhow::anyhow!("--max-skew must be positive (inf: no check)"))?;
    let device = device.to_owned();
    let key = ctx.key(TopicKind::Cloud, stream)?;
    let publisher = ctx
        .session
        .declare_publisher(key.clone())
        .congestion_control(CongestionControl::Drop)
        .wait()
        .map_err(|e| anyhow::anyhow!("publisher {key}: {e}"))?;
    let writer = PayloadWriter::new(true, 16 << 20);
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
