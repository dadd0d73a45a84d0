//! The RPLIDAR device state machine: requests in, answers and scan streams
//! out, motor driven by DTR (A1) or SET_MOTOR_PWM (A2), reboot on RESET.
//!
//! Request handling follows the protocol PDF §4: a scan answers its
//! descriptor at once and streams until STOP, RESET or any other accepted
//! request (SET_MOTOR_PWM excepted, which only changes the motor); requests
//! with a bad checksum or an unknown opcode change nothing.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use super::faults::FaultInjector;
use super::measure::Measurer;
use super::model::{ModelSpec, MotorDrive, RplidarModel, StreamFormat, MAX_PWM, NOMINAL_PWM};
use super::motor::Motor;
use super::options::RplidarOptions;
use super::protocol::cmd;
use super::rejects::{RejectCounts, RejectKind};
use super::reply;
use super::request::{Request, RequestParser};
use super::stream::{Stream, StreamContext};
use super::tx::TxBuffer;
use crate::device::{RaySource, SerialDeviceEmulator};

/// Seconds from a RESET request to the boot banner; bytes arriving before it
/// are lost (the PDF asks hosts to wait at least 2 ms after RESET).
pub(crate) const BOOT_S: f64 = 0.002;

/// An emulated Slamtec RPLIDAR A1 or A2 on a serial line.
pub struct RplidarEmulator {
    spec: &'static ModelSpec,
    rays: Box<dyn RaySource>,
    options: RplidarOptions,
    serial: [u8; 16],
    parser: RequestParser,
    motor: Motor,
    dtr_asserted: bool,
    pwm: u16,
    stream: Option<Stream>,
    /// When the core finishes rebooting, while it does.
    booting_until: Option<f64>,
    measurer: Measurer,
    faults: FaultInjector,
    tx: TxBuffer,
    rejects: RejectCounts,
}

impl RplidarEmulator {
    /// A powered-up, idle device of `model` measuring `rays`. Its motor
    /// starts turning at time 0 (DTR released; A2 duty 660) and is stable
    /// after half a second.
    pub fn new(model: RplidarModel, rays: Box<dyn RaySource>, options: RplidarOptions) -> Self {
        let spec = model.spec();
        let mut emulator = Self {
            spec,
            rays,
            options,
            serial: serial_number(options.seed),
            parser: RequestParser::new(),
            motor: Motor::new(spec.rotation_hz, 0.0),
            dtr_asserted: false,
            pwm: NOMINAL_PWM,
            stream: None,
            booting_until: None,
            measurer: Measurer::new(spec, &options),
            faults: FaultInjector::new(options.faults),
            tx: TxBuffer::default(),
            rejects: RejectCounts::default(),
        };
        emulator.motor = Motor::new(spec.rotation_hz, emulator.motor_target_hz());
        emulator
    }

    /// What the device refused or dropped so far.
    pub fn rejects(&self) -> &RejectCounts {
        &self.rejects
    }

    /// Whether a scan session is running (streaming, or waiting for the
    /// motor).
    pub fn is_scanning(&self) -> bool {
        self.stream.is_some()
    }

    /// The motor's current target rotation rate in Hz (0 = stopping or
    /// stopped).
    pub fn motor_target_hz(&self) -> f64 {
        match self.spec.motor {
            MotorDrive::Dtr if self.dtr_asserted => 0.0,
            MotorDrive::Dtr => self.spec.rotation_hz,
            MotorDrive::Pwm => {
                self.spec.rotation_hz * f64::from(self.pwm.min(MAX_PWM)) / f64::from(NOMINAL_PWM)
            }
        }
    }

    /// Brings the device up to `now`: the boot banner if due, then the scan
    /// stream.
    fn advance(&mut self, now: f64) {
        if self.booting_until.is_some_and(|end| end <= now) {
            self.booting_until = None;
            self.tx.send(&reply::banner(self.spec), &mut self.rejects);
        }
        if let Some(stream) = self.stream.as_mut() {
            let mut ctx = StreamContext {
                motor: &self.motor,
                rays: self.rays.as_ref(),
                measurer: &mut self.measurer,
                faults: &mut self.faults,
                tx: &mut self.tx,
                rejects: &mut self.rejects,
            };
            stream.advance(now, &mut ctx);
        }
    }

    fn is_booting(&self) -> bool {
        self.booting_until.is_some()
    }

    /// Applies a change of DTR or PWM to the motor.
    fn update_motor(&mut self, now: f64) {
        let target = self.motor_target_hz();
        if target == self.motor.target_hz() {
            return;
        }
        self.motor.set_target(target, now);
        if let Some(stream) = self.stream.as_mut() {
            stream.on_motor_change(now);
        }
    }

    fn send(&mut self, bytes: &[u8]) {
        self.tx.send(bytes, &mut self.rejects);
    }

    fn handle(&mut self, request: Request, now: f64) {
        match request.cmd {
            cmd::STOP => self.stream = None,
            cmd::RESET => self.reset(now),
            cmd::SCAN => self.start_standard(false, now),
            cmd::FORCE_SCAN => self.start_standard(true, now),
            cmd::EXPRESS_SCAN => self.start_express(&request.payload, now),
            cmd::GET_INFO => self.answer(reply::device_info(self.spec, &self.serial)),
            cmd::GET_HEALTH => self.answer(reply::health(self.options.health)),
            cmd::GET_SAMPLERATE => self.answer(reply::sample_rate(self.spec)),
            cmd::GET_LIDAR_CONF => self.answer_conf(&request.payload),
            cmd::GET_ACC_BOARD_FLAG => self.answer_acc_board(),
            cmd::SET_MOTOR_PWM => self.set_pwm(&request.payload, now),
            _ => self.rejects.count(RejectKind::UnknownCommand),
        }
    }

    /// A single answer ends any scan session first.
    fn answer(&mut self, bytes: Vec<u8>) {
        self.stream = None;
        self.send(&bytes);
    }

    /// RESET: the core reboots as from power-up (scan stopped, A2 duty back
    /// to 660) and prints its banner [`BOOT_S`] later.
    fn reset(&mut self, now: f64) {
        self.stream = None;
        self.parser.reset();
        self.pwm = NOMINAL_PWM;
        self.update_motor(now);
        self.booting_until = Some(now + BOOT_S);
    }

    fn start_standard(&mut self, force: bool, now: f64) {
        let us = u32::from(self.spec.standard_us);
        self.start(StreamFormat::Standard, us, force, now);
    }

    /// EXPRESS_SCAN: the 5-byte payload's `working_mode` 0 selects the legacy
    /// express capsules; a non-zero mode id selects that entry of the
    /// scan-mode table (`sl_lidar_driver.cpp`, `startScanExpress()`).
    fn start_express(&mut self, payload: &[u8], now: f64) {
        let Some(&working_mode) = payload.first().filter(|_| payload.len() >= 5) else {
            self.rejects.count(RejectKind::BadPayload);
            return;
        };
        if working_mode == 0 {
            let us = u32::from(self.spec.express_us);
            return self.start(StreamFormat::Capsule, us, false, now);
        }
        match self.spec.modes.get(usize::from(working_mode)) {
            Some(mode) if mode.format != StreamFormat::Standard => {
                self.start(mode.format, mode.us_per_sample, false, now)
            }
            _ => self.rejects.count(RejectKind::BadPayload),
        }
    }

    /// Answers the loop descriptor and starts streaming, unless the device
    /// is in Protection Stop.
    fn start(&mut self, format: StreamFormat, us_per_sample: u32, force: bool, now: f64) {
        if self.options.health.blocks_scanning() {
            self.rejects.count(RejectKind::ProtectionStop);
            return;
        }
        self.stream = None;
        self.send(&reply::descriptor(
            format.packet_len(),
            true,
            format.answer_type(),
        ));
        self.stream = Some(Stream::new(format, us_per_sample, force, now));
    }

    /// GET_LIDAR_CONF: a u32 key, then (per-mode keys) a u16 mode id, which
    /// reads as 0 when absent.
    fn answer_conf(&mut self, payload: &[u8]) {
        let Some(key) = payload.get(0..4).and_then(|b| b.try_into().ok()) else {
            self.rejects.count(RejectKind::BadPayload);
            return;
        };
        let mode = payload
            .get(4..6)
            .and_then(|b| b.try_into().ok())
            .map_or(0, u16::from_le_bytes);
        match reply::lidar_conf(self.spec, u32::from_le_bytes(key), mode) {
            Some(bytes) => self.answer(bytes),
            None => self.rejects.count(RejectKind::BadPayload),
        }
    }

    fn answer_acc_board(&mut self) {
        match self.spec.motor {
            MotorDrive::Pwm => self.answer(reply::acc_board_flag()),
            MotorDrive::Dtr => self.rejects.count(RejectKind::Unsupported),
        }
    }

    /// SET_MOTOR_PWM (A2): u16 LE duty, saturating at 1023; does not end a
    /// scan session.
    fn set_pwm(&mut self, payload: &[u8], now: f64) {
        if self.spec.motor != MotorDrive::Pwm {
            return self.rejects.count(RejectKind::Unsupported);
        }
        let Some(duty) = payload.get(0..2).and_then(|b| b.try_into().ok()) else {
            return self.rejects.count(RejectKind::BadPayload);
        };
        self.pwm = u16::from_le_bytes(duty).min(MAX_PWM);
        self.update_motor(now);
    }
}

impl SerialDeviceEmulator for RplidarEmulator {
    fn model(&self) -> &'static str {
        self.spec.name
    }

    fn receive(&mut self, bytes: &[u8], now: f64) {
        self.advance(now);
        for &byte in bytes {
            if self.is_booting() {
                self.rejects.count(RejectKind::WhileRebooting);
                continue;
            }
            if let Some(request) = self.parser.push(byte, now, &mut self.rejects) {
                self.handle(request, now);
            }
        }
    }

    fn poll(&mut self, now: f64, out: &mut Vec<u8>) {
        self.advance(now);
        self.tx.drain_into(out);
    }

    fn uart_baud(&self) -> Option<u32> {
        Some(self.spec.baud)
    }

    /// A1: DTR asserted stops the motor, released runs it (the SDK's
    /// `setMotorSpeed()` convention). The A2's motor ignores DTR.
    fn set_dtr(&mut self, asserted: bool, now: f64) {
        if self.spec.motor != MotorDrive::Dtr {
            return;
        }
        self.advance(now);
        self.dtr_asserted = asserted;
        self.update_motor(now);
    }
}

/// A serial number derived from the seed, so that several emulators differ.
fn serial_number(seed: u64) -> [u8; 16] {
    let mut rng = Pcg64::seed_from_u64(seed ^ 0x5EED_5E51_A100_0000);
    let mut serial = [0u8; 16];
    rng.fill(&mut serial);
    serial
}
