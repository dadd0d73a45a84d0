//! What a device node puts in its status about its device, the same for the
//! serial and the CAN drivers: its state, identity and health as labels, and
//! its driver's counters.

use crate::runtime::NodeContext;
use shroud_drivers::device::{DeviceState, DeviceStats};
use shroud_graph::metrics::names::{self as metric, Counter};

/// Labels that describe the node, not the device on its port.
const KEPT_LABELS: [&str; 3] = ["device.kind", "device.state", "device.clock"];

/// A new state; what the last device said is forgotten when it goes away.
pub(super) fn report_state(ctx: &NodeContext, state: &DeviceState) {
    tracing::info!("device state: {state:?}");
    if matches!(state, DeviceState::Connecting | DeviceState::Disconnected) {
        ctx.metrics.remove_labels("device.", &KEPT_LABELS);
    }
    ctx.metrics
        .set_label("device.state".into(), state.name().into());
}

/// What the device says it is, as `device.<key>` labels.
pub(super) fn report_identity(ctx: &NodeContext, pairs: Vec<(String, String)>) {
    let text: Vec<String> = pairs.iter().map(|(k, v)| format!("{k}={v}")).collect();
    tracing::info!("device identity: {}", text.join(", "));
    for (key, value) in pairs {
        ctx.metrics.set_label(format!("device.{key}"), value);
    }
}

/// The device's own health report, as the `device.health` label; a fault is
/// also counted (`device_unhealthy`) and logged.
pub(super) fn report_health(ctx: &NodeContext, ok: bool, detail: &str) {
    if !ok {
        ctx.metrics.add(metric::DEVICE_UNHEALTHY, 1);
        tracing::warn!("device health: {detail}");
    }
    let text = if ok {
        format!("ok: {detail}")
    } else {
        format!("fault: {detail}")
    };
    ctx.metrics.set_label("device.health".into(), text);
}

/// The driver's counters: scans, handshakes, and every error, invalid
/// reading and note by name. `extra_malformed` is added to the driver's
/// errors in `dropped_malformed` (input refused outside the driver).
pub(super) fn mirror_driver_counters(
    ctx: &NodeContext,
    device: &DeviceStats,
    extra_malformed: u64,
) {
    let m = &ctx.metrics;
    m.set_counter(metric::SCANS, device.scans);
    m.set_counter(metric::COMMANDS, device.commands);
    m.set_counter(metric::HANDSHAKES, device.handshakes);
    m.set_counter(
        metric::DROPPED_MALFORMED,
        device.total_errors() + extra_malformed,
    );
    let all = device.error_counts().chain(device.invalid_reading_counts());
    for (kind, n) in all.chain(device.note_counts()) {
        m.set_counter(Counter::of(kind), n);
    }
}
