//! The `serial` node for real range sensors (Hokuyo, RPLIDAR, Benewake): a
//! device driver on its port (one thread), and the assembly of its scans into
//! clouds in the robot's frame, published on `cloud/<stream>` (another). The
//! mount's angle, when it comes from a joint, arrives on `joints/<name>`.

use super::device_status::{mirror_driver_counters, report_health, report_identity, report_state};
use super::scan_publisher::CloudOut;
use crate::args::CloudArgs;
use crate::ingest::{host_now, run_device, DevicePortConfig, PortStats};
use crate::runtime::{Arrival, Listener, NodeContext, NodeMetrics, OnMessage};
use crate::transport::unix_ns;
use anyhow::Result;
use shroud_drivers::assembly::{AssembledCloud, CloudAssembler, MountMotion};
use shroud_drivers::device::{DeviceDriver, DeviceState, DeviceStats, DriverOutput, RangeScan};
use shroud_graph::metrics::names::{self as metric, Counter};
use shroud_msg::{check_stamp_skew, JointStateMessage, MessageError};
use std::sync::mpsc::{sync_channel, Receiver, RecvTimeoutError, SyncSender, TrySendError};
use std::sync::Arc;
use std::time::Duration;

/// Scans and joint samples waiting for the assembler.
const ASSEMBLY_QUEUE: usize = 256;

enum Input {
    Scan(RangeScan),
    Joint {
        unix_ns: u64,
        angle: f64,
    },
    /// Publish the cloud being filled (the device went away).
    Flush,
}

/// Runs `driver` on `port` and publishes its clouds until the node stops.
pub(super) fn run_device_clouds(
    ctx: &Arc<NodeContext>,
    driver: &mut dyn DeviceDriver,
    port: &DevicePortConfig,
    clouds: &CloudArgs,
    stream: &str,
    max_skew_ns: u64,
) -> Result<()> {
    let config = clouds.assembly()?;
    let joint = match &config.mount.motion {
        MountMotion::Joint { name } => Some(name.clone()),
        _ => None,
    };
    let assembler = CloudAssembler::new(config)?;
    let mut out = CloudOut::new(ctx, stream, driver.kind(), max_skew_ns)?;
    let (tx, rx) = sync_channel(ASSEMBLY_QUEUE);
    ctx.metrics
        .set_label("device.kind".into(), driver.kind().into());
    std::thread::scope(|scope| -> Result<()> {
        scope.spawn(|| assemble(ctx, rx, assembler, &mut out));
        // The subscriber holds a sender too: it goes before the thread is
        // waited for, so that the assembler sees the channel close.
        let joints = joint
            .map(|name| subscribe_mount_joint(ctx, &clouds.joints, name, tx.clone(), max_skew_ns))
            .transpose();
        let stats = match &joints {
            Err(e) => Err(anyhow::anyhow!("{e:#}")),
            Ok(_) => {
                let mut on_output = |output, device: &DeviceStats, port: &PortStats| {
                    report(ctx, output, &tx);
                    mirror_counters(ctx, device, port);
                };
                run_device(port, driver, &mut on_output, ctx.stop_flag())
                    .map_err(anyhow::Error::from)
            }
        };
        drop(joints);
        drop(tx);
        let stats = stats?;
        mirror_counters(ctx, driver.stats(), &stats);
        tracing::info!(
            "{} device stopped: {}; port: {stats:?}",
            driver.kind(),
            driver.stats()
        );
        Ok(())
    })
}

/// What the driver reported: scans to the assembler, the rest to the status.
fn report(ctx: &NodeContext, output: DriverOutput, tx: &SyncSender<Input>) {
    match output {
        DriverOutput::Scan(scan) => offer(ctx, tx, Input::Scan(scan)),
        DriverOutput::State(state) => {
            // Its scans are not merged with the next connection's (rare, so
            // waiting for room is fine). At a stop the unfinished cloud is
            // not published.
            if state == DeviceState::Disconnected && !ctx.stopping() {
                let _ = tx.send(Input::Flush);
            }
            report_state(ctx, &state);
        }
        DriverOutput::Identity(pairs) => report_identity(ctx, pairs),
        DriverOutput::Health { ok, detail } => report_health(ctx, ok, &detail),
        // The port carries these out itself.
        DriverOutput::Write(_)
        | DriverOutput::SetBaud(_)
        | DriverOutput::SetDtr(_)
        | DriverOutput::FlushInput
        | DriverOutput::Reconnect(_) => {}
    }
}

/// Hands work to the assembler; a full queue drops it, counted.
fn offer(ctx: &NodeContext, tx: &SyncSender<Input>, input: Input) {
    match tx.try_send(input) {
        Ok(()) => {}
        Err(TrySendError::Full(_)) => {
            ctx.metrics.add(metric::DROPPED_BACKLOG, 1);
            tracing::debug!("assembler busy: dropped a scan or joint sample");
        }
        Err(TrySendError::Disconnected(_)) => {}
    }
}

fn mirror_counters(ctx: &NodeContext, device: &DeviceStats, port: &PortStats) {
    // The device's errors plus the joint states refused (counted apart).
    let joints = ctx.metrics.counter(metric::JOINT_SAMPLES_MALFORMED);
    mirror_driver_counters(ctx, device, joints);
    let m = &ctx.metrics;
    m.set_counter(metric::BYTES_READ, device.bytes);
    m.set_counter(metric::OPENS, port.opens);
    m.set_counter(metric::OPEN_FAILURES, port.open_failures);
    m.set_counter(metric::DISCONNECTS, port.disconnects);
    m.set_counter(metric::RECONNECTS, port.reconnects);
    m.set_counter(metric::LINE_SETTING_FAILURES, port.line_setting_failures);
}

/// The assembler's thread: scans and joint samples in, clouds out.
fn assemble(
    ctx: &NodeContext,
    rx: Receiver<Input>,
    mut assembler: CloudAssembler,
    out: &mut CloudOut<'_>,
) {
    let mut clouds = Vec::new();
    loop {
        match rx.recv_timeout(Duration::from_millis(50)) {
            Ok(Input::Scan(scan)) => assembler.push_scan(scan, &mut clouds),
            Ok(Input::Joint { unix_ns, angle }) => {
                assembler.push_joint(unix_ns, angle, &mut clouds)
            }
            Ok(Input::Flush) => assembler.flush(&mut clouds),
            Err(RecvTimeoutError::Timeout) if ctx.stopping() => break,
            Err(RecvTimeoutError::Timeout) => {}
            Err(RecvTimeoutError::Disconnected) => break,
        }
        assembler.expire(host_now(), &mut clouds);
        for cloud in clouds.drain(..) {
            publish(ctx, out, &cloud);
        }
        let s = assembler.stats();
        ctx.metrics.set_counter(metric::CLOUDS, s.clouds);
        ctx.metrics
            .set_counter(metric::INVALID_RAYS, s.invalid_rays);
        ctx.metrics
            .set_counter(metric::MOUNT_ANGLE_MISSING, s.mount_angle_missing);
        ctx.metrics
            .set_counter(metric::JOINT_SAMPLES_REFUSED, s.joint_samples_refused);
        ctx.metrics
            .set_counter(metric::READINGS_LATE_UNBOUNDED, s.readings_late_unbounded);
        ctx.metrics.set_counter(
            metric::READINGS_LATE_BEYOND_BOUND,
            s.readings_late_beyond_bound,
        );
    }
    let unpublished = assembler.pending_points();
    if unpublished > 0 {
        // A window cut short by the stop: not a cloud the window promised.
        ctx.metrics
            .add(metric::POINTS_UNPUBLISHED_AT_STOP, unpublished as u64);
        tracing::info!("{unpublished} points of an unfinished cloud not published at stop");
    }
}

/// Publishes a cloud, aged from the arrival of its first scan's last byte.
fn publish(ctx: &NodeContext, out: &mut CloudOut<'_>, cloud: &AssembledCloud) {
    let first = cloud.first_received.monotonic_ns;
    out.publish_bounded(&cloud.cloud, cloud.position_error_m, || {
        host_now().monotonic_ns.saturating_sub(first)
    });
    let since_last = host_now().since(cloud.last_received);
    ctx.metrics
        .set(metric::LAST_BYTE_TO_PUBLISH_MS, since_last as f64 * 1e-6);
    ctx.metrics
        .set(metric::CLOUD_POINTS, cloud.cloud.points.len() as f64);
    ctx.metrics
        .set(metric::CLOUD_POSITION_ERROR_M, cloud.position_error_m);
}

/// Subscribes to the joint states carrying the mount's angle. Their stamps
/// place rays, so a stamp further than `max_skew_ns` from this node's clock
/// is refused (`clock_skew`); undecodable messages count as
/// `joint_samples_malformed`, messages without the joint as
/// `joint_samples_foreign` (another unit's joints on the same topic).
fn subscribe_mount_joint(
    ctx: &Arc<NodeContext>,
    topic: &str,
    joint: String,
    tx: SyncSender<Input>,
    max_skew_ns: u64,
) -> Result<Listener> {
    let mount = MountJoint {
        ctx: ctx.clone(),
        joint,
        tx,
        max_skew_ns,
    };
    ctx.listen::<JointStateMessage>(topic, mount)
}

/// The mount's joint, from the joint states of its topic.
struct MountJoint {
    ctx: Arc<NodeContext>,
    joint: String,
    tx: SyncSender<Input>,
    max_skew_ns: u64,
}

impl MountJoint {
    /// Counts a refused message, and logs it once, then every 1000th: a topic
    /// at 200 Hz must not flood the log.
    fn refuse(&self, key: &str, counter: Counter, why: &dyn std::fmt::Display) {
        let metrics = &self.ctx.metrics;
        metrics.add(counter, 1);
        let n = metrics.counter(counter);
        if n == 1 || n.is_multiple_of(1000) {
            tracing::warn!(key, "{} ({n} so far): {why}", counter.name);
        }
    }
}

impl OnMessage<JointStateMessage> for MountJoint {
    fn on_message(&self, arrival: &Arrival, msg: JointStateMessage) {
        let Some(i) = msg.names.iter().position(|n| *n == self.joint) else {
            let why = format!("no joint named {:?}", self.joint);
            return self.refuse(&arrival.key, metric::JOINT_SAMPLES_FOREIGN, &why);
        };
        if let Err(skew) = check_stamp_skew(msg.stamp_ns, unix_ns(), self.max_skew_ns) {
            let why = format!("joint state {skew}");
            return self.refuse(&arrival.key, metric::CLOCK_SKEW, &why);
        }
        let joint = Input::Joint {
            unix_ns: msg.stamp_ns,
            angle: msg.positions[i],
        };
        offer(&self.ctx, &self.tx, joint);
    }

    fn on_malformed(&self, _: &NodeMetrics, arrival: &Arrival, error: &MessageError) {
        self.refuse(&arrival.key, metric::JOINT_SAMPLES_MALFORMED, error);
    }
}
