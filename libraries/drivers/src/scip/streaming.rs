//! The driver's measurement loop: the `MD`/`MS`/`ME`/`ND`/`NE`
//! acknowledgement and streamed scans, polled `GD`/`GS`/`GE`/`HD`/`HE` scans,
//! the multi-echo and intensity fallbacks, and
//! the sensor's fault statuses (spec C-42-03320B §8.1, §8.2): `98` resumed is
//! counted, `0L` abnormal or repeated hardware trouble reboots the sensor.

use super::clock::ScanTiming;
use super::command::Command;
use super::driver::{Phase, ScipDriver, HARDWARE_FAULT_LIMIT};
use super::reply::Reply;
use super::scan_data::decode_scan;
use super::status::{Status, StatusClass};
use crate::device::{DeviceState, DriverOutput, HostTime, RangeScan, StampBound};

impl ScipDriver {
    /// Writes the current scan request: `M*` waits for its acknowledgement,
    /// `G*` for its scan (within the stream timeout).
    pub(super) fn send_scan_request(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        let Some(request) = self.session.request.clone() else {
            return self.reconnect("no scan request".to_owned(), out);
        };
        if request.kind.is_streamed() {
            self.send(&Command::Scan(request), Phase::StreamStart, now, out);
        } else {
            self.send(&Command::Scan(request), Phase::Polling, now, out);
            self.wait(Phase::Polling, self.session.stream_timeout_ns, now);
        }
    }

    /// A reply while starting, streaming or polling.
    pub(super) fn on_scan_reply(
        &mut self,
        reply: &Reply,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if !self.is_scan_echo(&reply.echo) {
            return self.on_foreign_reply(reply);
        }
        let status = match reply.lines.first().map(|l| Status::parse(l)) {
            Some(Ok(status)) => status,
            Some(Err(e)) => return self.dropped_scan(e.kind(), now, out),
            None => return self.dropped_scan("malformed_reply", now, out),
        };
        match status.class() {
            StatusClass::Streaming if self.phase != Phase::Polling => self.on_scan(reply, now, out),
            StatusClass::Ok if self.phase == Phase::Polling => self.on_scan(reply, now, out),
            StatusClass::Ok if self.phase == Phase::StreamStart => self.announce(now, out),
            StatusClass::Ok => {} // a repeated acknowledgement
            StatusClass::Resumed => self.stats.count("device_resumed"),
            StatusClass::Abnormal => {
                self.stats.count(status.error_kind());
                self.recover(
                    format!("the sensor reported {}", status.describe()),
                    now,
                    out,
                )
            }
            StatusClass::HardwareFault => self.on_hardware_fault(status, now, out),
            StatusClass::LaserOff if self.phase == Phase::Polling => {
                self.stats.count(status.error_kind());
                self.send(&Command::Bm, Phase::LaserOn, now, out);
            }
            _ => self.on_rejected(status, now, out),
        }
    }

    /// The measurement command was refused: fall back from multi-echo or
    /// intensity, or give up on this connection.
    fn on_rejected(&mut self, status: Status, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.stats.count(status.error_kind());
        let Some(kind) = self.session.request.as_ref().map(|r| r.kind) else {
            return;
        };
        if self.session.announced && self.phase != Phase::Polling {
            return; // a stray status inside a running stream: counted only
        }
        if self.fall_back(status) {
            return self.send_scan_request(now, out);
        }
        if self.phase == Phase::Polling && self.session.announced {
            return self.send_scan_request(now, out);
        }
        let reason = format!(
            "{} rejected with status {}",
            kind.symbol(),
            status.describe()
        );
        self.reconnect(reason, out);
    }

    /// Drops multi-echo (`ND` to `MD`, `NE` to `ME`, `HD` to `GD`, `HE` to
    /// `GE`), or else intensity (`ME` to `MD`, `GE` to `GD`), from the refused
    /// request: counted (`multiecho_unsupported`, `intensity_unsupported`) and
    /// noted for Identity. `false` when the request has neither. The next
    /// connect builds the configured request again.
    fn fall_back(&mut self, status: Status) -> bool {
        let Some(request) = self.session.request.as_mut() else {
            return false;
        };
        let kind = request.kind;
        let note = Some(format!(
            "unsupported ({} rejected with status {})",
            kind.symbol(),
            status.describe()
        ));
        if kind.is_multiecho() {
            request.kind = kind.without_multiecho();
            self.stats.count("multiecho_unsupported");
            self.session.multiecho_note = note;
        } else if kind.has_intensity() {
            request.kind = kind.without_intensity();
            self.stats.count("intensity_unsupported");
            self.session.intensity_note = note;
        } else {
            return false;
        }
        true
    }

    fn on_hardware_fault(&mut self, status: Status, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.stats.count(status.error_kind());
        self.session.hardware_faults += 1;
        if self.session.hardware_faults >= HARDWARE_FAULT_LIMIT {
            let reason = format!(
                "{} hardware-trouble replies in a row, last {}",
                self.session.hardware_faults,
                status.describe()
            );
            return self.recover(reason, now, out);
        }
        if self.phase == Phase::Polling {
            self.send_scan_request(now, out);
        }
    }

    /// A scan that cannot be delivered: counted; polling asks for the next.
    fn dropped_scan(&mut self, kind: &'static str, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.stats.count(kind);
        if self.phase == Phase::Polling {
            self.send_scan_request(now, out);
        }
    }

    /// A scan reply (`99` streamed, `00` polled): decode, stamp, deliver.
    fn on_scan(&mut self, reply: &Reply, now: HostTime, out: &mut Vec<DriverOutput>) {
        let (Some(request), Some(plan)) = (&self.session.request, &self.session.plan) else {
            return;
        };
        let decoded = decode_scan(reply.lines.get(1..).unwrap_or(&[]), request);
        let data = match decoded {
            Ok(data) => data,
            Err(e) => return self.dropped_scan(e.kind(), now, out),
        };
        let Some(rays) = plan.rays(&data) else {
            return self.dropped_scan("incomplete_scan", now, out);
        };
        let polled = self.phase == Phase::Polling;
        if polled && self.session.last_polled_ms == Some(data.timestamp_ms) {
            // Asked again before the next revolution was done: the same scan.
            self.stats.note("repeated_scan");
            return self.send_scan_request(now, out);
        }
        if polled {
            self.session.last_polled_ms = Some(data.timestamp_ms);
        }
        // On RS-232 the reply's bytes take time on the line (8N1: 10 bits a
        // byte: the echo, every line with its LF, the closing LF); over USB
        // that time is negligible.
        let line_bytes: u64 = reply.lines.iter().map(|l| l.len() as u64 + 1).sum();
        let reply_bytes = line_bytes + reply.echo.len() as u64 + 2;
        let transfer_ns = self.session.baud.filter(|b| *b > 0).map_or(0, |b| {
            reply_bytes.saturating_mul(10_000_000_000) / u64::from(b)
        });
        let timing = ScanTiming {
            device_ms: self.session.clock.unwrap(data.timestamp_ms),
            first_ray_delay_ns: plan.first_ray_delay_ns(),
            sweep_ns: plan.sweep_ns(),
            transfer_ns,
            // A poll is answered with the last complete revolution, which may
            // have ended up to a revolution before the request.
            held_ns: if polled {
                self.session
                    .geometry
                    .as_ref()
                    .map_or(0, |g| g.revolution_ns().max(0.0) as u64)
            } else {
                0
            },
            arrival: now,
        };
        let stamp_ns = self.session.stamper.stamp(&timing, &mut self.stats);
        if !self.session.announced {
            self.announce(now, out);
        }
        out.push(DriverOutput::Scan(RangeScan {
            sequence: self.sequence,
            stamp_ns,
            received: now,
            rays,
            stamp_bound: StampBound::Untracked,
        }));
        self.sequence = self.sequence.wrapping_add(1);
        self.stats.scans += 1;
        self.session.hardware_faults = 0;
        if self.phase == Phase::Polling {
            self.send_scan_request(now, out);
        } else {
            self.wait(Phase::Streaming, self.session.stream_timeout_ns, now);
        }
    }

    /// The measurement runs: state, handshake count, Identity.
    fn announce(&mut self, now: HostTime, out: &mut Vec<DriverOutput>) {
        self.session.announced = true;
        self.stats.handshakes += 1;
        self.set_state(DeviceState::Streaming, out);
        out.push(DriverOutput::Identity(self.identity()));
        if self.phase == Phase::StreamStart {
            self.wait(Phase::Streaming, self.session.stream_timeout_ns, now);
        }
    }

    /// Everything `VV`, `PP` and `II` said, plus what the driver runs.
    fn identity(&self) -> Vec<(String, String)> {
        let mut pairs = self.session.identity.clone();
        if let Some(request) = &self.session.request {
            let note = |note: &Option<String>, on: bool| match (note, on) {
                (Some(note), _) => note.clone(),
                (None, true) => "yes".to_owned(),
                (None, false) => "no".to_owned(),
            };
            let intensity = note(&self.session.intensity_note, request.kind.has_intensity());
            let multiecho = note(&self.session.multiecho_note, request.kind.is_multiecho());
            pairs.push(("scan_command".into(), request.kind.symbol().into()));
            pairs.push((
                "steps".into(),
                format!("{}..{}", request.start, request.end),
            ));
            pairs.push(("cluster".into(), request.cluster.to_string()));
            pairs.push(("intensity".into(), intensity));
            pairs.push(("multiecho".into(), multiecho));
        }
        let clock = match self.session.sync.best_rtt_ns() {
            Some(rtt) if !self.session.stamper.is_fallen_back() => {
                format!("TM1 sync, best round trip {} us", rtt / 1000)
            }
            _ => "none (stamps from arrival times)".to_owned(),
        };
        pairs.push(("clock_sync".into(), clock));
        if let Some(baud) = self.session.baud {
            pairs.push(("baud".into(), baud.to_string()));
        }
        pairs
    }

    /// `RB` replies: the first answers `01` (urg_stamped `cbRB`), then the
    /// second `RB` makes the sensor reboot.
    pub(super) fn on_reboot_reply(
        &mut self,
        sent: u8,
        reply: &Reply,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if reply.echo == b"RB" {
            self.after_reboot_reply(sent, now, out);
        }
    }

    /// After the first `RB` (answered or not) the second; after the second,
    /// reconnect.
    pub(super) fn after_reboot_reply(
        &mut self,
        sent: u8,
        now: HostTime,
        out: &mut Vec<DriverOutput>,
    ) {
        if sent < 2 {
            return self.send(&Command::Rb, Phase::Reboot { sent: sent + 1 }, now, out);
        }
        let reason = format!(
            "rebooted the sensor (RB twice) after: {}",
            self.session.recovery
        );
        self.reconnect(reason, out);
    }
}
