//! The driver's handshake (sensors.md §1.1, urg_c `connect_urg_device()`,
//! `urg_open()`): probe with `QT` (at each RS-232 rate), switch a SCIP 1.1
//! sensor with `SCIP2.0`, leave time-adjust mode with `TM2`, stop a stream
//! left running (`QT`, flush, drain, probe again), optionally change the bit
//! rate with `SS`, then read `VV`, `PP`, `II`, sync the clock with `TM0`,
//! `TM1` x N, `TM2`, and start the measurement.

use super::command::{Command, ScanRequest, TimeMode};
use super::driver::{duration_ns, Phase, ScipDriver, BAUD_SETTLE_NS, MAX_DRAINS};
use super::params::{health, parse_pairs, ScipGeometry};
use super::rays::ScanPlan;
use super::reply::Reply;
use super::scan_data::decode_timestamp;
use super::status::{Status, StatusClass};
use crate::device::{DeviceState, DriverOutput, HostTime};

impl ScipDriver {
    /// Probes at rate index `baud` (RS-232: set the port's rate first).
    pub(super) fn start_probe(&mut self, baud: usize, now: HostTime, out: &mut Vec<DriverOutput>) {
        let rate = self.bauds.as_ref().and_then(|b| b.get(baud).copied());
        if let Some(rate) = rate {
            out.push(DriverOutput::SetBaud(rate));
        }
        self.session.baud = rate;
        self.send(&Command::Qt, Phase::Probe { baud }, now, out);
    }

    /// No reply at rate index `baud`: the next rate, or give up.
    pub(super) fn next_probe(&mut self, baud: usize, now: HostTime, out: &mut Vec<DriverOutput>) {
        match &self.bauds {
            Some(bauds) if baud + 1 < bauds.len() => self.start_probe(baud + 1, now, out),
            Some(bauds) => {
                let rates: Vec<String> = bauds.iter().map(u32::to_string).collect();
                let reason = format!("no reply to QT at {} baud", rates.join(", "));
                self.reconnect(reason, out);
            }
            None => self.reconnect("no reply to QT over USB".to_owned(), out),
        }
    }

    pub(super) fn on_probe_reply(
        &mut self,
        baud: usize,
        reply: &Reply,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if reply.echo != b"QT" {
            // Printable text that is not our echo: scan data of a stream left
            // running (urg_c: "abnormal echo back, taken as receiving data").
            self.stats.count("unexpected_echo");
            return self.drain(baud, now, out);
        }
        let Some(first) = reply.lines.first() else {
            return self.stats.count("malformed_reply");
        };
        // A SCIP 1.1 sensor answers the unknown QT with a bare `E` (urg_c).
        if first == b"E" {
            return self.send(&Command::Scip2, Phase::Scip2 { baud }, now, out);
        }
        match Status::parse(first) {
            Err(e) => self.stats.count(e.kind()),
            // `0E` to QT: the sensor is in TM mode (urg_c) and takes only TM2.
            Ok(Status(code)) if &code == b"0E" => {
                let leave = Command::Tm(TimeMode::Leave);
                self.send(&leave, Phase::LeaveTimeMode { baud }, now, out);
            }
            Ok(status) if status.class() == StatusClass::Abnormal => {
                self.stats.count(status.error_kind());
                self.recover(format!("QT answered {}", status.describe()), now, out)
            }
            Ok(status) => {
                if status != Status::OK {
                    self.stats.count(status.error_kind());
                }
                self.found(now, out);
            }
        }
    }

    /// The sensor is mid-stream: `QT` stops it, the flush drops what it
    /// already sent, and the driver waits for the `QT` reply.
    fn drain(&mut self, baud: usize, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.session.drains += 1;
        if self.session.drains > MAX_DRAINS {
            let reason = format!("the sensor kept streaming after {MAX_DRAINS} QT");
            return self.reconnect(reason, out);
        }
        self.send(&Command::Qt, Phase::Drain { baud }, now, out);
        self.flush_input(out);
    }

    pub(super) fn on_drain_reply(
        &mut self,
        baud: usize,
        reply: &Reply,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        let stopped = reply.echo == b"QT"
            && reply.lines.first().and_then(|l| Status::parse(l).ok()) == Some(Status::OK);
        if stopped {
            self.send(&Command::Qt, Phase::Probe { baud }, now, out);
        }
    }

    /// The sensor answers in SCIP 2.0: configure it.
    fn found(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.set_state(DeviceState::Configuring, out);
        match (self.session.baud, self.config.target_baud) {
            (Some(current), Some(target)) if current != target => {
                let change = Command::SetBitRate(target);
                self.send(&change, Phase::ChangeBaud { target }, now, out);
            }
            _ => self.send(&Command::Vv, Phase::Version, now, out),
        }
    }

    /// A reply during a handshake step after the probe.
    pub(super) fn on_step_reply(
        &mut self,
        step: Phase,
        reply: &Reply,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if reply.echo != self.expected_echo {
            return self.on_foreign_reply(reply);
        }
        let status = reply.lines.first().map(|l| Status::parse(l));
        match (step, status) {
            // The SCIP 1.1 reply to `SCIP2.0` has no 2.0 status line; urg_c
            // ignores its status too.
            (Phase::Scip2 { .. } | Phase::LeaveTimeMode { .. }, _) => self.found(now, out),
            (_, Some(Ok(status))) if status.class() == StatusClass::Abnormal => {
                self.stats.count(status.error_kind());
                let what = String::from_utf8_lossy(&reply.echo).into_owned();
                self.recover(format!("{what} answered {}", status.describe()), now, out);
            }
            (_, Some(Ok(status))) => self.on_step_status(step, status, reply, now, out),
            (_, Some(Err(e))) => self.bad_step_reply(e.kind(), reply, out),
            (_, None) => self.bad_step_reply("malformed_reply", reply, out),
        }
    }

    fn bad_step_reply(&mut self, kind: &'static str, reply: &Reply, out: &mut Vec<DriverOutput>) {
        self.stats.count(kind);
        let what = String::from_utf8_lossy(&reply.echo).into_owned();
        self.reconnect(format!("bad reply to {what}: {kind}"), out);
    }

    fn on_step_status(
        &mut self,
        step: Phase,
        status: Status,
        reply: &Reply,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        let data = reply.lines.get(1..).unwrap_or(&[]);
        match step {
            Phase::ChangeBaud { target } => self.on_baud_changed(target, status, now, out),
            Phase::ConfirmBaud { .. } => self.send(&Command::Vv, Phase::Version, now, out),
            Phase::Version => self.on_version(status, data, now, out),
            Phase::Params => self.on_params(status, data, now, out),
            Phase::Info => self.on_info(status, data, now, out),
            Phase::TimeEnter => self.on_time_enter(status, now, out),
            Phase::TimeRead { done } => self.on_time_read(done, status, data, now, out),
            Phase::TimeLeave => self.start_measurement(now, out),
            Phase::LaserOn => self.on_laser_on(status, now, out),
            _ => {}
        }
    }

    /// `SS`: `00` switched, `03` already at that rate (spec §8.7; urg_c also
    /// accepts `04`, "not compatible", and stays at the current rate).
    fn on_baud_changed(
        &mut self,
        target: u32,
        status: Status,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if !status.is_any(&[b"00", b"03"]) {
            self.stats.count(status.error_kind());
            return self.send(&Command::Vv, Phase::Version, now, out);
        }
        out.push(DriverOutput::SetBaud(target));
        self.session.baud = Some(target);
        self.flush_input(out);
        self.wait(Phase::BaudSettle { target }, BAUD_SETTLE_NS, now);
    }

    fn required_ok(&mut self, status: Status, out: &mut Vec<DriverOutput>) -> bool {
        if status == Status::OK {
            return true;
        }
        self.stats.count(status.error_kind());
        let what = String::from_utf8_lossy(&self.expected_echo).into_owned();
        self.reconnect(
            format!("{what} failed with status {}", status.describe()),
            out,
        );
        false
    }

    fn on_version(
        &mut self,
        status: Status,
        data: &[Vec<u8>],
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if !self.required_ok(status, out) {
            return;
        }
        match parse_pairs(data) {
            Ok(pairs) => {
                self.session.identity.extend(pairs);
                self.send(&Command::Pp, Phase::Params, now, out);
            }
            Err(e) => self.bad_param_reply(e.kind(), e.to_string(), out),
        }
    }

    fn on_params(
        &mut self,
        status: Status,
        data: &[Vec<u8>],
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if !self.required_ok(status, out) {
            return;
        }
        let parsed = parse_pairs(data)
            .and_then(|pairs| ScipGeometry::from_pairs(&pairs).map(|geometry| (pairs, geometry)));
        match parsed {
            Ok((pairs, geometry)) => {
                self.session.identity.extend(pairs);
                self.session.geometry = Some(geometry);
                self.send(&Command::Ii, Phase::Info, now, out);
            }
            Err(e) => self.bad_param_reply(e.kind(), e.to_string(), out),
        }
    }

    fn bad_param_reply(&mut self, kind: &'static str, why: String, out: &mut Vec<DriverOutput>) {
        self.stats.count(kind);
        let what = String::from_utf8_lossy(&self.expected_echo).into_owned();
        self.reconnect(format!("bad reply to {what}: {why}"), out);
    }

    /// `II` feeds Identity and Health; a failed `II` is reported, not fatal.
    fn on_info(
        &mut self,
        status: Status,
        data: &[Vec<u8>],
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        let (ok, detail) = match parse_pairs(data) {
            Ok(pairs) if status == Status::OK => {
                let health = health(&pairs);
                self.session.identity.extend(pairs);
                health
            }
            Ok(_) => {
                self.stats.count(status.error_kind());
                (
                    false,
                    format!("II failed with status {}", status.describe()),
                )
            }
            Err(e) => {
                self.stats.count(e.kind());
                (false, format!("bad II reply: {e}"))
            }
        };
        out.push(DriverOutput::Health { ok, detail });
        self.start_time_sync(now, out);
    }

    fn start_time_sync(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        if self.config.tm_round_trips == 0 {
            return self.start_measurement(now, out);
        }
        self.send(&Command::Tm(TimeMode::Enter), Phase::TimeEnter, now, out);
    }

    /// `TM0`: `00`, or `02` already in adjust mode (spec §8.6). A sensor that
    /// rejects it gets no sync: stamps come from arrival times.
    fn on_time_enter(&mut self, status: Status, now: HostTime, out: &mut Vec<DriverOutput>) {
        if status.is_any(&[b"00", b"02"]) {
            return self.send(
                &Command::Tm(TimeMode::Read),
                Phase::TimeRead { done: 0 },
                now,
                out,
            );
        }
        self.stats.count(status.error_kind());
        self.start_measurement(now, out);
    }

    /// `TM1`: `00P`, then the 4-character timer line (spec §8.6).
    fn on_time_read(
        &mut self,
        done: u8,
        status: Status,
        data: &[Vec<u8>],
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        let timer = data.first().map(|line| decode_timestamp(line));
        match (status == Status::OK, timer) {
            (true, Some(Ok(raw))) => {
                let device_ms = self.session.clock.unwrap(raw);
                self.session.sync.add(device_ms, self.sent_at, now);
            }
            (true, Some(Err(e))) => self.stats.count(e.kind()),
            (true, None) => self.stats.count("malformed_reply"),
            (false, _) => self.stats.count(status.error_kind()),
        }
        let done = done.saturating_add(1);
        if done < self.config.tm_round_trips {
            self.send(
                &Command::Tm(TimeMode::Read),
                Phase::TimeRead { done },
                now,
                out,
            );
        } else {
            let offset = self.session.sync.offset_ns();
            let rtt_ns = self.session.sync.best_rtt_ns().unwrap_or(0);
            self.session.stamper.set_sync(offset, rtt_ns, now.unix_ns);
            self.send(&Command::Tm(TimeMode::Leave), Phase::TimeLeave, now, out);
        }
    }

    /// Starts the configured measurement: `MD`/`MS`/`ME`/`ND`/`NE` directly
    /// (they turn the laser on, spec §8.1), `GD`/`GS`/`GE`/`HD`/`HE` after
    /// `BM` (spec §8.2; urg_c `send_distance_command()` sends `BM` before a
    /// single `G*`/`H*` scan).
    pub(super) fn start_measurement(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        let Some(geometry) = self.session.geometry else {
            return self.reconnect("no PP geometry".to_owned(), out);
        };
        let request = self.build_request(&geometry);
        self.session.plan = Some(ScanPlan::new(&geometry, &request));
        self.session.stream_timeout_ns = self.stream_timeout_ns(&geometry, &request);
        let streamed = request.kind.is_streamed();
        self.session.request = Some(request);
        if streamed {
            self.send_scan_request(now, out);
        } else {
            self.send(&Command::Bm, Phase::LaserOn, now, out);
        }
    }

    /// `BM`: `00`, or `02` already on (spec §8.3; urg_c `urg_laser_on()`).
    /// `01` (laser malfunction) or hardware trouble reboots the sensor.
    fn on_laser_on(&mut self, status: Status, now: HostTime, out: &mut Vec<DriverOutput>) {
        if status.is_any(&[b"00", b"02"]) {
            return self.send_scan_request(now, out);
        }
        let reason = format!("BM (laser on) failed with status {}", status.describe());
        if status.is_any(&[b"01"]) || status.class() == StatusClass::HardwareFault {
            self.stats.count("device_error_hardware");
            self.recover(reason, now, out);
        } else {
            self.stats.count(status.error_kind());
            self.reconnect(reason, out);
        }
    }

    /// The request for `geometry`: steps from the configuration clamped to
    /// `AMIN..=AMAX` (defaults: the whole range), streamed without end.
    fn build_request(&self, geometry: &ScipGeometry) -> ScanRequest {
        let clamp = |step: u32, low: u32| step.clamp(low, geometry.amax) as u16;
        let start = clamp(
            self.config.start_step.map_or(geometry.amin, u32::from),
            geometry.amin,
        );
        let end = clamp(
            self.config.end_step.map_or(geometry.amax, u32::from),
            u32::from(start),
        );
        ScanRequest {
            kind: self.config.scan_kind(),
            start,
            end,
            cluster: self.config.cluster,
            interval: self.config.interval,
            scans: 0,
        }
    }

    /// The configured stream timeout, or max(3 x (scan period including
    /// skipped scans + transfer time at the RS-232 rate), 500 ms).
    fn stream_timeout_ns(&self, geometry: &ScipGeometry, request: &ScanRequest) -> u64 {
        if let Some(timeout) = self.config.stream_timeout {
            return duration_ns(timeout);
        }
        let period = geometry.revolution_ns() * f64::from(u32::from(request.interval) + 1);
        let transfer = match self.session.baud {
            Some(baud) if baud > 0 => {
                let bytes = reply_bytes(request);
                bytes * 10.0 * 1e9 / f64::from(baud)
            }
            _ => 0.0,
        };
        ((3.0 * (period + transfer)) as u64).max(500_000_000)
    }
}

/// About how many bytes one scan reply takes: data characters (multi-echo:
/// as if every step had 3 echoes) plus one sum and LF per 64 characters, plus
/// echo, status and timestamp lines.
fn reply_bytes(request: &ScanRequest) -> f64 {
    let data = (request.value_count() * request.kind.max_step_chars()) as f64;
    data * 66.0 / 64.0 + 40.0
}
