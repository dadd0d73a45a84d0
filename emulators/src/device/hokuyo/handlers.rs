//! What the sensor does with each command line: the SCIP 1.1 fallback, the
//! mode checks (time-adjust, abnormal) and every SCIP 2.0 command.

use super::codec::{encode_into, Reply};
use super::command::{self, Command, ScanRequest, StreamRequest, TimeControl};
use super::device::{HokuyoEmulator, Protocol, Stream};
use super::framer::Line;
use super::info::{self, SensorState};
use super::options::Link;
use super::stats::Rejection;
use super::status::{self, Status};

/// Two RBs at most this far apart reboot the sensor (urg_stamped PR #71:
/// "Sending it 2 times in 1 sec. is needed").
const REBOOT_CONFIRM_SECONDS: f64 = 1.0;

/// The commands an abnormal sensor still answers normally.
const ANSWERED_WHEN_ABNORMAL: [&[u8; 2]; 4] = [b"VV", b"PP", b"II", b"RB"];

impl HokuyoEmulator {
    /// Answers one command line received at `now`.
    pub(crate) fn handle_line(&mut self, line: &Line, now: f64) {
        self.stats.commands += 1;
        let echo = line.bytes.as_slice();
        if line.overflowed {
            self.refuse(now, echo, status::BUFFER_SHORTAGE, Rejection::LineTooLong);
            return;
        }
        match self.sensor.protocol {
            Protocol::Scip11 => self.handle_scip11(echo, now),
            Protocol::Scip20 => self.handle_scip20(echo, now),
        }
    }

    /// SCIP 1.1: only the switch command is emulated (spec §2, p. 3: reply
    /// `SCIP2.0` / `0` / LF). Anything else gets the echo and the 1.1 error
    /// status `E` without a sum, which urg_c's `connect_urg_device()` takes
    /// as "SCIP 1.1, send SCIP2.0".
    fn handle_scip11(&mut self, echo: &[u8], now: f64) {
        let status: &[u8] = if echo == b"SCIP2.0" {
            self.sensor.protocol = Protocol::Scip20;
            b"0"
        } else {
            self.stats.count_rejection(Rejection::Scip11Mode);
            b"E"
        };
        let mut reply = Vec::with_capacity(echo.len() + 4);
        reply.extend_from_slice(echo);
        reply.push(b'\n');
        reply.extend_from_slice(status);
        reply.extend_from_slice(b"\n\n");
        self.send(now, reply);
    }

    fn handle_scip20(&mut self, echo: &[u8], now: f64) {
        let symbol = echo.get(..2).unwrap_or_default();
        if self.sensor.time_adjust && symbol != b"TM" {
            // Spec §8.6: no other command is accepted in adjust mode.
            self.refuse(now, echo, status::UNDEFINED, Rejection::TimeAdjustMode);
            return;
        }
        let answered = ANSWERED_WHEN_ABNORMAL
            .iter()
            .any(|s| s.as_slice() == symbol);
        if self.sensor.abnormal && !answered {
            self.refuse(now, echo, status::ABNORMAL, Rejection::Abnormal);
            return;
        }
        match command::parse(echo, self.spec) {
            Ok(command) => self.execute(command, echo, now),
            Err(refusal) => self.refuse(now, echo, refusal.status, refusal.kind),
        }
    }

    fn refuse(&mut self, now: f64, echo: &[u8], status: Status, kind: Rejection) {
        self.stats.count_rejection(kind);
        self.reply(now, echo, status);
    }

    fn execute(&mut self, command: Command, echo: &[u8], now: f64) {
        match command {
            Command::Version => self.answer_version(echo, now),
            Command::Parameters => self.answer_parameters(echo, now),
            Command::Info => self.answer_info(echo, now),
            Command::LaserOn => self.laser_on(echo, now),
            Command::Quit => self.quit(echo, now),
            Command::Reset => self.reset(echo, now),
            Command::Reboot => self.reboot(echo, now),
            Command::Time(control) => self.time(control, echo, now),
            Command::BitRate(rate) => self.bit_rate(rate, echo, now),
            Command::Stream(request) => self.start_stream(request, echo, now),
            Command::Single(request) => self.single_scan(&request, echo, now),
        }
    }

    fn answer_version(&mut self, echo: &[u8], now: f64) {
        let mut reply = Reply::new(echo, status::OK);
        info::write_version(&mut reply, self.model);
        self.send(now, reply.finish());
    }

    fn answer_parameters(&mut self, echo: &[u8], now: f64) {
        let mut reply = Reply::new(echo, status::OK);
        info::write_parameters(&mut reply, self.model, self.spec);
        self.send(now, reply.finish());
    }

    fn answer_info(&mut self, echo: &[u8], now: f64) {
        let state = SensorState {
            laser_on: self.sensor.laser_on,
            streaming: self.sensor.stream.is_some(),
            abnormal: self.sensor.abnormal,
            bit_rate: self.sensor.bit_rate,
            clock_ms: self.sensor.clock.ms_at(now),
        };
        let mut reply = Reply::new(echo, status::OK);
        info::write_info(&mut reply, self.model, self.spec, &state);
        self.send(now, reply.finish());
    }

    /// BM: 00, or 02 when the laser is already on (spec §8.3, p. 14).
    fn laser_on(&mut self, echo: &[u8], now: f64) {
        let status = if self.sensor.laser_on {
            status::CODE_02
        } else {
            self.sensor.laser_on = true;
            status::OK
        };
        self.reply(now, echo, status);
    }

    /// QT: laser off, stream stopped (spec §8.4, p. 14).
    fn quit(&mut self, echo: &[u8], now: f64) {
        self.stop_measuring();
        self.reply(now, echo, status::OK);
    }

    /// RS: laser off, stream stopped, bit rate back to the power-on rate
    /// once the reply is sent, clock reset to 0 (spec §8.5, p. 14).
    fn reset(&mut self, echo: &[u8], now: f64) {
        self.stop_measuring();
        self.sensor.clock = super::timing::DeviceClock::new(0, now);
        self.reply(now, echo, status::OK);
        if let Link::Rs232 { baud } = self.options.link {
            self.sensor.bit_rate = Some(baud);
            self.output.change_baud_after_queued(now, baud);
        } else if self.sensor.bit_rate.is_some() {
            self.sensor.bit_rate = Some(self.spec.default_bit_rate);
        }
    }

    /// RB: the first answers 01; a second within one second answers 00 and
    /// reboots the sensor once the reply is out (urg_stamped `urg_sim.cpp`
    /// `handleRB`; urg_c `urg_reboot()` accepts 00 and 01).
    fn reboot(&mut self, echo: &[u8], now: f64) {
        let confirmed = self
            .sensor
            .reboot_requested_at
            .is_some_and(|first| now - first <= REBOOT_CONFIRM_SECONDS);
        if !confirmed {
            self.sensor.reboot_requested_at = Some(now);
            self.reply(now, echo, status::CODE_01);
            return;
        }
        self.reply(now, echo, status::OK);
        let reply_sent = self.output.busy_until().max(now);
        self.start_reboot(reply_sent);
    }

    /// TM0/TM1/TM2 (spec §8.6, p. 15): 02 already in adjust mode, 03 not in
    /// it, 04 time asked outside it. TM1 adds the 4-character clock line.
    fn time(&mut self, control: TimeControl, echo: &[u8], now: f64) {
        let adjusting = self.sensor.time_adjust;
        match control {
            TimeControl::AdjustOn if adjusting => self.wrong_state(now, echo, status::CODE_02),
            TimeControl::AdjustOff if !adjusting => self.wrong_state(now, echo, status::CODE_03),
            TimeControl::Read if !adjusting => self.wrong_state(now, echo, status::CODE_04),
            TimeControl::AdjustOn => {
                // "When the sensor is in adjustment mode laser is switched off".
                self.stop_measuring();
                self.sensor.time_adjust = true;
                self.reply(now, echo, status::OK);
            }
            TimeControl::AdjustOff => {
                self.sensor.time_adjust = false;
                self.reply(now, echo, status::OK);
            }
            TimeControl::Read => {
                let mut time = Vec::with_capacity(4);
                encode_into(self.sensor.clock.ms_at(now), 4, &mut time);
                let mut reply = Reply::new(echo, status::OK);
                reply.line_with_sum(&time);
                self.send(now, reply.finish());
            }
        }
    }

    fn wrong_state(&mut self, now: f64, echo: &[u8], status: Status) {
        self.refuse(now, echo, status, Rejection::WrongState);
    }

    /// SS (spec §8.7, p. 16): 04 on a model without RS-232, 02 for a rate
    /// the model lacks, 03 for the current rate; else 00, and on an RS-232
    /// link the new rate applies once the reply is sent. Over USB the
    /// setting is kept for a later RS-232 connection.
    fn bit_rate(&mut self, rate: u32, echo: &[u8], now: f64) {
        if self.spec.bit_rates.is_empty() {
            return self.wrong_state(now, echo, status::CODE_04);
        }
        if !self.spec.bit_rates.contains(&rate) {
            return self.refuse(now, echo, status::CODE_02, Rejection::BadParameter);
        }
        if self.sensor.bit_rate == Some(rate) {
            return self.wrong_state(now, echo, status::CODE_03);
        }
        self.sensor.bit_rate = Some(rate);
        self.reply(now, echo, status::OK);
        self.output.change_baud_after_queued(now, rate);
    }

    /// MD/MS/ME/ND/NE: acknowledge, switch the laser on, and send scans of the
    /// revolutions that start after now (spec §8.1, p. 10: "measurement data
    /// that was taken after the command was received"). A new stream
    /// replaces a running one.
    fn start_stream(&mut self, request: StreamRequest, echo: &[u8], now: f64) {
        self.reply(now, echo, status::OK);
        self.sensor.laser_on = true;
        self.sensor.stream = Some(Stream {
            request,
            next_revolution: self.sensor.rotation.first_starting_at_or_after(now),
            remaining: (request.scans != 0).then_some(request.scans),
            line: echo.to_vec(),
        });
    }

    /// GD/GS/GE/HD/HE: the latest complete revolution, or 10 with the laser
    /// off (spec §8.2, p. 13; HD/HE assumed to behave as GD/GE).
    fn single_scan(&mut self, request: &ScanRequest, echo: &[u8], now: f64) {
        if !self.sensor.laser_on {
            return self.wrong_state(now, echo, status::LASER_OFF);
        }
        let revolution = self.sensor.rotation.latest_ready_at(now);
        self.send_scan(now, echo, status::OK, revolution, request);
    }

    fn stop_measuring(&mut self) {
        self.sensor.stream = None;
        self.sensor.laser_on = false;
    }
}
