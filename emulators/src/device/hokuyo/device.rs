//! The emulator: sensor state, the passage of time (revolutions, stream
//! scans, reboot) and the [`SerialDeviceEmulator`] interface. Command
//! handling is in `handlers.rs`.

use super::codec::{data_line_count, encode_into, Reply};
use super::command::{DataEncoding, ScanRequest, StreamRequest};
use super::echo::{encode_echoes, max_payload_len, EchoSampler, StepEchoes};
use super::faults::FaultInjector;
use super::framer::LineFramer;
use super::model::{HokuyoModel, ModelSpec};
use super::options::{HokuyoOptions, Link};
use super::output::OutputLine;
use super::scan::{encode_values, measure_scan, Measurement, Sampler, ScanSetup};
use super::stats::HokuyoStats;
use super::status::{self, Status};
use super::timing::{DeviceClock, Rotation};
use crate::device::{RaySource, SerialDeviceEmulator};

/// Most stream scans handled in one step of time; a longer gap skips the
/// rest (they would not fit the output buffer anyway).
const MAX_SCANS_PER_ADVANCE: u32 = 10_000;

/// Which protocol the sensor speaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Protocol {
    Scip11,
    Scip20,
}

/// A running MD/MS/ME/ND/NE stream.
#[derive(Debug)]
pub(crate) struct Stream {
    pub(crate) request: StreamRequest,
    /// The revolution of the next scan to send.
    pub(crate) next_revolution: u64,
    /// Scans left to send; `None` = until stopped.
    pub(crate) remaining: Option<u32>,
    /// The command line, whose scans' echoes carry the remaining count in
    /// place of the requested one (spec p. 11).
    pub(crate) line: Vec<u8>,
}

/// The sensor's state from power-on; a reboot starts it afresh.
#[derive(Debug)]
pub(crate) struct Sensor {
    pub(crate) protocol: Protocol,
    pub(crate) laser_on: bool,
    pub(crate) time_adjust: bool,
    pub(crate) stream: Option<Stream>,
    pub(crate) clock: DeviceClock,
    pub(crate) rotation: Rotation,
    /// The RS-232 bit-rate setting; `None` for a model without RS-232.
    pub(crate) bit_rate: Option<u32>,
    pub(crate) abnormal: bool,
    /// When the last unanswered first RB arrived.
    pub(crate) reboot_requested_at: Option<f64>,
    /// While rebooting: when the sensor is back.
    pub(crate) rebooting_until: Option<f64>,
}

/// An emulated Hokuyo URG-04LX or UTM-30LX on a USB or RS-232 link.
pub struct HokuyoEmulator {
    pub(crate) model: HokuyoModel,
    pub(crate) spec: &'static ModelSpec,
    pub(crate) rays: Box<dyn RaySource>,
    pub(crate) options: HokuyoOptions,
    /// The latest time seen.
    pub(crate) now: f64,
    pub(crate) framer: LineFramer,
    pub(crate) output: OutputLine,
    pub(crate) sensor: Sensor,
    pub(crate) sampler: Sampler,
    pub(crate) echo_sampler: EchoSampler,
    pub(crate) faults: FaultInjector,
    pub(crate) stats: HokuyoStats,
    /// Whether `abnormal_after_scans` is still to happen.
    pub(crate) abnormal_armed: bool,
    measurements: Vec<Measurement>,
    echoes: Vec<StepEchoes>,
}

impl HokuyoEmulator {
    /// A sensor of `model` that measures `rays`, powered on at time 0.
    pub fn new(model: HokuyoModel, rays: Box<dyn RaySource>, options: HokuyoOptions) -> Self {
        let spec = model.spec();
        let link_baud = match options.link {
            Link::Usb => None,
            Link::Rs232 { baud } => Some(baud),
        };
        let sensor = Sensor::power_on(spec, &options, 0.0, options.clock_start_ms);
        let mut emulator = HokuyoEmulator {
            model,
            spec,
            rays,
            now: 0.0,
            framer: LineFramer::default(),
            output: OutputLine::new(link_baud),
            sensor,
            sampler: Sampler::new(
                options.seed,
                options.range_noise_scale,
                options.dropout_probability,
            ),
            echo_sampler: EchoSampler::new(options.seed, options.multi_echo_fraction),
            faults: FaultInjector::new(options.faults),
            stats: HokuyoStats::default(),
            abnormal_armed: options.abnormal_after_scans.is_some(),
            measurements: Vec::new(),
            echoes: Vec::new(),
            options,
        };
        emulator.check_abnormal();
        emulator
    }

    /// What the emulator has done so far.
    pub fn stats(&self) -> &HokuyoStats {
        &self.stats
    }

    /// Moves time to `now` (never backwards), sending what falls due:
    /// stream scans, and the end of a reboot.
    pub(crate) fn advance(&mut self, now: f64) {
        let now = if now.is_finite() {
            now.max(self.now)
        } else {
            self.now
        };
        let mut budget = MAX_SCANS_PER_ADVANCE;
        loop {
            let boot = self.sensor.rebooting_until.filter(|&t| t <= now);
            let scan = self.next_scan_time().filter(|&t| t <= now);
            match (boot, scan) {
                (Some(t), _) => self.finish_reboot(t),
                (None, Some(_)) if budget == 0 && !self.sensor.abnormal => self.skip_stream_to(now),
                (None, Some(t)) => {
                    budget -= 1;
                    self.stream_event(t);
                }
                (None, None) => break,
            }
        }
        self.output.advance(now);
        self.now = now;
    }

    fn next_scan_time(&self) -> Option<f64> {
        let stream = self.sensor.stream.as_ref()?;
        Some(self.sensor.rotation.ready_time(stream.next_revolution))
    }

    /// Sends the stream's next scan, due at `t`.
    fn stream_event(&mut self, t: f64) {
        let Some(mut stream) = self.sensor.stream.take() else {
            return;
        };
        if self.sensor.abnormal {
            // The stream ends with the abnormal status in place of the scan.
            let echo = stream_echo(&stream.line, stream.remaining.unwrap_or(0));
            self.reply(t, &echo, status::ABNORMAL);
            return;
        }
        let revolution = stream.next_revolution;
        let remaining = stream.remaining.map(|r| r.saturating_sub(1));
        let echo = stream_echo(&stream.line, remaining.unwrap_or(0));
        let request = stream.request.scan;
        stream.remaining = remaining;
        let step = u64::from(stream.request.interval) + 1;
        stream.next_revolution = revolution.saturating_add(step);
        if remaining == Some(0) {
            // Spec p. 10: the laser goes off after the requested scans.
            self.sensor.laser_on = false;
        } else {
            self.sensor.stream = Some(stream);
        }
        if self.output.is_busy_at(t) {
            self.stats.scans_skipped_link_busy += 1;
        } else if !self.output.has_room(scan_message_len(echo.len(), &request)) {
            self.stats.scans_skipped_output_full += 1;
        } else {
            self.send_scan(t, &echo, status::STREAMING, revolution, &request);
        }
    }

    /// Skips, unsent, every stream scan due by `now`.
    fn skip_stream_to(&mut self, now: f64) {
        let rotation = self.sensor.rotation;
        let Some(stream) = self.sensor.stream.as_mut() else {
            return;
        };
        let step = u64::from(stream.request.interval) + 1;
        let last_ready = rotation.latest_ready_at(now).max(stream.next_revolution);
        let due = last_ready.saturating_sub(stream.next_revolution) / step + 1;
        let skipped = stream.remaining.map_or(due, |r| due.min(u64::from(r)));
        stream.next_revolution = stream
            .next_revolution
            .saturating_add(skipped.saturating_mul(step));
        stream.remaining = stream
            .remaining
            .map(|r| r.saturating_sub(u32::try_from(skipped).unwrap_or(u32::MAX)));
        self.stats.scans_skipped_output_full =
            self.stats.scans_skipped_output_full.saturating_add(skipped);
        let finished = stream.remaining == Some(0);
        // Guards the time loop should the revolution count saturate.
        let stuck = self.next_scan_time().is_some_and(|t| t <= now);
        if finished || stuck {
            self.sensor.stream = None;
            self.sensor.laser_on = false;
        }
    }

    /// Measures revolution `revolution` for `request` and sends it as a
    /// scan message (echo, status, timestamp, data), with the configured
    /// faults.
    pub(crate) fn send_scan(
        &mut self,
        t: f64,
        echo: &[u8],
        status: Status,
        revolution: u64,
        request: &ScanRequest,
    ) {
        let setup = ScanSetup {
            rays: self.rays.as_ref(),
            spec: self.spec,
            rotation: self.sensor.rotation,
        };
        measure_scan(
            &setup,
            &mut self.sampler,
            revolution,
            request,
            &mut self.measurements,
        );
        let payload = self.encode_scan(request);
        self.stats.scans_sent += 1;
        let faults = self
            .faults
            .for_scan(self.stats.scans_sent, data_line_count(payload.len()));
        // The spec does not say which moment the timestamp marks; Hokuyo's
        // own ROS driver (urg_node `urg_c_wrapper.cpp`,
        // `getAngularTimeOffset()`) takes it as the beam passing the rear
        // centre, half a turn from the front step (AFRT - ARES/2), which for
        // these models is before step 0 of the same revolution.
        let mut timestamp = Vec::with_capacity(4);
        let scan_start = self.sensor.rotation.start(revolution);
        let rear_steps_before_zero = (self.spec.ares / 2).saturating_sub(self.spec.afrt);
        let rear = scan_start
            - self.sensor.rotation.period * f64::from(rear_steps_before_zero)
                / f64::from(self.spec.ares.max(1));
        encode_into(self.sensor.clock.ms_at(rear), 4, &mut timestamp);
        let mut reply = Reply::new(echo, status);
        reply.line_with_sum(&timestamp);
        reply.data_blocks(&payload, faults.corrupt_line);
        self.send(t, faults.garbage);
        self.send(t, reply.finish());
        self.check_abnormal();
    }

    /// The data of the measured scan, before cutting into lines; for a
    /// multi-echo request with the further echoes drawn now.
    fn encode_scan(&mut self, request: &ScanRequest) -> Vec<u8> {
        let mut payload = Vec::with_capacity(self.measurements.len() * 6);
        let encoding = request.format.encoding;
        if request.format.multi_echo {
            let firsts = &self.measurements;
            self.echo_sampler
                .add_echoes(self.spec, firsts, &mut self.echoes);
            encode_echoes(&self.echoes, encoding, &mut payload);
        } else {
            encode_values(&self.measurements, encoding, &mut payload);
        }
        payload
    }

    /// Enters the abnormal state once `abnormal_after_scans` scans are sent.
    fn check_abnormal(&mut self) {
        let due = self
            .options
            .abnormal_after_scans
            .is_some_and(|n| self.stats.scans_sent >= n);
        if self.abnormal_armed && due {
            self.abnormal_armed = false;
            self.sensor.abnormal = true;
            self.sensor.laser_on = false;
        }
    }

    /// Queues `bytes` made at `t`, counting them if the buffer is full.
    pub(crate) fn send(&mut self, t: f64, bytes: Vec<u8>) {
        let len = bytes.len() as u64;
        if !self.output.send(t, bytes) {
            self.stats.bytes_dropped_output_full += len;
        }
    }

    /// Sends a reply made of the echo and a status line only.
    pub(crate) fn reply(&mut self, t: f64, echo: &[u8], status: Status) {
        self.send(t, Reply::new(echo, status).finish());
    }

    /// Starts a reboot at `t`: silent and deaf for `reboot_seconds`.
    pub(crate) fn start_reboot(&mut self, t: f64) {
        let seconds = self.options.reboot_seconds;
        let seconds = if seconds.is_finite() {
            seconds.max(0.0)
        } else {
            0.0
        };
        self.sensor.stream = None;
        self.sensor.laser_on = false;
        self.sensor.rebooting_until = Some(t + seconds);
        self.framer.clear();
    }

    /// The sensor is back at `t`: power-on state, clock from 0, link at its
    /// power-on rate.
    fn finish_reboot(&mut self, t: f64) {
        self.sensor = Sensor::power_on(self.spec, &self.options, t, 0);
        if let Link::Rs232 { baud } = self.options.link {
            self.output.change_baud_after_queued(t, baud);
        }
        self.framer.clear();
    }
}

impl Sensor {
    /// The state at power-on at time `t`, the clock reading `clock_ms`.
    pub(crate) fn power_on(
        spec: &ModelSpec,
        options: &HokuyoOptions,
        t: f64,
        clock_ms: u32,
    ) -> Self {
        let link_rate = match options.link {
            Link::Usb => spec.default_bit_rate,
            Link::Rs232 { baud } => baud,
        };
        let bit_rate = (!spec.bit_rates.is_empty()).then_some(link_rate);
        Sensor {
            protocol: if options.starts_in_scip1 {
                Protocol::Scip11
            } else {
                Protocol::Scip20
            },
            laser_on: false,
            time_adjust: false,
            stream: None,
            clock: DeviceClock::new(clock_ms, t),
            rotation: Rotation::new(t, spec.period(), spec.ares, spec.amax),
            bit_rate,
            abnormal: false,
            reboot_requested_at: None,
            rebooting_until: None,
        }
    }
}

/// The echo of a stream scan: the command with `remaining` in place of the
/// 2-digit scan count (characters 13-14), the `;string` kept.
fn stream_echo(line: &[u8], remaining: u32) -> Vec<u8> {
    let mut echo = Vec::with_capacity(line.len());
    echo.extend_from_slice(line.get(..13).unwrap_or(line));
    let count = remaining.min(99);
    // `count` < 100, so both digits are < 10.
    echo.push(b'0' + (count / 10) as u8);
    echo.push(b'0' + (count % 10) as u8);
    echo.extend_from_slice(line.get(15..).unwrap_or_default());
    echo
}

/// The length of a scan message for `request` with an echo of `echo_len`;
/// for a multi-echo request the longest it can be.
fn scan_message_len(echo_len: usize, request: &ScanRequest) -> usize {
    let steps = request.end.saturating_sub(request.start) as usize + 1;
    let values = steps.div_ceil(request.cluster.max(1) as usize);
    let width = match request.format.encoding {
        DataEncoding::TwoChar => 2,
        DataEncoding::ThreeChar => 3,
        DataEncoding::WithIntensity => 6,
    };
    let payload = if request.format.multi_echo {
        max_payload_len(values, width)
    } else {
        values * width
    };
    // Echo+LF, "99b"+LF, timestamp+sum+LF, data lines with sum+LF, LF.
    echo_len + 1 + 4 + 6 + payload + 2 * data_line_count(payload) + 1
}

impl SerialDeviceEmulator for HokuyoEmulator {
    fn model(&self) -> &'static str {
        self.model.name()
    }

    fn receive(&mut self, bytes: &[u8], now: f64) {
        self.advance(now);
        for &byte in bytes {
            if self.sensor.rebooting_until.is_some() {
                self.stats
                    .count_rejection(super::stats::Rejection::Rebooting);
                continue;
            }
            if let Some(line) = self.framer.push(byte) {
                self.handle_line(&line, self.now);
            }
        }
    }

    fn poll(&mut self, now: f64, out: &mut Vec<u8>) {
        self.advance(now);
        self.output.drain(self.now, out);
    }

    fn uart_baud(&self) -> Option<u32> {
        self.output.baud()
    }
}
