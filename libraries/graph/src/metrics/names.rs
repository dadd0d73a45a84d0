//! The names of the counters and gauges nodes publish in their status, one
//! constant each with what it counts and which node kinds publish it: nodes
//! set them through these constants only, and `docs/metrics.md` is this list.

use crate::launch::NodeKind;
use NodeKind::*;

/// A count in a node's status (`counters`): it only grows, or mirrors a count
/// another part keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Counter {
    pub name: &'static str,
    pub meaning: &'static str,
    pub kinds: &'static [NodeKind],
}

/// A measure in a node's status (`gauges`): its latest value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Gauge {
    pub name: &'static str,
    pub meaning: &'static str,
    pub kinds: &'static [NodeKind],
}

impl Counter {
    /// A counter whose name comes from a typed value (a verdict kind, a cause
    /// of loss) rather than from this list.
    pub const fn of(name: &'static str) -> Self {
        Self {
            name,
            meaning: "",
            kinds: &[],
        }
    }
}

const fn counter(name: &'static str, kinds: &'static [NodeKind], meaning: &'static str) -> Counter {
    Counter {
        name,
        meaning,
        kinds,
    }
}

const fn gauge(name: &'static str, kinds: &'static [NodeKind], meaning: &'static str) -> Gauge {
    Gauge {
        name,
        meaning,
        kinds,
    }
}

pub const RECEIVED: Counter = counter(
    "received",
    &[Fit, Smooth, Blend, Record],
    "messages taken from the node's inbox to be used",
);
pub const PUBLISHED: Counter = counter(
    "published",
    &[
        Scanner, Fit, Guard, Arm, Serial, Can, Blend, Smooth, Replay, Dashboard, Foxglove, Ros2,
    ],
    "messages handed to zenoh (a verdict, once its put returned)",
);
pub const PUBLISH_ERRORS: Counter = counter(
    "publish_errors",
    &[
        Scanner, Fit, Guard, Arm, Serial, Can, Blend, Smooth, Replay, Dashboard, Foxglove, Ros2,
    ],
    "messages that could not be encoded or that zenoh refused to publish (logged)",
);
pub const DROPPED_MALFORMED: Counter = counter(
    "dropped_malformed",
    &[
        Fit, Guard, Arm, Serial, Can, Blend, Smooth, Dashboard, Foxglove, Ros2,
    ],
    "messages that could not be decoded or used (logged with their key); for serial and can nodes, the driver's errors plus the transport's (a serial mount's undecodable joint states included)",
);
pub const DROPPED_BACKLOG: Counter = counter(
    "dropped_backlog",
    &[Fit, Smooth, Blend, Serial, Ros2],
    "messages dropped because the node's queue was full (the fit, smooth and blend nodes keep the newest; a serial node's assembler and a ros2 node's cloud input drop the new one)",
);
pub const SEQUENCE_GAPS: Counter = counter(
    "sequence_gaps",
    &[Fit],
    "clouds missing from their source's sequence before this node decoded them",
);
pub const CLOCK_OFFSET: Counter = counter(
    "clock_offset",
    &[Fit, Guard],
    "messages whose publication stamp lies further in the future than the clock offset bound allows (dropped)",
);
pub const CLOCK_SKEW: Counter = counter(
    "clock_skew",
    &[Guard, Serial, Can],
    "stamps further than `max_skew` from this node's clock: a guard's view or a mount's joint state is refused; a sensor's own cloud is published and only counted",
);
pub const NO_PUBLISH_STAMP: Counter = counter(
    "no_publish_stamp",
    &[Fit, Guard],
    "messages without a zenoh timestamp: their transit cannot be counted (dropped)",
);
pub const FIT_ERRORS: Counter = counter(
    "fit_errors",
    &[Fit, Smooth],
    "clouds the fitter could not fit (logged)",
);
pub const SECTORS_PUBLISHED: Counter = counter(
    "sectors_published",
    &[Fit],
    "sector surrogates published (with `sectors`)",
);
pub const SECTORS_UNSTATED: Counter = counter(
    "sectors_unstated",
    &[Fit],
    "clouds whose sectors could not be fitted: the cloud states no field of view (logged once)",
);
pub const SECTOR_ERRORS: Counter = counter(
    "sector_errors",
    &[Fit],
    "sectors not fitted: no room in the field of view, or the fitter refused its points (logged once per sector)",
);
pub const ROS2_RECEIVED: Counter = counter(
    "ros2_received",
    &[Ros2],
    "ROS 2 samples received (clouds and joint states), before any check",
);
pub const ROS2_BAD_ATTACHMENT: Counter = counter(
    "ros2_bad_attachment",
    &[Ros2],
    "ROS 2 samples without rmw_zenoh's 33-byte attachment, or with another (dropped, logged)",
);
pub const ROS2_EMPTY_RAYS: Counter = counter(
    "ros2_empty_rays",
    &[Ros2],
    "points of ROS 2 clouds without a return (not finite): those in groups holding a 2 x 2 block are stated as unseen cones",
);
pub const ROS2_UNKNOWN_JOINTS: Counter = counter(
    "ros2_unknown_joints",
    &[Ros2],
    "joint values of ROS 2 joint states whose names the arm has not (dropped; each name logged once)",
);
pub const ROS2_SENT: Counter = counter(
    "ros2_sent",
    &[Ros2],
    "ROS 2 messages sent (verdicts, speed scales, markers, clouds, transforms)",
);
pub const POINTS: Gauge = gauge(
    "points",
    &[Scanner, Fit, Blend, Ros2],
    "points of the latest cloud",
);
pub const TRANSIT_MS: Gauge = gauge(
    "transit_ms",
    &[Fit],
    "the latest cloud's time from its stamp to its arrival here",
);
pub const QUEUE_WAIT_MS: Gauge = gauge(
    "queue_wait_ms",
    &[Fit],
    "the latest cloud's wait in the inbox",
);
pub const DECODE_MS: Gauge = gauge("decode_ms", &[Fit], "the latest cloud's decoding");
pub const PUBLISH_MS: Gauge = gauge(
    "publish_ms",
    &[Fit],
    "the latest surrogate's encoding and publication",
);
pub const FIT_P50_MS: Gauge = gauge(
    "fit_p50_ms",
    &[Fit],
    "median fit time over the last 256 clouds",
);
pub const FIT_P99_MS: Gauge = gauge(
    "fit_p99_ms",
    &[Fit],
    "99th percentile fit time over the last 256 clouds",
);
pub const LATENCY_P50_MS: Gauge = gauge(
    "latency_p50_ms",
    &[Fit],
    "median of the surrogates' ages at publication (`pipeline_ns`)",
);
pub const LATENCY_P99_MS: Gauge = gauge(
    "latency_p99_ms",
    &[Fit],
    "99th percentile of the surrogates' ages at publication",
);
pub const SURROGATES: Counter = counter("surrogates", &[Guard], "surrogates accepted as views");
pub const STOPS: Counter = counter(
    "stops",
    &[Guard],
    "verdicts that stop the arm (every kind but clear)",
);
pub const CHECK_US: Gauge = gauge("check_us", &[Guard], "the latest decision's time");
pub const MIN_CLEARANCE: Gauge = gauge(
    "min_clearance",
    &[Guard],
    "the latest decision's smallest clearance over the links",
);
pub const SURROGATE_AGE_MS: Gauge = gauge(
    "surrogate_age_ms",
    &[Guard],
    "age of the oldest view behind the latest decision",
);
pub const SPEED_SCALE: Gauge = gauge(
    "speed_scale",
    &[Guard, Arm],
    "the latest verdict's speed scale (guard: published; arm: applied), 0 to 1",
);
pub const HALTS: Counter = counter("halts", &[Arm], "times the arm halted");
pub const VERDICTS: Counter = counter(
    "verdicts",
    &[Arm],
    "verdicts applied (every stop, and a clear for a remembered joint state that is newer than the last stop)",
);
pub const VERDICTS_SUPERSEDED: Counter = counter(
    "verdicts_superseded",
    &[Arm],
    "clear verdicts for a joint state sent before the last stop arrived (ignored)",
);
pub const VERDICTS_UNKNOWN: Counter = counter(
    "verdicts_unknown",
    &[Arm],
    "clear verdicts for a joint state this arm does not remember (ignored)",
);
pub const TRAJECTORY_S: Gauge = gauge("trajectory_s", &[Arm], "time along the trajectory");
pub const HALTED: Gauge = gauge("halted", &[Arm], "1 while the arm is halted, else 0");
pub const HALTED_S: Gauge = gauge("halted_s", &[Arm], "total time halted");
pub const HALT_CURRENT_S: Gauge = gauge("halt_current_s", &[Arm], "time in the current halt");
pub const APPLIED: Counter = counter("applied", &[Blend], "blend commands applied");
pub const BLEND_ERRORS: Counter = counter("blend_errors", &[Blend], "blends that failed (logged)");
pub const PARENT_REFUSED: Counter =
    counter("parent_refused", &[Blend], "parent clouds refused (logged)");
pub const SUPERSEDED: Counter = counter(
    "superseded",
    &[Blend],
    "commands replaced by a newer one before they were applied",
);
pub const BLEND_MS: Gauge = gauge("blend_ms", &[Blend], "the latest blend's time");
pub const TRANSITION_POINTS: Gauge = gauge(
    "transition_points",
    &[Blend],
    "points of the latest blend's transition",
);
pub const CENTRES: Gauge = gauge("centres", &[Blend], "RBF centres of the latest blend");
pub const COMMITS: Gauge = gauge("commits", &[Blend], "parts committed into the parent");
pub const POINTS_OUTSIDE: Counter = counter(
    "points_outside",
    &[Smooth],
    "points outside the fit's domain (skipped)",
);
pub const FIT_MS: Gauge = gauge("fit_ms", &[Smooth], "the latest fit's time");
pub const FUNCTIONS: Gauge = gauge("functions", &[Smooth], "basis functions of the fit");
pub const RMSE: Gauge = gauge("rmse", &[Smooth], "the latest fit's root mean square error");
pub const LATENCY_MS: Gauge = gauge(
    "latency_ms",
    &[Smooth],
    "the latest cloud's age when its fit was done",
);
pub const MISSED_TICKS: Counter = counter(
    "missed_ticks",
    &[Scanner],
    "frames not published on time because the last one took too long",
);
pub const SENT_SHM: Counter = counter(
    "sent_shm",
    &[Scanner, Serial, Can, Blend],
    "clouds sent through shared memory",
);
pub const SENT_COPY: Counter = counter(
    "sent_copy",
    &[Scanner, Serial, Can, Blend],
    "clouds sent by copy (below 64 KiB, with --shm off, or with the segment full)",
);
pub const ZENOH_DROPPED_ACCESS_CONTROL: Counter = counter(
    "zenoh_dropped_access_control",
    &NodeKind::ALL,
    "messages zenoh's access control refused in this process (a router's: publications by a host that does not own the stream; docs/multi-host.md); also in the router's and every launcher's status",
);
pub const ZENOH_DROPPED_CONGESTION: Counter = counter(
    "zenoh_dropped_congestion",
    &NodeKind::ALL,
    "messages zenoh dropped on a congested link (publications with congestion control Drop); also in the router's and every launcher's status",
);
pub const OPENS: Counter = counter("opens", &[Serial, Can], "times the device was opened");
pub const OPEN_FAILURES: Counter = counter(
    "open_failures",
    &[Serial, Can],
    "failed attempts to open the device",
);
pub const DISCONNECTS: Counter =
    counter("disconnects", &[Serial, Can], "times the device went away");
pub const RECONNECTS: Counter = counter("reconnects", &[Serial], "reconnects the driver asked for");
pub const BYTES_READ: Counter = counter("bytes_read", &[Serial], "bytes read from the port");
pub const LINE_SETTING_FAILURES: Counter = counter(
    "line_setting_failures",
    &[Serial],
    "failures to set the serial line (DTR, baud rate, input flush)",
);
pub const CLOUDS: Counter = counter("clouds", &[Serial], "clouds assembled");
pub const INVALID_RAYS: Counter = counter(
    "invalid_rays",
    &[Serial],
    "rays the device marked invalid (not placed)",
);
pub const MOUNT_ANGLE_MISSING: Counter = counter(
    "mount_angle_missing",
    &[Serial],
    "scans dropped because no mount angle places them",
);
pub const JOINT_SAMPLES_REFUSED: Counter = counter(
    "joint_samples_refused",
    &[Serial],
    "joint states refused as a mount angle (a non-finite angle, or a stamp not later than the last)",
);
pub const JOINT_SAMPLES_MALFORMED: Counter = counter(
    "joint_samples_malformed",
    &[Serial],
    "joint states that could not be decoded",
);
pub const JOINT_SAMPLES_FOREIGN: Counter = counter(
    "joint_samples_foreign",
    &[Serial],
    "joint states without the mount's joint (another unit's, ignored)",
);
pub const POINTS_UNPUBLISHED_AT_STOP: Counter = counter(
    "points_unpublished_at_stop",
    &[Serial],
    "points of a cloud cut short by the node's stop",
);
pub const READINGS_LATE_UNBOUNDED: Counter = counter(
    "readings_late_unbounded",
    &[Serial],
    "readings whose lateness has no bound (dropped)",
);
pub const READINGS_LATE_BEYOND_BOUND: Counter = counter(
    "readings_late_beyond_bound",
    &[Serial],
    "readings whose position error bound exceeds `max_position_error` (dropped)",
);
pub const DEVICE_UNHEALTHY: Counter = counter(
    "device_unhealthy",
    &[Serial, Can],
    "reports of an unhealthy device",
);
pub const COMMANDS: Counter = counter("commands", &[Serial, Can], "commands sent to the device");
pub const SCANS: Counter = counter("scans", &[Serial, Can], "scans decoded");
pub const HANDSHAKES: Counter = counter(
    "handshakes",
    &[Serial, Can],
    "handshakes completed with the device",
);
pub const CLOUD_POINTS: Gauge = gauge("cloud_points", &[Serial, Can], "points of the latest cloud");
pub const CLOUD_POSITION_ERROR_M: Gauge = gauge(
    "cloud_position_error_m",
    &[Serial],
    "the latest cloud's largest position error bound",
);
pub const LAST_BYTE_TO_PUBLISH_MS: Gauge = gauge(
    "last_byte_to_publish_ms",
    &[Serial],
    "time from the latest cloud's last byte to its publication",
);
pub const FRAMES_RECEIVED: Counter = counter("frames_received", &[Can], "CAN frames received");
pub const FRAMES_SENT: Counter = counter(
    "frames_sent",
    &[Can, Dashboard],
    "frames sent (to the CAN bus; to browsers)",
);
pub const FRAMES_UNSENT: Counter =
    counter("frames_unsent", &[Can], "CAN frames that could not be sent");
pub const BYTES_DROPPED: Counter = counter(
    "bytes_dropped",
    &[DeviceSim],
    "bytes lost (in a stall, or beyond the device's buffer or the host's backlog)",
);
pub const BYTES_FROM_HOST: Counter = counter(
    "bytes_from_host",
    &[DeviceSim],
    "bytes the host sent to the emulator",
);
pub const BYTES_GARBLED: Counter = counter(
    "bytes_garbled",
    &[DeviceSim],
    "bytes garbled by a baud-rate mismatch",
);
pub const BYTES_TO_HOST: Counter = counter(
    "bytes_to_host",
    &[DeviceSim],
    "bytes the emulator sent to the host",
);
pub const UNPLUGS: Counter = counter("unplugs", &[DeviceSim], "simulated unplugs");
pub const BROWSERS_CONNECTED: Counter = counter(
    "browsers_connected",
    &[Dashboard],
    "browsers that connected",
);
pub const BROWSERS: Gauge = gauge("browsers", &[Dashboard], "browsers connected now");
pub const PACED_SUPERSEDED: Counter = counter(
    "paced_superseded",
    &[Dashboard, Foxglove, Ros2],
    "paced samples replaced by a newer one before they were sent",
);
pub const SAMPLES_SUPERSEDED: Counter = counter(
    "samples_superseded",
    &[Dashboard, Foxglove],
    "samples replaced by a newer one before they were decoded",
);
pub const FRAMES_SUPERSEDED: Counter = counter(
    "frames_superseded",
    &[Dashboard],
    "frames for a browser replaced by a newer one before the browser took them",
);
pub const BLEND_COMMANDS: Counter = counter(
    "blend_commands",
    &[Dashboard, Foxglove],
    "blend commands sent from the page or panel",
);
pub const CLIENTS_CONNECTED: Counter =
    counter("clients_connected", &[Foxglove], "clients that connected");
pub const CLIENTS: Gauge = gauge("clients", &[Foxglove], "clients connected now");
pub const CLIENT_MESSAGES: Counter = counter(
    "client_messages",
    &[Foxglove],
    "messages received from clients",
);
pub const BLEND_REFUSED: Counter = counter(
    "blend_refused",
    &[Foxglove],
    "client blend commands refused (logged)",
);
pub const MESSAGES_LOGGED: Counter = counter(
    "messages_logged",
    &[Foxglove],
    "messages logged to the Foxglove channels",
);
pub const WRITTEN: Counter = counter("written", &[Record], "messages written to the recording");
pub const BYTES_WRITTEN: Counter =
    counter("bytes_written", &[Record], "bytes written to the recording");
pub const VIEWS_WRITTEN: Counter =
    counter("views_written", &[Record], "Foxglove view messages written");
pub const VIEWS_FAILED: Counter = counter(
    "views_failed",
    &[Record],
    "Foxglove view messages that could not be made",
);
pub const VIEWS_PACED: Counter = counter(
    "views_paced",
    &[Record],
    "Foxglove view messages skipped by the pacing rate",
);
pub const QUEUE_MB: Gauge = gauge(
    "queue_mb",
    &[Record],
    "megabytes waiting in the write queue",
);
pub const PASS: Gauge = gauge(
    "pass",
    &[Replay],
    "the index of the current pass through the file (0 first; with `loop`)",
);

/// Every counter above, in the order of `docs/metrics.md`.
pub const COUNTERS: &[Counter] = &[
    RECEIVED,
    PUBLISHED,
    PUBLISH_ERRORS,
    DROPPED_MALFORMED,
    DROPPED_BACKLOG,
    SEQUENCE_GAPS,
    CLOCK_OFFSET,
    CLOCK_SKEW,
    NO_PUBLISH_STAMP,
    FIT_ERRORS,
    SECTORS_PUBLISHED,
    SECTORS_UNSTATED,
    SECTOR_ERRORS,
    ROS2_RECEIVED,
    ROS2_BAD_ATTACHMENT,
    ROS2_EMPTY_RAYS,
    ROS2_UNKNOWN_JOINTS,
    ROS2_SENT,
    SURROGATES,
    STOPS,
    HALTS,
    VERDICTS,
    VERDICTS_SUPERSEDED,
    VERDICTS_UNKNOWN,
    APPLIED,
    BLEND_ERRORS,
    PARENT_REFUSED,
    SUPERSEDED,
    POINTS_OUTSIDE,
    MISSED_TICKS,
    SENT_SHM,
    SENT_COPY,
    OPENS,
    OPEN_FAILURES,
    DISCONNECTS,
    RECONNECTS,
    BYTES_READ,
    LINE_SETTING_FAILURES,
    CLOUDS,
    INVALID_RAYS,
    MOUNT_ANGLE_MISSING,
    JOINT_SAMPLES_REFUSED,
    JOINT_SAMPLES_MALFORMED,
    JOINT_SAMPLES_FOREIGN,
    POINTS_UNPUBLISHED_AT_STOP,
    READINGS_LATE_UNBOUNDED,
    READINGS_LATE_BEYOND_BOUND,
    DEVICE_UNHEALTHY,
    COMMANDS,
    SCANS,
    HANDSHAKES,
    FRAMES_RECEIVED,
    FRAMES_SENT,
    FRAMES_UNSENT,
    BYTES_DROPPED,
    BYTES_FROM_HOST,
    BYTES_GARBLED,
    BYTES_TO_HOST,
    UNPLUGS,
    BROWSERS_CONNECTED,
    PACED_SUPERSEDED,
    SAMPLES_SUPERSEDED,
    FRAMES_SUPERSEDED,
    BLEND_COMMANDS,
    CLIENTS_CONNECTED,
    CLIENT_MESSAGES,
    BLEND_REFUSED,
    MESSAGES_LOGGED,
    WRITTEN,
    BYTES_WRITTEN,
    VIEWS_WRITTEN,
    VIEWS_FAILED,
    VIEWS_PACED,
    ZENOH_DROPPED_ACCESS_CONTROL,
    ZENOH_DROPPED_CONGESTION,
];

/// Every gauge above.
pub const GAUGES: &[Gauge] = &[
    POINTS,
    TRANSIT_MS,
    QUEUE_WAIT_MS,
    DECODE_MS,
    PUBLISH_MS,
    FIT_P50_MS,
    FIT_P99_MS,
    LATENCY_P50_MS,
    LATENCY_P99_MS,
    CHECK_US,
    MIN_CLEARANCE,
    SURROGATE_AGE_MS,
    SPEED_SCALE,
    TRAJECTORY_S,
    HALTED,
    HALTED_S,
    HALT_CURRENT_S,
    BLEND_MS,
    TRANSITION_POINTS,
    CENTRES,
    COMMITS,
    FIT_MS,
    FUNCTIONS,
    RMSE,
    LATENCY_MS,
    CLOUD_POINTS,
    CLOUD_POSITION_ERROR_M,
    LAST_BYTE_TO_PUBLISH_MS,
    BROWSERS,
    CLIENTS,
    QUEUE_MB,
    PASS,
];

/// The counters and gauges a node kind publishes (besides those named from
/// typed values, such as the arm's `halts_<verdict>`).
pub fn of_kind(kind: NodeKind) -> (Vec<&'static Counter>, Vec<&'static Gauge>) {
    (
        COUNTERS
            .iter()
            .filter(|c| c.kinds.contains(&kind))
            .collect(),
        GAUGES.iter().filter(|g| g.kinds.contains(&kind)).collect(),
    )
}

/// `docs/metrics.md`'s table: per node kind, its counters and gauges.
pub fn table_markdown() -> String {
    let mut out = String::from("| node kind | counters | gauges |\n|---|---|---|\n");
    for kind in NodeKind::ALL {
        let (counters, gauges) = of_kind(kind);
        let names = |list: Vec<&'static str>| {
            list.iter()
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        out.push_str(&format!(
            "| `{kind}` | {} | {} |\n",
            names(counters.iter().map(|c| c.name).collect()),
            names(gauges.iter().map(|g| g.name).collect())
        ));
    }
    out.push_str("\n| name | kind | meaning |\n|---|---|---|\n");
    for c in COUNTERS {
        out.push_str(&format!("| `{}` | counter | {} |\n", c.name, c.meaning));
    }
    for g in GAUGES {
        out.push_str(&format!("| `{}` | gauge | {} |\n", g.name, g.meaning));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_each_is_published_by_some_kind() {
        let mut names: Vec<&str> = COUNTERS.iter().map(|c| c.name).collect();
        names.extend(GAUGES.iter().map(|g| g.name));
        let count = names.len();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), count, "a name is listed twice");
        assert!(COUNTERS
            .iter()
            .all(|c| !c.kinds.is_empty() && !c.meaning.is_empty()));
        assert!(GAUGES
            .iter()
            .all(|g| !g.kinds.is_empty() && !g.meaning.is_empty()));
    }

    #[test]
    fn the_docs_list_is_this_list() {
        let docs = include_str!("../../../../docs/metrics.md");
        let table = table_markdown();
        assert!(
            docs.contains(&table),
            "docs/metrics.md must hold this table:\n{table}"
        );
    }
}
