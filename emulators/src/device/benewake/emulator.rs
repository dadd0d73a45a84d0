//! The Benewake rangefinder state machine: data frames at the frame rate,
//! `5A` commands answered per the manuals, settings saved and restored,
//! the UART rate switched after the baud command's reply.

use super::command::{id, reply, Command, CommandParser, RawCommand};
use super::faults::FrameFaults;
use super::frame;
use super::measure::{Ranger, Reading};
use super::model::{BenewakeModel, ModelSpec, TailBytes};
use super::options::BenewakeOptions;
use super::rejects::{RejectCounts, RejectKind};
use super::settings::{is_standard_baud, OutputFormat, Settings};
use crate::device::{RaySource, SerialDeviceEmulator};

/// Bytes held between polls: over five seconds of a 115200-baud line.
pub(crate) const TX_CAPACITY: usize = 64 * 1024;
/// Frames older than this at a poll are skipped rather than generated, as a
/// stalled host's receive buffer would overflow.
const MAX_STALL_S: f64 = 1.0;
/// The original TFmini reports distance mode 0x02 (short) below this range
/// and 0x07 (long) from it; the switching point is this emulator's choice.
const TFMINI_LONG_MODE_M: f64 = 2.0;
const TFMINI_SHORT_MODE: u16 = 0x02;
const TFMINI_LONG_MODE: u16 = 0x07;
/// Status byte of a successful reset, factory reset or save.
const SUCCESS: u8 = 0;

/// An emulated Benewake TFmini / TFmini-S / TFmini Plus / TF-Luna /
/// TF02-Pro on a UART.
pub struct BenewakeEmulator {
    spec: &'static ModelSpec,
    rays: Box<dyn RaySource>,
    options: BenewakeOptions,
    settings: Settings,
    saved: Settings,
    uart_baud: u32,
    /// The UART switches to this once the pending replies are out.
    pending_baud: Option<u32>,
    parser: CommandParser,
    /// Frame k of the current run goes out at `origin + (k + 1) · period`.
    origin: f64,
    next_frame: u64,
    ranger: Ranger,
    faults: FrameFaults,
    tx: Vec<u8>,
    rejects: RejectCounts,
}

impl BenewakeEmulator {
    /// A powered-up device of `model` with factory settings (100 Hz, 9-byte
    /// cm frames, 115200 baud), measuring along the +x axis of `rays`.
    pub fn new(model: BenewakeModel, rays: Box<dyn RaySource>, options: BenewakeOptions) -> Self {
        let spec = model.spec();
        let settings = Settings::factory(spec);
        Self {
            spec,
            rays,
            options,
            settings,
            saved: settings,
            uart_baud: settings.baud,
            pending_baud: None,
            parser: CommandParser::default(),
            origin: 0.0,
            next_frame: 0,
            ranger: Ranger::new(&options),
            faults: FrameFaults::new(options.faults),
            tx: Vec::new(),
            rejects: RejectCounts::default(),
        }
    }

    /// What the device refused or dropped so far.
    pub fn rejects(&self) -> &RejectCounts {
        &self.rejects
    }

    /// The frame rate now set, Hz (0 = trigger mode).
    pub fn frame_rate_hz(&self) -> u16 {
        self.settings.frame_rate_hz
    }

    fn send(&mut self, bytes: &[u8]) {
        let room = TX_CAPACITY.saturating_sub(self.tx.len());
        let fits = bytes.len().min(room);
        self.tx
            .extend_from_slice(bytes.get(..fits).unwrap_or_default());
        let dropped = u64::try_from(bytes.len() - fits).unwrap_or(u64::MAX);
        if dropped > 0 {
            self.rejects.add(RejectKind::TxOverflow, dropped);
        }
    }

    /// Seconds between streamed frames, or `None` when none stream.
    fn streaming_period(&self) -> Option<f64> {
        self.settings
            .frame_period_s(self.spec)
            .filter(|_| self.settings.output_enabled)
    }

    fn frame_time(&self, period: f64, frame: u64) -> f64 {
        self.origin + (frame as f64 + 1.0) * period
    }

    /// Restarts the frame clock at `now` (after a rate, enable or reset
    /// change).
    fn restart_frames(&mut self, now: f64) {
        self.origin = now;
        self.next_frame = 0;
    }

    /// Sends every frame due by `now`.
    fn advance(&mut self, now: f64) {
        let Some(period) = self.streaming_period() else {
            return;
        };
        let behind = now - MAX_STALL_S - self.frame_time(period, self.next_frame);
        if behind > 0.0 {
            let skipped = (behind / period).ceil();
            self.rejects.add(RejectKind::StalledHost, skipped as u64);
            self.next_frame = self.next_frame.saturating_add(skipped as u64);
        }
        while self.frame_time(period, self.next_frame) <= now {
            let t = self.frame_time(period, self.next_frame);
            self.send_frame(t);
            self.next_frame = self.next_frame.saturating_add(1);
        }
    }

    fn send_frame(&mut self, t: f64) {
        let reading = self.ranger.measure(self.spec, self.rays.as_ref(), t);
        let (garbage, broken) = self.faults.next_frame();
        self.send(&garbage);
        let bytes = self.encode(reading, broken);
        self.send(&bytes);
    }

    fn encode(&self, reading: Reading, broken: bool) -> Vec<u8> {
        let invalid = self.spec.invalid.distance;
        let field = |per_metre: f64| {
            reading.range_m.map_or(invalid, |m| {
                (m * per_metre).round().clamp(0.0, 65535.0) as u16
            })
        };
        let distance = match self.settings.format {
            OutputFormat::Centimetres => field(100.0),
            OutputFormat::Millimetres => field(1000.0),
            OutputFormat::Pix => return frame::pix(self.pix_metres(reading)),
        };
        frame::standard(distance, reading.strength, self.tail(reading), broken).to_vec()
    }

    /// Pix reports metres; an unreliable reading reads as the model's
    /// invalid distance in metres, −1 for the models that send 0xFFFF (the
    /// TFmini manual: "-1 in case of Pixhawk data format").
    fn pix_metres(&self, reading: Reading) -> f64 {
        match (reading.range_m, self.spec.invalid.distance) {
            (Some(m), _) => m,
            (None, 0xFFFF) => -1.0,
            (None, invalid) => f64::from(invalid) / 100.0,
        }
    }

    fn tail(&self, reading: Reading) -> u16 {
        match self.spec.tail {
            TailBytes::Temperature => frame::temperature_raw(self.options.temperature_c),
            TailBytes::DistanceMode => match reading.range_m {
                Some(m) if m < TFMINI_LONG_MODE_M => TFMINI_SHORT_MODE,
                _ => TFMINI_LONG_MODE,
            },
        }
    }

    fn handle(&mut self, raw: RawCommand, now: f64) {
        if !self.spec.has_commands {
            return self.rejects.count(RejectKind::Unsupported);
        }
        let Some(command) = Command::parse(&raw) else {
            return self.rejects.count(RejectKind::UnknownCommand);
        };
        match command {
            Command::Version => self.send(&reply(id::VERSION, &self.spec.version)),
            Command::SoftReset => self.soft_reset(now),
            Command::FrameRate(rate) => {
                self.settings.frame_rate_hz = rate;
                self.restart_frames(now);
                self.send(&reply(id::FRAME_RATE, &raw.payload));
            }
            Command::Trigger => self.trigger(now),
            Command::OutputFormat(format) => self.set_format(format, &raw.payload),
            Command::BaudRate(baud) => self.set_baud(baud, &raw.payload),
            Command::OutputEnable(flag) => self.set_output(flag, &raw.payload, now),
            Command::ChecksumEnable(flag) => self.set_checksum(flag, &raw.payload),
            Command::FactoryReset => {
                self.settings = Settings::factory(self.spec);
                self.saved = self.settings;
                self.pending_baud = Some(self.settings.baud);
                self.restart_frames(now);
                self.send(&reply(id::FACTORY_RESET, &[SUCCESS]));
            }
            Command::Save => {
                self.saved = self.settings;
                self.send(&reply(id::SAVE, &[SUCCESS]));
            }
        }
    }

    /// ID 0x02: replies success, then restarts with the saved settings.
    fn soft_reset(&mut self, now: f64) {
        self.send(&reply(id::SOFT_RESET, &[SUCCESS]));
        self.settings = self.saved;
        self.pending_baud = Some(self.settings.baud);
        self.parser.reset();
        self.restart_frames(now);
    }

    /// ID 0x04: one frame, in trigger mode (frame rate 0) with output on.
    fn trigger(&mut self, now: f64) {
        if self.settings.frame_rate_hz == 0 && self.settings.output_enabled {
            self.send_frame(now);
        } else {
            self.rejects.count(RejectKind::IgnoredTrigger);
        }
    }

    fn set_format(&mut self, format: u8, payload: &[u8]) {
        match OutputFormat::from_id(format) {
            Some(format) => {
                self.settings.format = format;
                self.send(&reply(id::OUTPUT_FORMAT, payload));
            }
            None => self.rejects.count(RejectKind::BadPayload),
        }
    }

    /// ID 0x06: echoes, then the UART runs at the new rate once the echo is
    /// out.
    fn set_baud(&mut self, baud: u32, payload: &[u8]) {
        if !is_standard_baud(baud) {
            return self.rejects.count(RejectKind::BadPayload);
        }
        self.settings.baud = baud;
        self.pending_baud = Some(baud);
        self.send(&reply(id::BAUD_RATE, payload));
    }

    fn set_output(&mut self, flag: u8, payload: &[u8], now: f64) {
        let Some(enabled) = flag_value(flag) else {
            return self.rejects.count(RejectKind::BadPayload);
        };
        self.settings.output_enabled = enabled;
        self.restart_frames(now);
        self.send(&reply(id::OUTPUT_ENABLE, payload));
    }

    /// ID 0x08 (TF-Luna): 1 = check command sums, 0 = ignore them.
    fn set_checksum(&mut self, flag: u8, payload: &[u8]) {
        if !self.spec.checksum_switch {
            return self.rejects.count(RejectKind::UnknownCommand);
        }
        let Some(check) = flag_value(flag) else {
            return self.rejects.count(RejectKind::BadPayload);
        };
        self.settings.check_sums = check;
        self.send(&reply(id::CHECKSUM_ENABLE, payload));
    }
}

fn flag_value(flag: u8) -> Option<bool> {
    match flag {
        0 => Some(false),
        1 => Some(true),
        _ => None,
    }
}

impl SerialDeviceEmulator for BenewakeEmulator {
    fn model(&self) -> &'static str {
        self.spec.name
    }

    fn receive(&mut self, bytes: &[u8], now: f64) {
        self.advance(now);
        for &byte in bytes {
            let check_sums = self.settings.check_sums;
            if let Some(raw) = self.parser.push(byte, check_sums, &mut self.rejects) {
                self.handle(raw, now);
            }
        }
    }

    fn poll(&mut self, now: f64, out: &mut Vec<u8>) {
        self.advance(now);
        out.append(&mut self.tx);
        if let Some(baud) = self.pending_baud.take() {
            self.uart_baud = baud;
        }
    }

    fn uart_baud(&self) -> Option<u32> {
        Some(self.uart_baud)
    }
}
