//! The `can` node: a range sensor on a CAN bus (SocketCAN, an SLCAN adapter or
//! a candump log). With `--device shroud` a blocking reader decodes shroud's
//! own scan protocol; with a real device (ARS408 radar, Benewake
//! rangefinders) its driver assembles each measurement cycle into a cloud in
//! the robot's frame. Either way each cloud is published on `cloud/<stream>`.

use super::device_status::{mirror_driver_counters, report_health, report_identity, report_state};
use super::scan_publisher::{cloud_publisher, max_skew_ns, mirror_reader_counters, CloudOut};
use crate::args::CanDeviceArgs;
use crate::ingest::{
    host_now, run_can_device, run_can_reader, BackoffConfig, BusStats, CanReaderConfig,
    CanSourceSpec,
};
use crate::runtime::{run_node, NodeCommon, NodeContext};
use anyhow::Result;
use clap::Args;
use shroud_drivers::can_device::{CanDeviceDriver, CanDriverOutput, SensorCloud};
use shroud_drivers::device::DeviceState;
use shroud_graph::metrics::names as metric;
use std::sync::Arc;

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
    #[command(flatten)]
    pub device: CanDeviceArgs,
}

pub fn run_can(args: CanNodeArgs) -> Result<()> {
    let max_skew_ns = max_skew_ns(args.max_skew)?;
    let spec: CanSourceSpec = args
        .source
        .parse()
        .map_err(|e| anyhow::anyhow!("--source {:?}: {e}", args.source))?;
    let common = args.common.clone();
    if args.device.is_real_device() {
        // Settings are checked before the node joins the graph.
        let driver = args.device.driver()?;
        check_source(&spec, &args.source)?;
        return run_node(&common, "can", move |ctx| {
            run_device_clouds(&ctx, driver, &spec, &args.stream, max_skew_ns)
        });
    }
    args.device.check_protocol_only()?;
    check_source(&spec, &args.source)?;
    run_node(&common, "can", move |ctx| {
        let mut publish = cloud_publisher(&ctx, &args.stream, &args.source, max_skew_ns)?;
        let stats = run_can_reader(
            &mut || spec.open(),
            &CanReaderConfig::default(),
            &mut publish,
            ctx.stop_flag(),
        )?;
        // The counters as the reader leaves them (the last status has them).
        mirror_reader_counters(&ctx, &stats);
        Ok(())
    })
}

fn check_source(spec: &CanSourceSpec, text: &str) -> Result<()> {
    spec.check()
        .map_err(|e| anyhow::anyhow!("--source {text:?}: {e}"))
}

/// Runs `driver` on the bus `spec` names and publishes its clouds until the
/// node stops or the log ends.
fn run_device_clouds(
    ctx: &Arc<NodeContext>,
    mut driver: Box<dyn CanDeviceDriver>,
    spec: &CanSourceSpec,
    stream: &str,
    max_skew_ns: u64,
) -> Result<()> {
    let mut out = CloudOut::new(ctx, stream, driver.kind(), max_skew_ns)?;
    ctx.metrics
        .set_label("device.kind".into(), driver.kind().into());
    ctx.metrics
        .set_label("device.clock".into(), spec.clock().name().into());
    // Until the bus opens, nothing vouches for the device.
    report_state(ctx, &DeviceState::Disconnected);
    let mut on_output = |output, driver: &dyn CanDeviceDriver, bus: &BusStats| {
        match output {
            Some(CanDriverOutput::Cloud(cloud)) => publish(ctx, &mut out, &cloud),
            Some(CanDriverOutput::State(state)) => report_state(ctx, &state),
            Some(CanDriverOutput::Identity(pairs)) => report_identity(ctx, pairs),
            Some(CanDriverOutput::Health { ok, detail }) => report_health(ctx, ok, &detail),
            Some(CanDriverOutput::Send(_)) | None => {}
        }
        mirror_counters(ctx, driver, bus);
    };
    let stats = run_can_device(
        &mut || spec.open(),
        driver.as_mut(),
        BackoffConfig::default(),
        &mut on_output,
        ctx.stop_flag(),
    )?;
    mirror_counters(ctx, driver.as_ref(), &stats);
    tracing::info!(
        "{} device stopped: {}; bus: {stats:?}",
        driver.kind(),
        driver.stats()
    );
    Ok(())
}

/// Publishes a cycle's cloud, aged from the arrival of its first frame.
fn publish(ctx: &NodeContext, out: &mut CloudOut<'_>, cloud: &SensorCloud) {
    let first = cloud.received.monotonic_ns;
    out.publish(&cloud.scan, || {
        host_now().monotonic_ns.saturating_sub(first)
    });
    ctx.metrics
        .set(metric::CLOUD_POINTS, cloud.scan.points.len() as f64);
}

fn mirror_counters(ctx: &NodeContext, driver: &dyn CanDeviceDriver, bus: &BusStats) {
    mirror_driver_counters(ctx, driver.stats(), bus.transport.total_errors());
    for (name, n) in driver.named_counters() {
        ctx.metrics.set_named_counter(name, n);
    }
    let m = &ctx.metrics;
    m.set_counter(metric::OPENS, bus.opens);
    m.set_counter(metric::OPEN_FAILURES, bus.open_failures);
    m.set_counter(metric::DISCONNECTS, bus.disconnects);
    m.set_counter(metric::FRAMES_RECEIVED, bus.frames_received);
    m.set_counter(metric::FRAMES_SENT, bus.frames_sent);
    m.set_counter(metric::FRAMES_UNSENT, bus.frames_unsent);
}
