//! The Hokuyo SCIP 2.0 driver: a sans-I/O state machine implementing
//! [`DeviceDriver`]. This file holds the driver's state, the byte plumbing
//! (lines, replies), command sending, timeouts and the way out (reconnect,
//! recovery); `handshake.rs` and `streaming.rs` handle the replies.

use std::time::Duration;

use super::clock::{ClockSync, DeviceClock, ScanStamper};
use super::command::{Command, ScanRequest};
use super::config::ScipConfig;
use super::line::{LineEvent, LineSplitter};
use super::params::ScipGeometry;
use super::rays::ScanPlan;
use super::reply::{Assembled, Reply, ReplyAssembler};
use crate::device::{DeviceDriver, DeviceState, DeviceStats, DriverOutput, HostTime};

/// How long the sensor gets to switch its bit rate after `SS` before the
/// driver checks it with `QT` (urg_c `change_sensor_baudrate()` waits its
/// 140 ms `MAX_TIMEOUT`).
pub(super) const BAUD_SETTLE_NS: u64 = 150_000_000;

/// `QT` + flush rounds tried on a sensor that keeps streaming.
pub(super) const MAX_DRAINS: u8 = 3;

/// Consecutive hardware-trouble replies (status 50..97) that trigger a reboot.
pub(super) const HARDWARE_FAULT_LIMIT: u32 = 3;

/// Where the driver is; each waiting phase has a deadline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Phase {
    /// Not connected, or shut down.
    Idle,
    /// `QT` sent at probe rate `baud` (an index; 0 on USB).
    Probe { baud: usize },
    /// The sensor was streaming: `QT` sent and input flushed; waiting for the
    /// `QT` reply before probing again.
    Drain { baud: usize },
    /// `SCIP2.0` sent to a SCIP 1.1 sensor.
    Scip2 { baud: usize },
    /// `TM2` sent to a sensor left in time-adjust mode.
    LeaveTimeMode { baud: usize },
    /// `SS` sent.
    ChangeBaud { target: u32 },
    /// Port switched to `target`; waiting for the sensor to follow.
    BaudSettle { target: u32 },
    /// `QT` sent at the new rate.
    ConfirmBaud { target: u32 },
    /// `VV` sent.
    Version,
    /// `PP` sent.
    Params,
    /// `II` sent.
    Info,
    /// `TM0` sent.
    TimeEnter,
    /// `TM1` number `done + 1` sent.
    TimeRead { done: u8 },
    /// `TM2` sent after the round trips.
    TimeLeave,
    /// `BM` sent (before `GD`/`GE`/`HD`/`HE`).
    LaserOn,
    /// `MD`/`MS`/`ME`/`ND`/`NE` sent, waiting for its `00` acknowledgement.
    StreamStart,
    /// Receiving streamed scans.
    Streaming,
    /// `GD`/`GS`/`GE`/`HD`/`HE` sent, waiting for the scan.
    Polling,
    /// `RB` number `sent` written.
    Reboot { sent: u8 },
}

/// What the driver learns about the sensor during one connection; forgotten
/// on every connect.
#[derive(Debug, Default)]
pub(super) struct Session {
    /// The current RS-232 rate (`None` on USB).
    pub baud: Option<u32>,
    pub drains: u8,
    pub identity: Vec<(String, String)>,
    pub geometry: Option<ScipGeometry>,
    pub request: Option<ScanRequest>,
    pub plan: Option<ScanPlan>,
    /// Set when the sensor rejected the intensity command.
    pub intensity_note: Option<String>,
    /// Set when the sensor rejected the multi-echo command.
    pub multiecho_note: Option<String>,
    pub clock: DeviceClock,
    pub sync: ClockSync,
    pub stamper: ScanStamper,
    pub stream_timeout_ns: u64,
    pub hardware_faults: u32,
    /// `Streaming` announced (and the handshake counted).
    pub announced: bool,
    /// Why the driver is rebooting the sensor.
    pub recovery: String,
    /// The timestamp of the last polled scan: a poll answered before the
    /// next revolution completes gets the same scan again.
    pub last_polled_ms: Option<u32>,
}

/// The Hokuyo SCIP 2.0 driver (URG-04LX and other SCIP 2.0 sensors over USB
/// or RS-232), device kind `hokuyo`.
///
/// On every [`connect`](DeviceDriver::connect) it flushes the input and
/// probes with `QT` (RS-232: at each configured rate, `reply_timeout` each);
/// a bare `E` answer gets `SCIP2.0`, `0E` gets `TM2`, a reply that is not the
/// `QT` echo (a stream left running) gets `QT` + flush and a new probe once
/// the `QT` reply is in (at most 3 times). Then `SS` (RS-232 target rate),
/// `VV`, `PP`, `II` (→ [`DriverOutput::Health`] from `STAT`), `TM0`, `TM1` x
/// `tm_round_trips`, `TM2`, `BM` for polled commands, and the measurement
/// command (`MD`, `MS`, `ME`, `ND`, `NE` streamed; `GD`, `GE`, `HD`, `HE`
/// polled). A refused multi-echo command falls back to its single-echo twin,
/// a refused intensity command to its range-only twin (each counted, and
/// asked again on the next connect). When it runs,
/// [`DriverOutput::Identity`] carries every `VV`/`PP`/`II` pair plus
/// `scan_command`, `steps`, `cluster`, `intensity`, `multiecho`, `clock_sync`
/// and (RS-232) `baud`. A sensor that does not answer a handshake command within
/// `reply_timeout`, or a stream without a delivered scan for the stream
/// timeout, ends in [`DriverOutput::Reconnect`] naming what was awaited; `0L`
/// or 3 hardware-trouble replies in a row reboot the sensor (`RB` twice) and
/// then reconnect. Error kinds counted: `bad_checksum`, `malformed_reply`,
/// `unexpected_echo`, `oversize_line`, `oversize_reply`, `incomplete_scan`,
/// `malformed_multiecho`, `garbage`, `timeout`, `clock_mismatch`,
/// `intensity_unsupported`, `multiecho_unsupported`, `device_resumed` and
/// `device_error_*` by status class (see
/// [`StatusClass::error_kind`](super::StatusClass::error_kind)).
#[derive(Debug)]
pub struct ScipDriver {
    pub(super) config: ScipConfig,
    pub(super) bauds: Option<Vec<u32>>,
    pub(super) state: DeviceState,
    pub(super) stats: DeviceStats,
    lines: LineSplitter,
    replies: ReplyAssembler,
    pub(super) phase: Phase,
    deadline_ns: u64,
    /// When the awaited command was written (for `TM1` round trips).
    pub(super) sent_at: HostTime,
    /// The echo the awaited reply must carry.
    pub(super) expected_echo: Vec<u8>,
    /// Input was flushed during the current `receive`: drop the rest.
    flushed: bool,
    pub(super) session: Session,
    pub(super) sequence: u32,
}

impl ScipDriver {
    /// A driver for `config`; out-of-range values are clamped (cluster 1..=99,
    /// interval 0..=9).
    pub fn new(mut config: ScipConfig) -> Self {
        config.cluster = config.cluster.clamp(1, 99);
        config.interval = config.interval.min(9);
        Self {
            bauds: config.probe_bauds(),
            config,
            state: DeviceState::Disconnected,
            stats: DeviceStats::default(),
            lines: LineSplitter::new(),
            replies: ReplyAssembler::new(),
            phase: Phase::Idle,
            deadline_ns: 0,
            sent_at: HostTime::default(),
            expected_echo: Vec::new(),
            flushed: false,
            session: Session::default(),
            sequence: 0,
        }
    }

    /// The configuration in use (after clamping).
    pub fn config(&self) -> &ScipConfig {
        &self.config
    }

    /// The sensor's geometry from `PP`, once read on this connection.
    pub fn geometry(&self) -> Option<&ScipGeometry> {
        self.session.geometry.as_ref()
    }

    /// Writes `command`, counts it, and waits for its reply in `phase` for the
    /// reply timeout.
    pub(super) fn send(
        &mut self,
        command: &Command,
        phase: Phase,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        let bytes = match command.to_bytes(None) {
            Ok(bytes) => bytes,
            Err(e) => return self.reconnect(format!("cannot build {command:?}: {e}"), out),
        };
        self.expected_echo = bytes.strip_suffix(b"\n").unwrap_or(&bytes).to_vec();
        out.push(DriverOutput::Write(bytes));
        self.stats.commands += 1;
        self.sent_at = now;
        self.wait(phase, duration_ns(self.config.reply_timeout), now);
    }

    /// Enters `phase` with a deadline `timeout_ns` from `now`.
    pub(super) fn wait(&mut self, phase: Phase, timeout_ns: u64, now: HostTime) {
        self.phase = phase;
        self.deadline_ns = now.monotonic_ns.saturating_add(timeout_ns);
    }

    /// Asks the port to drop its buffered input, and drops ours.
    pub(super) fn flush_input(&mut self, out: &mut Vec<DriverOutput>) {
        out.push(DriverOutput::FlushInput);
        self.lines.reset();
        self.replies.reset();
        self.flushed = true;
    }

    pub(super) fn set_state(&mut self, state: DeviceState, out: &mut Vec<DriverOutput>) {
        if self.state != state {
            self.state = state.clone();
            out.push(DriverOutput::State(state));
        }
    }

    /// Gives up on the link: the node reopens the port and calls `connect`.
    pub(super) fn reconnect(&mut self, reason: String, out: &mut Vec<DriverOutput>) {
        self.phase = Phase::Idle;
        self.stats.reconnects += 1;
        self.set_state(DeviceState::Disconnected, out);
        out.push(DriverOutput::Reconnect(reason));
    }

    /// The sensor reported a fault only a reboot clears: `RB` twice, then
    /// reconnect (urg_c `urg_reboot()`; seqsense/urg_stamped `cbRB`: the
    /// first `RB` answers `01`, the second, within 1 s, `00`).
    pub(super) fn recover(&mut self, reason: String, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.set_state(DeviceState::Recovering(reason.clone()), out);
        out.push(DriverOutput::Health {
            ok: false,
            detail: reason.clone(),
        });
        self.session.recovery = reason;
        self.send(&Command::Rb, Phase::Reboot { sent: 1 }, now, out);
    }

    /// Whether an echo is that of the current scan request.
    pub(super) fn is_scan_echo(&self, echo: &[u8]) -> bool {
        self.session
            .request
            .as_ref()
            .is_some_and(|r| r.matches_echo(echo, None))
    }

    fn on_reply(&mut self, reply: Reply, now: HostTime, out: &mut Vec<DriverOutput>) {
        if !reply.is_printable() {
            self.stats.count("garbage");
            return;
        }
        if reply.damaged {
            let kind = if self.is_scan_echo(&reply.echo) {
                "incomplete_scan"
            } else {
                "malformed_reply"
            };
            self.stats.count(kind);
            return;
        }
        match self.phase {
            Phase::Idle | Phase::BaudSettle { .. } => {}
            Phase::Probe { baud } => self.on_probe_reply(baud, &reply, now, out),
            Phase::Drain { baud } => self.on_drain_reply(baud, &reply, now, out),
            Phase::Reboot { sent } => self.on_reboot_reply(sent, &reply, now, out),
            Phase::StreamStart | Phase::Streaming | Phase::Polling => {
                self.on_scan_reply(&reply, now, out)
            }
            step => self.on_step_reply(step, &reply, now, out),
        }
    }

    /// A reply whose echo is not the awaited one: a late `QT` answer is
    /// expected after draining and ignored, anything else is counted.
    pub(super) fn on_foreign_reply(&mut self, reply: &Reply) {
        if reply.echo != b"QT" {
            self.stats.count("unexpected_echo");
        }
    }

    fn on_deadline(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        match self.phase {
            Phase::Idle => {}
            Phase::BaudSettle { target } => {
                self.send(&Command::Qt, Phase::ConfirmBaud { target }, now, out)
            }
            Phase::Probe { baud } => {
                self.stats.count("timeout");
                self.next_probe(baud, now, out);
            }
            Phase::Drain { baud } => {
                self.stats.count("timeout");
                self.send(&Command::Qt, Phase::Probe { baud }, now, out);
            }
            Phase::Reboot { sent } => self.after_reboot_reply(sent, now, out),
            Phase::Streaming => {
                self.stats.count("timeout");
                let ms = self.session.stream_timeout_ns / 1_000_000;
                self.reconnect(format!("no scan from the sensor for {ms} ms"), out);
            }
            _ => {
                self.stats.count("timeout");
                let ms = self.deadline_wait_ms();
                let what = String::from_utf8_lossy(&self.expected_echo).into_owned();
                self.reconnect(format!("no reply to {what} within {ms} ms"), out);
            }
        }
    }

    fn deadline_wait_ms(&self) -> u64 {
        match self.phase {
            Phase::Polling => self.session.stream_timeout_ns / 1_000_000,
            _ => duration_ns(self.config.reply_timeout) / 1_000_000,
        }
    }
}

/// A duration in nanoseconds, saturated.
pub(super) fn duration_ns(d: Duration) -> u64 {
    u64::try_from(d.as_nanos()).unwrap_or(u64::MAX)
}

impl DeviceDriver for ScipDriver {
    fn kind(&self) -> &'static str {
        "hokuyo"
    }

    fn connect(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.session = Session::default();
        self.state = DeviceState::Disconnected;
        self.set_state(DeviceState::Connecting, out);
        self.flush_input(out);
        self.start_probe(0, now, out);
    }

    fn receive(&mut self, bytes: &[u8], now: HostTime, out: &mut Vec<DriverOutput>) {
        self.stats.bytes += bytes.len() as u64;
        self.flushed = false;
        for &byte in bytes {
            if self.phase == Phase::Idle || self.flushed {
                break;
            }
            let Some(event) = self.lines.push(byte) else {
                continue;
            };
            if event == LineEvent::Oversize {
                self.stats.count("oversize_line");
            }
            match self.replies.push(event) {
                Some(Assembled::Reply(reply)) => self.on_reply(reply, now, out),
                Some(Assembled::Overflow) => self.stats.count("oversize_reply"),
                None => {}
            }
        }
    }

    fn poll(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        if self.phase != Phase::Idle && now.monotonic_ns >= self.deadline_ns {
            self.on_deadline(now, out);
        }
    }

    fn shutdown(&mut self, out: &mut Vec<DriverOutput>) {
        out.push(DriverOutput::Write(b"QT\n".to_vec()));
        self.stats.commands += 1;
        self.phase = Phase::Idle;
        self.set_state(DeviceState::Disconnected, out);
    }

    fn state(&self) -> &DeviceState {
        &self.state
    }

    fn stats(&self) -> &DeviceStats {
        &self.stats
    }
}
