//! The RPLIDAR driver's state machine: connect (stop a stream left running,
//! settle, flush), configure (health, identity, scan modes, motor), stream
//! (decode, assemble, deliver revolutions), recover (reset on a health
//! error, reconnect on silence).
//!
//! Sequence per connect, after the SDK's `stop()` / `getHealth()` /
//! `getDeviceInfo()` / `startScan()` and the research notes (§1.2, §5):
//! `STOP`, wait [`SETTLE`] (the SDK's `delay(100)` in `stop()`, as a timer
//! checked by `poll`), `FlushInput`, `GET_HEALTH` (error → `RESET`, drain the
//! boot banner, reconnect; warning → counted, go on), `GET_INFO`,
//! `GET_SAMPLERATE`, `GET_LIDAR_CONF` (mode count, then name, answer type,
//! sample duration and range of each mode, typical mode),
//! `GET_ACC_BOARD_FLAG` (motor `Auto` only), `Identity`, motor on, scan start,
//! descriptor, stream.
//!
//! Rules: a health status the protocol does not define is treated as a
//! warning. A required request (`GET_HEALTH`, `GET_INFO`, the scan start)
//! unanswered after `reply_timeout` is sent once more (`timeout`), then the
//! driver asks for a reconnect naming it. Optional requests
//! (`GET_SAMPLERATE`, `GET_LIDAR_CONF`, `GET_ACC_BOARD_FLAG`) are asked once;
//! silence counts `optional_timeout` and means "not supported" (no mode count:
//! no further `GET_LIDAR_CONF`). Answers of the wrong type, and late answers,
//! are counted `unexpected_response` and skipped; short answers `bad_reply`
//! (required ones are then waited for again). A stream with no complete
//! revolution for `stream_timeout` asks for a reconnect (`stream_timeout`).
//! Every write counts in `DeviceStats::commands`; a reconnect request in
//! `reconnects`; a started stream in `handshakes`.

use std::time::Duration;

use super::conf;
use super::conf::ConfQuery;
use super::config::RplidarConfig;
use super::device::{
    DeviceDriver, DeviceState, DeviceStats, DriverOutput, HostTime, RangeScan, StampBound,
};
use super::motor::MotorDrive;
use super::plan::{self, Capabilities, ScanPlan};
use super::probe::{Probe, Query};
use super::protocol::cmd;
use super::reader::{ReaderEvent, ResponseReader};
use super::replies::{parse_acc_board_pwm, DeviceInfo, Health, HealthStatus, SampleRate};
use super::request;
use super::revolution::{Revolution, RevolutionAssembler};
use super::stream::{StreamDecoder, StreamEvent};
use super::timing::SampleClock;

/// Wait after `STOP` before flushing (the SDK's `stop()` waits 100 ms).
pub const SETTLE: Duration = Duration::from_millis(100);
/// After `RESET`: wait at least this long for the device to reboot…
pub const RESET_MIN: Duration = Duration::from_millis(1000);
/// …and until its banner has been quiet this long…
pub const RESET_QUIET: Duration = Duration::from_millis(100);
/// …but no longer than this.
pub const RESET_MAX: Duration = Duration::from_millis(3000);

fn ns(d: Duration) -> u64 {
    u64::try_from(d.as_nanos()).unwrap_or(u64::MAX)
}

#[derive(Debug, Clone, PartialEq, Eq)]
enum Phase {
    /// Not connected (before `connect`, after `shutdown`).
    Idle,
    /// `STOP` sent; bytes still arriving are a stream left running.
    Settling {
        until_ns: u64,
    },
    /// A request is out.
    Awaiting {
        query: Query,
        sent_ns: u64,
        retried: bool,
    },
    /// `RESET` sent; draining the boot banner.
    Resetting {
        since_ns: u64,
        last_byte_ns: u64,
        reason: String,
    },
    Streaming {
        last_scan_ns: u64,
    },
    /// `Reconnect` asked for; waiting for `connect`.
    Failed,
}

/// The scan decoding pipeline of one stream.
#[derive(Debug, Clone)]
struct Stream {
    decoder: StreamDecoder,
    assembler: RevolutionAssembler,
}

/// The RPLIDAR A/S/C-series driver (sans-I/O; see the module docs).
#[derive(Debug, Clone)]
pub struct RplidarDriver {
    config: RplidarConfig,
    state: DeviceState,
    stats: DeviceStats,
    phase: Phase,
    reader: ResponseReader,
    probe: Probe,
    plan: Option<ScanPlan>,
    motor: Option<MotorDrive>,
    stream: Option<Stream>,
    events: Vec<StreamEvent>,
    sequence: u32,
}

impl RplidarDriver {
    pub fn new(config: RplidarConfig) -> Self {
        Self {
            config,
            state: DeviceState::Disconnected,
            stats: DeviceStats::default(),
            phase: Phase::Idle,
            reader: ResponseReader::default(),
            probe: Probe::default(),
            plan: None,
            motor: None,
            stream: None,
            events: Vec::new(),
            sequence: 0,
        }
    }

    /// The settings it was made with.
    pub fn config(&self) -> &RplidarConfig {
        &self.config
    }

    fn set_state(&mut self, state: DeviceState, out: &mut Vec<DriverOutput>) {
        if self.state != state {
            self.state = state.clone();
            out.push(DriverOutput::State(state));
        }
    }

    fn write(&mut self, bytes: Vec<u8>, out: &mut Vec<DriverOutput>) {
        self.stats.commands += 1;
        out.push(DriverOutput::Write(bytes));
    }

    /// Emits a motor output; PWM/RPM commands are writes.
    fn motor_output(&mut self, output: DriverOutput, out: &mut Vec<DriverOutput>) {
        match output {
            DriverOutput::Write(bytes) => self.write(bytes, out),
            other => out.push(other),
        }
    }

    fn fail(&mut self, reason: String, out: &mut Vec<DriverOutput>) {
        self.stats.reconnects += 1;
        self.phase = Phase::Failed;
        self.stream = None;
        self.set_state(DeviceState::Disconnected, out);
        out.push(DriverOutput::Reconnect(reason));
    }

    fn send(&mut self, query: Query, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.ask(query, false, now, out);
    }

    /// Writes `query`'s request and awaits its answer (`retried`: the second time).
    fn ask(&mut self, query: Query, retried: bool, now: HostTime, out: &mut Vec<DriverOutput>) {
        let bytes = query.request(self.plan.as_ref());
        self.reader.reset();
        self.write(bytes, out);
        self.phase = Phase::Awaiting {
            query,
            sent_ns: now.monotonic_ns,
            retried,
        };
    }

    /// Asks the next question, or starts the scan when none is left.
    fn advance(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        match self.probe.next_query() {
            Some(query) => self.send(query, now, out),
            None => self.start_scan(now, out),
        }
    }

    fn start_scan(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        let Some(info) = self.probe.info.clone() else {
            return self.fail("no device info".to_string(), out);
        };
        let caps = Capabilities {
            info: &info,
            rate: self.probe.rate,
            conf: &self.probe.conf,
        };
        let (plan, fell_back) = plan::choose(self.config.scan_mode, caps);
        if fell_back {
            self.stats.count("unsupported_scan_mode");
        }
        let motor = MotorDrive::configured(self.config.motor)
            .unwrap_or_else(|| MotorDrive::detect(&info, self.probe.board_pwm));
        out.push(DriverOutput::Identity(self.probe.identity(&plan, motor)));
        self.motor = Some(motor);
        self.plan = Some(plan);
        self.motor_output(motor.start(), out);
        self.send(Query::StartScan, now, out);
    }

    fn on_reader_event(&mut self, event: ReaderEvent, now: HostTime, out: &mut Vec<DriverOutput>) {
        let Phase::Awaiting { query, .. } = self.phase.clone() else {
            return;
        };
        match event {
            ReaderEvent::Rejected(_) => self.stats.count("bad_descriptor"),
            ReaderEvent::Stream(descriptor) => {
                let expected = query == Query::StartScan
                    && self.plan.as_ref().is_some_and(|p| p.expects(&descriptor));
                if expected {
                    self.begin_stream(now, out);
                } else {
                    self.stats.count("unexpected_response");
                }
            }
            ReaderEvent::Reply {
                answer_type,
                payload,
            } => {
                if query != Query::StartScan && answer_type == query.answer_type() {
                    self.on_answer(query, &payload, now, out);
                } else {
                    self.stats.count("unexpected_response");
                }
            }
        }
    }

    fn on_answer(
        &mut self,
        query: Query,
        payload: &[u8],
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        match query {
            Query::Health => match Health::parse(payload) {
                Ok(health) => self.on_health(health, now, out),
                Err(_) => self.stats.count("bad_reply"),
            },
            Query::Info => match DeviceInfo::parse(payload) {
                Ok(info) => {
                    self.probe.learn_info(info, self.config.motor);
                    self.advance(now, out);
                }
                Err(_) => self.stats.count("bad_reply"),
            },
            Query::SampleRate => {
                match SampleRate::parse(payload) {
                    Ok(rate) => self.probe.rate = Some(rate),
                    Err(_) => self.stats.count("bad_reply"),
                }
                self.advance(now, out);
            }
            Query::Conf(q) => self.on_conf(q, payload, now, out),
            Query::AccBoardFlag => {
                match parse_acc_board_pwm(payload) {
                    Ok(pwm) => self.probe.board_pwm = Some(pwm),
                    Err(_) => self.stats.count("bad_reply"),
                }
                self.advance(now, out);
            }
            Query::StartScan => {}
        }
    }

    fn on_health(&mut self, health: Health, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.probe.health = Some(health);
        out.push(DriverOutput::Health {
            ok: health.status == HealthStatus::Ok,
            detail: health.detail(),
        });
        match health.status {
            HealthStatus::Ok => self.send(Query::Info, now, out),
            HealthStatus::Warning | HealthStatus::Unknown(_) => {
                self.stats.count("health_warning");
                self.send(Query::Info, now, out);
            }
            HealthStatus::Error => {
                self.stats.count("health_error");
                let reason = format!("device health error {:#06x}; reset it", health.error_code);
                self.set_state(DeviceState::Recovering(reason.clone()), out);
                self.write(request::encode(cmd::RESET, &[]), out);
                self.phase = Phase::Resetting {
                    since_ns: now.monotonic_ns,
                    last_byte_ns: now.monotonic_ns,
                    reason,
                };
            }
        }
    }

    /// A `GET_LIDAR_CONF` answer must echo the key asked; an empty value
    /// means the device has no answer for it.
    fn on_conf(
        &mut self,
        q: ConfQuery,
        payload: &[u8],
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        let (key, value) = match conf::split_answer(payload) {
            Ok(split) => split,
            Err(_) => {
                self.stats.count("bad_reply");
                return;
            }
        };
        if key != q.key() {
            self.stats.count("unexpected_response");
            return;
        }
        if value.is_empty() {
            self.conf_unanswered(q);
        } else if self.probe.conf.record(q, value).is_err() {
            self.stats.count("bad_reply");
            self.conf_unanswered(q);
        } else if q == ConfQuery::ModeCount {
            if self.probe.conf.mode_count.unwrap_or(0) > conf::MAX_SCAN_MODES {
                self.stats.count("too_many_scan_modes");
            }
            self.probe.plan_mode_queries();
        }
        self.advance(now, out);
    }

    /// Without a mode count there is nothing to ask about modes.
    fn conf_unanswered(&mut self, q: ConfQuery) {
        if q == ConfQuery::ModeCount {
            self.probe.drop_conf_queries();
        }
    }

    fn begin_stream(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        let Some(plan) = &self.plan else { return };
        let clock = SampleClock::new(plan.sample_us_q8, self.config.baud);
        self.stream = Some(Stream {
            decoder: StreamDecoder::new(plan.format, clock),
            assembler: RevolutionAssembler::new(
                self.config.max_rays,
                plan.format.boundary_confirmation(),
            ),
        });
        self.phase = Phase::Streaming {
            last_scan_ns: now.monotonic_ns,
        };
        self.stats.handshakes += 1;
        self.set_state(DeviceState::Streaming, out);
    }

    fn feed_replies(&mut self, bytes: &[u8], now: HostTime, out: &mut Vec<DriverOutput>) {
        let mut rest = bytes;
        while !rest.is_empty() {
            match self.phase {
                Phase::Streaming { .. } => return self.feed_stream(rest, now, out),
                Phase::Awaiting { .. } => {}
                _ => return,
            }
            let fed = self.reader.feed(rest);
            rest = rest.get(fed.consumed..).unwrap_or_default();
            self.stats.add("stray_bytes", fed.stray);
            if let Some(event) = fed.event {
                self.on_reader_event(event, now, out);
            }
        }
    }

    fn feed_stream(&mut self, bytes: &[u8], now: HostTime, out: &mut Vec<DriverOutput>) {
        let Some(stream) = &mut self.stream else {
            return;
        };
        let mut events = std::mem::take(&mut self.events);
        stream
            .decoder
            .feed(bytes, now, &mut self.stats, &mut events);
        let mut done = Vec::new();
        for event in events.drain(..) {
            if let Some(revolution) = stream.assembler.push(event, &mut self.stats) {
                done.push(revolution);
            }
        }
        self.events = events;
        for revolution in done {
            self.deliver(revolution, now, out);
        }
    }

    fn deliver(&mut self, revolution: Revolution, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.stats.scans += 1;
        let sequence = self.sequence;
        self.sequence = self.sequence.wrapping_add(1);
        self.phase = Phase::Streaming {
            last_scan_ns: now.monotonic_ns,
        };
        // A revolution is known complete only at the next capsule (or after
        // the confirming nodes): its age counts from its last sample's time,
        // back-dated like every sample from its own packet's arrival, not
        // from now (never younger than it is).
        let last_offset = revolution.rays.last().map_or(0, |r| u64::from(r.offset_ns));
        let last_sample = revolution.stamp_ns.saturating_add(last_offset);
        // Measured on the wall clock, applied to both: bounded by a second
        // (a slow revolution) so that a wall-clock step cannot skew it.
        let lag = now.unix_ns.saturating_sub(last_sample).min(1_000_000_000);
        let received = HostTime::new(
            now.monotonic_ns.saturating_sub(lag),
            now.unix_ns.saturating_sub(lag),
        );
        out.push(DriverOutput::Scan(RangeScan {
            sequence,
            stamp_ns: revolution.stamp_ns,
            received,
            rays: revolution.rays,
            stamp_bound: StampBound::Untracked,
        }));
    }

    fn on_reply_timeout(
        &mut self,
        query: Query,
        retried: bool,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if query.optional() {
            self.stats.note("optional_timeout");
            if let Query::Conf(q) = query {
                self.conf_unanswered(q);
            }
            return self.advance(now, out);
        }
        self.stats.count("timeout");
        if retried {
            return self.fail(format!("no answer to {} (asked twice)", query.name()), out);
        }
        self.ask(query, true, now, out);
    }
}

impl DeviceDriver for RplidarDriver {
    fn kind(&self) -> &'static str {
        "rplidar"
    }

    fn connect(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.reader.reset();
        self.probe = Probe::default();
        self.plan = None;
        self.motor = None;
        self.stream = None;
        self.set_state(DeviceState::Connecting, out);
        self.write(request::encode(cmd::STOP, &[]), out);
        self.phase = Phase::Settling {
            until_ns: now.monotonic_ns.saturating_add(ns(SETTLE)),
        };
    }

    fn receive(&mut self, bytes: &[u8], now: HostTime, out: &mut Vec<DriverOutput>) {
        self.stats.bytes += bytes.len() as u64;
        match &mut self.phase {
            Phase::Idle | Phase::Failed | Phase::Settling { .. } => {}
            Phase::Resetting { last_byte_ns, .. } => {
                if !bytes.is_empty() {
                    *last_byte_ns = now.monotonic_ns;
                }
            }
            Phase::Awaiting { .. } => self.feed_replies(bytes, now, out),
            Phase::Streaming { .. } => self.feed_stream(bytes, now, out),
        }
    }

    fn poll(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        let t = now.monotonic_ns;
        match self.phase.clone() {
            Phase::Idle | Phase::Failed => {}
            Phase::Settling { until_ns } => {
                if t >= until_ns {
                    out.push(DriverOutput::FlushInput);
                    self.set_state(DeviceState::Configuring, out);
                    self.send(Query::Health, now, out);
                }
            }
            Phase::Awaiting {
                query,
                sent_ns,
                retried,
            } => {
                if t.saturating_sub(sent_ns) >= ns(self.config.reply_timeout) {
                    self.on_reply_timeout(query, retried, now, out);
                }
            }
            Phase::Resetting {
                since_ns,
                last_byte_ns,
                reason,
            } => {
                let (age, quiet) = (t.saturating_sub(since_ns), t.saturating_sub(last_byte_ns));
                if (age >= ns(RESET_MIN) && quiet >= ns(RESET_QUIET)) || age >= ns(RESET_MAX) {
                    out.push(DriverOutput::FlushInput);
                    self.fail(reason, out);
                }
            }
            Phase::Streaming { last_scan_ns } => {
                if t.saturating_sub(last_scan_ns) >= ns(self.config.stream_timeout) {
                    self.stats.count("stream_timeout");
                    let secs = self.config.stream_timeout.as_secs_f64();
                    self.fail(format!("no complete revolution for {secs:.1} s"), out);
                }
            }
        }
    }

    fn shutdown(&mut self, out: &mut Vec<DriverOutput>) {
        self.write(request::encode(cmd::STOP, &[]), out);
        let motor = self
            .motor
            .or_else(|| MotorDrive::configured(self.config.motor))
            .unwrap_or(MotorDrive::Dtr);
        self.motor_output(motor.stop(), out);
        self.phase = Phase::Idle;
        self.stream = None;
        self.set_state(DeviceState::Disconnected, out);
    }

    fn state(&self) -> &DeviceState {
        &self.state
    }

    fn stats(&self) -> &DeviceStats {
        &self.stats
    }
}
