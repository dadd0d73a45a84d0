//! Benewake CAN rangefinders on one bus: each unit casts its +x ray into the
//! mesh from its mount, reports at the model's rate (the units take turns,
//! evenly spread over the period), and takes the `5A` CAN configuration
//! commands on its receive id (sensors.md §2.1).
//!
//! When a setting takes effect: the TF03 manual says a new send id works
//! "after it is executed and restarted with saved settings" (V0.4 §4.3.12);
//! the emulator applies the CAN settings when they are saved (`5A 04 11
//! 6F`), as if the unit restarted then. Replies go out on the unit's TX id in
//! force when the command arrived (the manuals give the reply bytes, not the
//! id: the emulator's assumption), so a save's reply still uses the old id.

use super::command::{id, status_reply, u32_le, Command, CommandParser};
use super::measure::{measure, Reading};
use super::model::{BenewakeCanModel, CanModelSpec, Commands, Layout};
use super::settings::CanSettings;
use crate::can_device::bus::Transmitter;
use crate::can_device::signals::encode;
use crate::can_device::CanDeviceEmulator;
use rand::SeedableRng;
use rand_pcg::Pcg64;
use shroud_drivers::assembly::{MountPose, MovingMount};
use shroud_drivers::can::CanFrame;
use shroud_drivers::dbc::{builtin, CanDatabase};
use shroud_sim::world::{MeshRays, RaySource};
use shroud_sim::Bvh;
use std::sync::Arc;

/// Units one emulator drives at most.
pub const MAX_UNITS: usize = 16;
/// Readings older than this at a poll are skipped rather than generated.
const MAX_STALL_S: f64 = 1.0;
/// Legacy TF02 exposure codes (data sheet §9.2: 0x03 short, 0x06 long); the
/// emulator uses the long one for weak returns (below four times the
/// threshold).
const EXPOSURE_SHORT: f64 = 3.0;
const EXPOSURE_LONG: f64 = 6.0;
/// Status byte of a failed save (the manual: `5A 05 11 ER SU`, ER ≠ 0).
const SAVE_FAILED: u8 = 1;

/// One rangefinder on the bus.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitSpec {
    /// The id it sends on; its receive id follows from it
    /// ([`BenewakeCanModel::default_rx_id`]).
    pub id: u32,
    pub extended: bool,
    /// Where it sits in the mesh's frame; it measures along its +x.
    pub mount: MountPose,
}

/// What the emulator counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BenewakeCanCounts {
    /// Readings sent.
    pub readings: u64,
    /// Readings left out by `drop_frame_every`.
    pub dropped: u64,
    /// Readings skipped because the host polled late.
    pub skipped: u64,
    /// Commands answered.
    pub commands: u64,
    /// Complete commands the model does not take (no reply, as the manual's
    /// "fail: no response").
    pub refused: u64,
    /// Frames the DBC refused to encode (a DBC/emulator mismatch).
    pub encode_errors: u64,
}

struct Unit {
    rays: Option<MeshRays>,
    /// In force, set since, saved, and out of the box.
    applied: CanSettings,
    pending: CanSettings,
    saved: CanSettings,
    factory: CanSettings,
    parser: CommandParser,
}

/// Emulated Benewake CAN rangefinders of one model sharing a bus.
pub struct BenewakeCanEmulator {
    model: BenewakeCanModel,
    spec: &'static CanModelSpec,
    db: CanDatabase,
    units: Vec<Unit>,
    tx: Transmitter,
    /// Slot k is unit k mod n's reading of round k / n.
    next_slot: u64,
    drop_frame_every: u64,
    rng: Pcg64,
    counts: BenewakeCanCounts,
}

impl BenewakeCanEmulator {
    /// `units` (at least one, at most [`MAX_UNITS`], distinct ids that fit
    /// their format) measuring `mesh` (none: every reading is invalid).
    /// `drop_frame_every` = n: one reading (the middle unit's) is left out of
    /// every n-th round; 0 = never.
    pub fn new(
        model: BenewakeCanModel,
        units: &[UnitSpec],
        mesh: Option<Arc<Bvh>>,
        drop_frame_every: u64,
        seed: u64,
    ) -> Result<Self, String> {
        let spec = model.spec();
        if units.is_empty() || units.len() > MAX_UNITS {
            return Err(format!(
                "{} emulator: {} rangefinders (1..={MAX_UNITS})",
                spec.name,
                units.len()
            ));
        }
        let db = builtin(spec.dbc)
            .ok_or_else(|| format!("the builtin DBC {:?} is missing", spec.dbc))?;
        let mut made = Vec::with_capacity(units.len());
        for unit in units {
            let settings = CanSettings {
                tx_id: unit.id,
                rx_id: model.default_rx_id(unit.id),
                extended: unit.extended,
                bitrate: default_bitrate_setting(spec),
            };
            if !settings.usable() {
                return Err(format!(
                    "{} rangefinder id {:#x} does not fit a {} frame",
                    spec.name,
                    unit.id,
                    if unit.extended {
                        "extended"
                    } else {
                        "standard"
                    }
                ));
            }
            let rays = match &mesh {
                Some(bvh) => Some(MeshRays::new(
                    bvh.clone(),
                    MovingMount::fixed(unit.mount),
                    0,
                )?),
                None => None,
            };
            made.push(Unit {
                rays,
                applied: settings,
                pending: settings,
                saved: settings,
                factory: settings,
                parser: CommandParser::default(),
            });
        }
        let emulator = Self {
            model,
            spec,
            db,
            units: made,
            tx: Transmitter::new(spec.bitrate),
            next_slot: 0,
            drop_frame_every,
            rng: Pcg64::seed_from_u64(seed),
            counts: BenewakeCanCounts::default(),
        };
        emulator.check_ids()?;
        Ok(emulator)
    }

    /// The model emulated.
    pub fn benewake_model(&self) -> BenewakeCanModel {
        self.model
    }

    /// Each unit's CAN settings in force, in unit order.
    pub fn settings(&self) -> Vec<CanSettings> {
        self.units.iter().map(|u| u.applied).collect()
    }

    /// What was counted so far.
    pub fn counts(&self) -> BenewakeCanCounts {
        self.counts
    }

    /// Two units may not send on one id, nor listen on one.
    fn check_ids(&self) -> Result<(), String> {
        for (i, a) in self.units.iter().enumerate() {
            for b in self.units.iter().skip(i + 1) {
                let (a, b) = (a.applied, b.applied);
                if (a.tx_id, a.extended) == (b.tx_id, b.extended) {
                    return Err(format!(
                        "two {} rangefinders send on id {:#x}",
                        self.spec.name, a.tx_id
                    ));
                }
                if self.spec.commands != Commands::None && a.rx_id == b.rx_id {
                    return Err(format!(
                        "two {} rangefinders listen on id {:#x}",
                        self.spec.name, a.rx_id
                    ));
                }
            }
        }
        Ok(())
    }

    fn period(&self) -> f64 {
        1.0 / self.spec.rate_hz
    }

    fn slot_time(&self, slot: u64) -> f64 {
        let n = self.units.len().max(1) as u64;
        let (round, unit) = (slot / n, slot % n);
        self.period() * (round as f64 + 1.0 + unit as f64 / n as f64)
    }

    /// Generates every reading due by `now`.
    fn generate(&mut self, now: f64) {
        if !now.is_finite() {
            return;
        }
        let n = self.units.len().max(1) as u64;
        let behind = now - MAX_STALL_S - self.slot_time(self.next_slot);
        if behind > 0.0 {
            let rounds = (behind / self.period()).ceil() as u64;
            let slots = rounds.saturating_mul(n);
            self.next_slot = self.next_slot.saturating_add(slots);
            self.counts.skipped = self.counts.skipped.saturating_add(slots);
        }
        // At most a stall's worth of readings (and a little): the bound only
        // keeps absurd times, where a slot no longer moves a float, from
        // looping.
        let budget = ((MAX_STALL_S + 1.0) * self.spec.rate_hz).ceil() as u64 * n + n;
        for _ in 0..budget {
            if self.slot_time(self.next_slot) > now {
                break;
            }
            let slot = self.next_slot;
            self.next_slot = slot.saturating_add(1);
            let (round, unit) = (slot / n, (slot % n) as usize);
            let every = self.drop_frame_every;
            if every != 0 && round % every == every - 1 && unit == self.units.len() / 2 {
                self.counts.dropped += 1;
                continue;
            }
            self.reading(unit, self.slot_time(slot));
        }
    }

    fn reading(&mut self, index: usize, t: f64) {
        let Some(unit) = self.units.get(index) else {
            return;
        };
        let rays = unit.rays.as_ref().map(|r| r as &dyn RaySource);
        let reading = measure(self.spec, rays, t, &mut self.rng);
        let settings = unit.applied;
        match self.encode(reading, t) {
            Ok(mut frame) => {
                frame.id = settings.tx_id;
                frame.extended = settings.extended;
                self.tx.push_single(t, frame);
                self.counts.readings += 1;
            }
            Err(()) => self.counts.encode_errors += 1,
        }
    }

    fn encode(&self, reading: Reading, t: f64) -> Result<CanFrame, ()> {
        let spec = self.spec;
        let dist = reading
            .range_m
            .map_or(f64::from(spec.invalid_cm), |m| (m * 100.0).round());
        let strength = f64::from(reading.strength);
        let values: Vec<(&str, f64)> = match spec.layout {
            Layout::DistStrength => vec![("Dist", dist), ("Strength", strength)],
            Layout::Timestamped => {
                let ms = ((t * 1000.0).round().max(0.0) as u64 & 0xFFFF_FFFF) as f64;
                vec![("Dist", dist), ("Strength", strength), ("Timestamp", ms)]
            }
            Layout::Legacy => {
                let min = f64::from(spec.min_strength.max(1));
                let reliability = match reading.range_m {
                    Some(_) if strength >= 2.0 * min => 8.0,
                    Some(_) => 7.0,
                    None => (1.0 + 5.0 * strength / min).floor().clamp(1.0, 6.0),
                };
                let exposure = if strength < 4.0 * min {
                    EXPOSURE_LONG
                } else {
                    EXPOSURE_SHORT
                };
                vec![
                    ("Dist", dist),
                    ("Strength", strength),
                    ("ExposureTime", exposure),
                    ("Reliability", reliability),
                ]
            }
        };
        encode(&self.db, spec.message, &values).map_err(|_| ())
    }

    /// Sends `bytes` on `settings`' TX id, 8 bytes a frame.
    fn reply(&mut self, settings: CanSettings, bytes: &[u8], now: f64) {
        for chunk in bytes.chunks(8) {
            if let Ok(frame) = CanFrame::new(settings.tx_id, settings.extended, chunk) {
                self.tx.push_single(now, frame);
            }
        }
    }

    fn handle(&mut self, index: usize, command: &Command, now: f64) {
        let spec = self.spec;
        let others: Vec<CanSettings> = (self.units.iter().enumerate())
            .filter(|(i, _)| *i != index)
            .map(|(_, u)| u.applied)
            .collect();
        let Some(unit) = self.units.get_mut(index) else {
            return;
        };
        // A save moves the ids only after its reply: replies go out on the
        // ids in force when the command came.
        let before = unit.applied;
        let reply = match (spec.commands, command.id()) {
            (Commands::None, _) => None,
            (_, id::SAVE) => {
                let p = unit.pending;
                let clash = others
                    .iter()
                    .any(|o| (o.tx_id, o.extended) == (p.tx_id, p.extended) || o.rx_id == p.rx_id);
                let ok = p.usable() && !clash;
                if ok {
                    unit.saved = unit.pending;
                    unit.applied = unit.saved;
                }
                Some(status_reply(id::SAVE, if ok { 0 } else { SAVE_FAILED }))
            }
            (_, id::FACTORY_RESET) => {
                unit.pending = unit.factory;
                unit.saved = unit.factory;
                unit.applied = unit.factory;
                Some(status_reply(id::FACTORY_RESET, 0))
            }
            (Commands::Tf03, code) => tf03_setting(&mut unit.pending, code, command.payload())
                .then(|| status_reply(code, 0)),
            (Commands::Industrial, id::RX_ID_OR_CAN_SETTING) => {
                // The manual gives no reply for this command: the emulator
                // echoes it (its assumption).
                industrial_setting(&mut unit.pending, command.payload())
                    .then(|| command.bytes.clone())
            }
            (Commands::Industrial, _) => None,
        };
        match reply {
            Some(bytes) => {
                self.counts.commands += 1;
                self.reply(before, &bytes, now);
            }
            None => self.counts.refused += 1,
        }
    }
}

/// The TF03's setting commands (V1.2.2 p.14): 0x50 TX id, 0x51 RX id (u32
/// LE), 0x52 bit rate (u32 LE), 0x5D frame type (0 standard, 1 extended).
/// Returns whether the command was taken.
fn tf03_setting(pending: &mut CanSettings, code: u8, payload: &[u8]) -> bool {
    let id = u32_le(payload, 0).filter(|&id| id <= shroud_drivers::can::MAX_EXTENDED_ID);
    match (code, payload.len()) {
        (id::TX_ID, 4) => id.map(|id| pending.tx_id = id).is_some(),
        (id::RX_ID_OR_CAN_SETTING, 4) => id.map(|id| pending.rx_id = id).is_some(),
        (id::BITRATE, 4) => id.map(|rate| pending.bitrate = rate).is_some(),
        (id::FRAME_TYPE, 1) => match payload.first() {
            Some(0) => {
                pending.extended = false;
                true
            }
            Some(1) => {
                pending.extended = true;
                true
            }
            _ => false,
        },
        _ => false,
    }
}

/// The TFmini-i / TF02-i CAN setting (manual §3.2.1): type (0 standard, 1
/// extended), baud code, receive id (u32 LE), send id (u32 LE).
fn industrial_setting(pending: &mut CanSettings, payload: &[u8]) -> bool {
    let (Some(&kind), Some(&baud), Some(rx), Some(tx)) = (
        payload.first(),
        payload.get(1),
        u32_le(payload, 2),
        u32_le(payload, 6),
    ) else {
        return false;
    };
    if payload.len() != 10 || kind > 1 {
        return false;
    }
    let max = shroud_drivers::can::MAX_EXTENDED_ID;
    if rx > max || tx > max {
        return false;
    }
    *pending = CanSettings {
        tx_id: tx,
        rx_id: rx,
        extended: kind == 1,
        bitrate: u32::from(baud),
    };
    true
}

/// The bit-rate field out of the box: the TF03's bit/s, the industrial
/// models' baud code 0x08 (250 kbit/s).
fn default_bitrate_setting(spec: &CanModelSpec) -> u32 {
    match spec.commands {
        Commands::Industrial => 0x08,
        _ => spec.bitrate,
    }
}

impl CanDeviceEmulator for BenewakeCanEmulator {
    fn model(&self) -> &'static str {
        self.spec.name
    }

    fn receive(&mut self, frame: &CanFrame, now: f64) {
        self.generate(now);
        if frame.remote || self.spec.commands == Commands::None {
            return;
        }
        // Either frame format: the TF03 "receive frame supports standard and
        // extended frame" (V1.2.2 Table 6).
        for index in 0..self.units.len() {
            let mut commands = Vec::new();
            match self.units.get_mut(index) {
                Some(unit) if unit.applied.rx_id == frame.id => {
                    unit.parser.push(frame.payload(), &mut commands);
                }
                _ => continue,
            }
            for command in &commands {
                self.handle(index, command, now);
            }
        }
    }

    fn poll(&mut self, now: f64, out: &mut Vec<(f64, CanFrame)>) {
        self.generate(now);
        self.tx.send_until(now, out);
    }
}
