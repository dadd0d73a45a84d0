//! The Benewake driver's state machine: connect (version request), configure
//! (frame rate, output format, output enable, save), stream (one reading per
//! data frame), and ask for a reconnect when the device falls silent.

use std::collections::VecDeque;

use super::command::Command;
use super::config::BenewakeConfig;
use super::decoder::{Decoded, Decoder, Packet};
use super::frame::DataFrame;
use super::handshake::{plan, Step};
use super::identity::identity;
use super::reading::Reading;
use super::reply::{FirmwareVersion, Reply};
use super::timing::{duration_ns, frame_transmission_ns, stream_timeout_ns};
use crate::assembly::lateness::DEFAULT_PERIOD_TOLERANCE;
use crate::assembly::lateness::{best_estimate_ns, Behind, FrameTiming};
use crate::device::{
    DeviceDriver, DeviceState, DeviceStats, DriverOutput, HostTime, RangeScan, ReadWindow,
    StampBound,
};

/// A command sent and not yet answered.
#[derive(Debug, Clone, Copy)]
struct Pending {
    step: Step,
    deadline_ns: u64,
}

/// What one connection has learned and is waiting for; reset at every
/// connect.
#[derive(Debug, Clone, Default)]
struct Session {
    /// Plan steps not yet sent.
    steps: VecDeque<Step>,
    pending: Option<Pending>,
    firmware: Option<FirmwareVersion>,
    /// The frame rate the device echoed.
    confirmed_rate: Option<u16>,
    /// Valid data frames since connect (while configuring too).
    frames_seen: u64,
    /// Monotonic ns of the last valid data frame.
    last_frame_ns: u64,
    /// Monotonic ns of the connect, then of the start of streaming.
    state_since_ns: u64,
    /// Monotonic ns of the trigger still awaiting its frame (trigger mode).
    trigger_sent_ns: Option<u64>,
}

/// Driver of one TFmini-family rangefinder on a UART (kind `tfmini`).
///
/// Connect: `SetBaud(baud)` (unless `baud` is 0), `FlushInput`, then the plan of
/// [`plan`](super::plan) one command at a time: version request
/// (state `Connecting`), then frame rate if configured, output format, output
/// enable and save if configured (state `Configuring`). Each command waits up
/// to `reply_timeout` for its echo while data frames keep arriving; one left
/// unanswered is counted (`command_unanswered`) and the plan moves on, except
/// the version request when no data frame arrived either: then the device is
/// absent and the driver asks for a reconnect. The original TFmini takes no
/// commands: the driver only listens and streams from its first frame.
///
/// Data frames before the plan completes are dropped (noted as
/// `frame_while_configuring`):
/// their unit and rate are not settled yet. Once streaming, each data frame,
/// valid or not, is one [`RangeScan`] of one ray (angle 0, offset 0,
/// intensity = strength). Invalid readings are `NaN` rays, counted as
/// invalid readings (not errors) under `weak_return`, `saturated` or
/// `out_of_range`.
/// A stream silent for max(10 frame periods, `stream_timeout`) ends in
/// [`DriverOutput::Reconnect`].
///
/// Trigger mode (`frame_rate: Some(0)`): once streaming, the driver sends a
/// trigger (`5A 04 04 62`) whenever the previous trigger's frame has arrived
/// (checked at every poll), or again after `reply_timeout` without it
/// (`trigger_unanswered`); the stream is then declared dead after
/// max(`stream_timeout`, 2 × `reply_timeout`) without a frame.
///
/// Shutdown sends nothing (state `Disconnected`): output stays enabled, as
/// the driver left it and as the device powers up; settings are never saved
/// on shutdown. The driver never changes the device's baud rate and does not
/// probe baud rates: a wrong `baud` shows as garbage and reconnects.
/// [`DriverOutput::Identity`] is sent each time streaming starts
/// (pairs from [`identity`](super::identity())).
#[derive(Debug, Clone)]
pub struct BenewakeDriver {
    config: BenewakeConfig,
    state: DeviceState,
    stats: DeviceStats,
    decoder: Decoder,
    /// Reused buffer of decoder output.
    decoded: Vec<Decoded>,
    session: Session,
    sequence: u32,
    last_reading: Option<Reading>,
}

impl BenewakeDriver {
    pub fn new(config: BenewakeConfig) -> Self {
        Self {
            config,
            state: DeviceState::Disconnected,
            stats: DeviceStats::default(),
            decoder: Decoder::new(),
            decoded: Vec::new(),
            session: Session::default(),
            sequence: 0,
            last_reading: None,
        }
    }

    /// The configuration the driver runs with.
    pub fn config(&self) -> &BenewakeConfig {
        &self.config
    }

    /// The last reading delivered (with its temperature), if any.
    pub fn last_reading(&self) -> Option<&Reading> {
        self.last_reading.as_ref()
    }

    /// The firmware version the device reported at this connection.
    pub fn firmware(&self) -> Option<FirmwareVersion> {
        self.session.firmware
    }

    /// Bytes the decoder skipped while hunting for frames, since creation.
    pub fn skipped_bytes(&self) -> u64 {
        self.decoder.skipped_bytes()
    }

    fn set_state(&mut self, state: DeviceState, out: &mut Vec<DriverOutput>) {
        if self.state != state {
            self.state = state.clone();
            out.push(DriverOutput::State(state));
        }
    }

    fn write(&mut self, command: Command, out: &mut Vec<DriverOutput>) {
        self.stats.commands += 1;
        out.push(DriverOutput::Write(command.encode()));
    }

    fn reconnect(&mut self, reason: String, out: &mut Vec<DriverOutput>) {
        self.stats.reconnects += 1;
        self.session.pending = None;
        self.set_state(DeviceState::Disconnected, out);
        out.push(DriverOutput::Reconnect(reason));
    }

    /// Sends the next plan step, or starts streaming when none is left.
    fn next_step(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        match self.session.steps.pop_front() {
            Some(step) => {
                self.write(step.command(), out);
                let deadline_ns = now
                    .monotonic_ns
                    .saturating_add(duration_ns(self.config.reply_timeout));
                self.session.pending = Some(Pending { step, deadline_ns });
            }
            None => self.start_streaming(now, out),
        }
    }

    /// The pending step is over (answered or given up): move on.
    fn step_done(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.session.pending = None;
        if self.state == DeviceState::Connecting {
            self.set_state(DeviceState::Configuring, out);
        }
        self.next_step(now, out);
    }

    fn start_streaming(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.set_state(DeviceState::Streaming, out);
        self.session.state_since_ns = now.monotonic_ns;
        self.stats.handshakes += 1;
        let pairs = identity(
            &self.config,
            self.session.firmware,
            self.session.confirmed_rate,
        );
        out.push(DriverOutput::Identity(pairs));
        if self.config.trigger_mode() {
            self.trigger(now, out);
        }
    }

    fn trigger(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.write(Command::Trigger, out);
        self.session.trigger_sent_ns = Some(now.monotonic_ns);
    }

    fn on_packet(
        &mut self,
        decoded: Decoded,
        now: HostTime,
        bound: StampBound,
        out: &mut Vec<DriverOutput>,
    ) {
        match decoded {
            Err(error) => self.stats.count(error.kind()),
            Ok(Packet::Data(frame)) => self.on_frame(frame, now, bound, out),
            Ok(Packet::Reply(frame)) => self.on_reply(frame.reply(), now, out),
        }
    }

    fn on_frame(
        &mut self,
        frame: DataFrame,
        now: HostTime,
        bound: StampBound,
        out: &mut Vec<DriverOutput>,
    ) {
        self.session.frames_seen = self.session.frames_seen.saturating_add(1);
        self.session.last_frame_ns = now.monotonic_ns;
        let listen_only = !self.config.model.has_commands();
        match self.state {
            DeviceState::Streaming => self.deliver(frame, now, bound, out),
            DeviceState::Connecting if listen_only => {
                self.start_streaming(now, out);
                self.deliver(frame, now, bound, out);
            }
            _ => self.stats.note("frame_while_configuring"),
        }
    }

    /// `now` is when the frame's last byte is taken to have arrived;
    /// `bound`, when the frame was measured, if the read it came in says.
    fn deliver(
        &mut self,
        frame: DataFrame,
        now: HostTime,
        bound: StampBound,
        out: &mut Vec<DriverOutput>,
    ) {
        let reading = Reading::classify(frame, self.config.model, self.config.effective_unit());
        if let Some(kind) = reading.validity.counter() {
            self.stats.count_invalid_reading(kind);
        }
        let stamp_ns = match bound {
            StampBound::Within {
                earliest_ns,
                latest_ns,
            } => best_estimate_ns(earliest_ns, latest_ns),
            _ => now
                .unix_ns
                .saturating_sub(frame_transmission_ns(self.config.baud)),
        };
        out.push(DriverOutput::Scan(RangeScan {
            sequence: self.sequence,
            stamp_ns,
            received: now,
            rays: vec![reading.ray()],
            stamp_bound: bound,
        }));
        self.sequence = self.sequence.wrapping_add(1);
        self.stats.scans += 1;
        self.last_reading = Some(reading);
        self.session.trigger_sent_ns = None;
    }

    fn on_reply(&mut self, reply: Reply, now: HostTime, out: &mut Vec<DriverOutput>) {
        let Some(pending) = self.session.pending else {
            self.stats.count("unexpected_reply");
            return;
        };
        if !pending.step.answered_by(&reply) {
            self.stats.count("unexpected_reply");
            return;
        }
        match reply {
            Reply::Version(version) => self.session.firmware = Some(version),
            Reply::FrameRate(hz) => self.session.confirmed_rate = Some(hz),
            Reply::Status { ok: false, .. } => self.stats.count("save_failed"),
            _ => {}
        }
        self.step_done(now, out);
    }

    /// The pending command's reply is overdue.
    fn on_reply_timeout(&mut self, step: Step, now: HostTime, out: &mut Vec<DriverOutput>) {
        if step == Step::Version && self.session.frames_seen == 0 {
            let ms = self.config.reply_timeout.as_millis();
            let reason = format!("no reply to the version request and no data frame in {ms} ms");
            self.stats.count("timeout");
            self.reconnect(reason, out);
            return;
        }
        self.stats.count("command_unanswered");
        self.step_done(now, out);
    }

    /// The silence that ends the stream, in ns: max(10 frame periods,
    /// `stream_timeout`), and in trigger mode at least two unanswered
    /// triggers' worth (2 × `reply_timeout`).
    fn stream_timeout_ns(&self) -> u64 {
        let rate = self.session.confirmed_rate.or(self.config.frame_rate);
        let timeout = stream_timeout_ns(self.config.stream_timeout, rate);
        if self.config.trigger_mode() {
            timeout.max(duration_ns(self.config.reply_timeout).saturating_mul(2))
        } else {
            timeout
        }
    }

    /// Asks for a reconnect when no frame came within the stream timeout of
    /// the later of the last frame and the connect (listen-only) or the start
    /// of streaming.
    fn check_silence(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        let since = self.session.last_frame_ns.max(self.session.state_since_ns);
        let timeout = self.stream_timeout_ns();
        if now.monotonic_ns.saturating_sub(since) > timeout {
            let ms = timeout / 1_000_000;
            self.stats.count("timeout");
            self.reconnect(format!("no data frame for {ms} ms"), out);
        }
    }

    /// What the host knows of the stream's timing: a frame's wire time, the
    /// nominal period (the rate the device echoed, else the one configured,
    /// else the model's factory rate; none in trigger mode), and the
    /// configured hidden latency.
    fn frame_timing(&self) -> FrameTiming {
        let rate = match self.session.confirmed_rate.or(self.config.frame_rate) {
            Some(hz) => hz,
            None => self.config.model.factory_frame_rate_hz(),
        };
        FrameTiming {
            wire_ns: frame_transmission_ns(self.config.baud),
            period_ns: (rate > 0).then(|| 1_000_000_000 / u64::from(rate)),
            period_tolerance: DEFAULT_PERIOD_TOLERANCE,
            hidden_latency_ns: duration_ns(self.config.link_latency),
        }
    }

    /// Decodes `bytes` read by a read returning at `now`; with the read's
    /// `window`, each frame's measurement time is bounded.
    fn receive_bytes(
        &mut self,
        bytes: &[u8],
        now: HostTime,
        window: Option<ReadWindow>,
        out: &mut Vec<DriverOutput>,
    ) {
        self.stats.bytes = self.stats.bytes.saturating_add(bytes.len() as u64);
        if self.state == DeviceState::Disconnected {
            return;
        }
        let mut decoded = std::mem::take(&mut self.decoded);
        self.decoder.feed(bytes, &mut decoded);
        let timing = self.frame_timing();
        // Several frames in one read arrived one after another on the wire:
        // each earlier one is back-dated by the frames that followed it (the
        // last ends about when the read returned).
        let mut behind = Behind {
            frames: decoded
                .iter()
                .filter(|d| matches!(d, Ok(Packet::Data(_))))
                .count() as u64,
            // A malformed frame (a bad sum) was a frame slot on the wire.
            slots: decoded
                .iter()
                .filter(|d| !matches!(d, Ok(Packet::Reply(_))))
                .count() as u64,
        };
        let per_frame = frame_transmission_ns(self.config.baud);
        for item in decoded.drain(..) {
            if self.state == DeviceState::Disconnected {
                break;
            }
            let mut at = now;
            let mut bound = StampBound::Untracked;
            if !matches!(item, Ok(Packet::Reply(_))) {
                behind.slots = behind.slots.saturating_sub(1);
            }
            if matches!(item, Ok(Packet::Data(_))) {
                behind.frames = behind.frames.saturating_sub(1);
                let back = behind.frames.saturating_mul(per_frame);
                at.unix_ns = at.unix_ns.saturating_sub(back);
                at.monotonic_ns = at.monotonic_ns.saturating_sub(back);
                if let Some(window) = window {
                    bound = timing.interval(window, behind);
                }
            }
            self.on_packet(item, at, bound, out);
        }
        self.decoded = decoded;
    }

    /// Trigger mode: a new trigger once the last one's frame came, or again
    /// when it went unanswered for `reply_timeout`.
    fn poll_trigger(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        match self.session.trigger_sent_ns {
            None => self.trigger(now, out),
            Some(sent)
                if now.monotonic_ns.saturating_sub(sent)
                    >= duration_ns(self.config.reply_timeout) =>
            {
                self.stats.count("trigger_unanswered");
                self.trigger(now, out);
            }
            Some(_) => {}
        }
    }
}

impl DeviceDriver for BenewakeDriver {
    fn kind(&self) -> &'static str {
        "tfmini"
    }

    fn connect(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.decoder.reset();
        self.session = Session {
            steps: plan(&self.config).into(),
            ..Session::default()
        };
        if self.config.baud > 0 {
            out.push(DriverOutput::SetBaud(self.config.baud));
        }
        out.push(DriverOutput::FlushInput);
        self.set_state(DeviceState::Connecting, out);
        self.session.state_since_ns = now.monotonic_ns;
        if !self.session.steps.is_empty() {
            self.next_step(now, out);
        }
    }

    fn receive(&mut self, bytes: &[u8], now: HostTime, out: &mut Vec<DriverOutput>) {
        self.receive_bytes(bytes, now, None, out);
    }

    /// The frame carries no device time (the manuals' 9-byte data frame:
    /// header, distance, strength, temperature, checksum): each
    /// reading's time is bounded from the read ([`FrameTiming::interval`])
    /// and stamped at the middle of its bound.
    fn receive_read(&mut self, bytes: &[u8], window: ReadWindow, out: &mut Vec<DriverOutput>) {
        self.receive_bytes(bytes, window.returned, Some(window), out);
    }

    fn poll(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        if let Some(pending) = self.session.pending {
            if now.monotonic_ns >= pending.deadline_ns {
                self.on_reply_timeout(pending.step, now, out);
            }
        }
        let listening = self.state == DeviceState::Connecting && !self.config.model.has_commands();
        if self.state == DeviceState::Streaming || listening {
            self.check_silence(now, out);
        }
        if self.state == DeviceState::Streaming && self.config.trigger_mode() {
            self.poll_trigger(now, out);
        }
    }

    fn shutdown(&mut self, out: &mut Vec<DriverOutput>) {
        self.session.pending = None;
        self.set_state(DeviceState::Disconnected, out);
    }

    fn state(&self) -> &DeviceState {
        &self.state
    }

    fn stats(&self) -> &DeviceStats {
        &self.stats
    }
}
