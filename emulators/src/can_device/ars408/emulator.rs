//! The ARS408-21 state machine: 0x201 RadarState every 50 ms, 0x700
//! VersionID every second, a measurement cycle every 72 ms (clusters or
//! objects, per the configuration), and 0x200 RadarConfiguration applied as
//! it arrives (sensors.md §2.2).
//!
//! When a configuration takes effect: the radar applies a 0x200 at once, so
//! the next 0x201 reports it, and the next cycle uses it; a cycle already on
//! the bus finishes as it began. A new SensorID moves every id, 0x201 and the
//! 0x200 it listens on included, from then on (the real radar answers on its
//! new ids once it has applied the setting; the emulator applies it at once).

use super::config::{OutputType, RadarConfig};
use super::frames::{cluster_cycle, object_cycle, radar_state, version, Object};
use super::scene::{clusters, targets, Detection};
use crate::can_device::bus::Transmitter;
use crate::can_device::CanDeviceEmulator;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use shroud_drivers::assembly::MountPose;
use shroud_drivers::can::CanFrame;
use shroud_drivers::dbc::{builtin, CanDatabase, DbcError};
use shroud_sim::MovingSpheres;

/// The radar's bus: 500 kbit/s.
pub const BITRATE: u32 = 500_000;
/// 0x201 RadarState period.
pub const STATE_PERIOD_S: f64 = 0.05;
/// 0x700 VersionID period.
pub const VERSION_PERIOD_S: f64 = 1.0;
/// Measurement cycle period.
pub const CYCLE_PERIOD_S: f64 = 0.072;
/// Work older than this at a poll is skipped rather than generated (a host
/// that stalls for minutes gets the present, not a backlog).
const MAX_STALL_S: f64 = 1.0;
/// Events one call generates at most: a second of work is about 35 (20
/// states, 1 version, 14 cycles); the bound only keeps absurd times (where
/// adding a period no longer moves a float) from looping.
const MAX_EVENTS_PER_CALL: usize = 1_000;
/// Sensor ids the radar takes (3 bits).
const SENSOR_IDS: u8 = 8;
/// Id step per sensor id.
pub const SENSOR_ID_STEP: u32 = 0x10;
/// Standard deviations of the measurement noise: position (m), velocity
/// (m/s).
const POSITION_NOISE_M: f64 = 0.03;
const VELOCITY_NOISE_MPS: f64 = 0.03;

/// What the emulator could not do, counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Ars408Counts {
    /// Cycles generated.
    pub cycles: u64,
    /// Cycles and status frames skipped because the host polled late.
    pub skipped: u64,
    /// Frames the DBC refused to encode (a DBC/emulator mismatch).
    pub encode_errors: u64,
    /// Host frames that were not a RadarConfiguration for this radar.
    pub ignored: u64,
    /// Frames dropped because the transmit queue was full.
    pub queue_full: u64,
}

/// An emulated Continental ARS408-21 radar measuring moving spheres.
pub struct Ars408Emulator {
    spheres: MovingSpheres,
    mount: MountPose,
    /// The builtin DBC moved to each sensor id (index = sensor id).
    dbs: Vec<CanDatabase>,
    config: RadarConfig,
    tx: Transmitter,
    next_state: f64,
    next_version: f64,
    next_cycle: f64,
    drop_frame_every: u64,
    /// Which spheres the previous object cycle reported.
    tracked: Vec<bool>,
    rng: Pcg64,
    counts: Ars408Counts,
}

impl Ars408Emulator {
    /// A powered-up radar with `config` (its sensor id included) at `mount`
    /// in the scene, looking along its +x. `drop_frame_every` = n: the middle
    /// 0x701 (or 0x60B) of every n-th cycle is left out; 0 = never.
    pub fn new(
        spheres: MovingSpheres,
        mount: MountPose,
        config: RadarConfig,
        drop_frame_every: u64,
        seed: u64,
    ) -> Result<Self, String> {
        if config.sensor_id >= SENSOR_IDS {
            return Err(format!(
                "ARS408 sensor id {} is not 0..=7",
                config.sensor_id
            ));
        }
        spheres
            .validate()
            .map_err(|e| format!("ARS408 scene: {e}"))?;
        let base = builtin("ars408").ok_or("the builtin DBC \"ars408\" is missing")?;
        let dbs = (0..SENSOR_IDS)
            .map(|n| base.with_id_offset(SENSOR_ID_STEP * u32::from(n)))
            .collect::<Result<Vec<_>, DbcError>>()
            .map_err(|e| format!("ARS408 DBC: {e}"))?;
        let tracked = vec![false; spheres.radii.len()];
        Ok(Self {
            spheres,
            mount,
            dbs,
            config,
            tx: Transmitter::new(BITRATE),
            next_state: 0.0,
            next_version: 0.0,
            next_cycle: CYCLE_PERIOD_S,
            drop_frame_every,
            tracked,
            rng: Pcg64::seed_from_u64(seed),
            counts: Ars408Counts::default(),
        })
    }

    /// The configuration in effect.
    pub fn config(&self) -> &RadarConfig {
        &self.config
    }

    /// What was counted so far.
    pub fn counts(&self) -> Ars408Counts {
        Ars408Counts {
            queue_full: self.tx.dropped,
            ..self.counts
        }
    }

    fn db(&self) -> Option<&CanDatabase> {
        self.dbs.get(usize::from(self.config.sensor_id))
    }

    fn sent(&mut self, frame: Result<CanFrame, DbcError>, ready: f64) {
        match frame {
            Ok(frame) => self.tx.push_single(ready, frame),
            Err(_) => self.counts.encode_errors = self.counts.encode_errors.saturating_add(1),
        }
    }

    /// Generates every frame due by `now` (status, version, cycles), in time
    /// order, so that each uses the configuration of its own time.
    fn generate(&mut self, now: f64) {
        if !now.is_finite() {
            return;
        }
        for (next, period) in [
            (&mut self.next_state, STATE_PERIOD_S),
            (&mut self.next_version, VERSION_PERIOD_S),
            (&mut self.next_cycle, CYCLE_PERIOD_S),
        ] {
            let skipped = skip_stale(next, period, now);
            self.counts.skipped = self.counts.skipped.saturating_add(skipped);
        }
        for _ in 0..MAX_EVENTS_PER_CALL {
            let t = self.next_state.min(self.next_version).min(self.next_cycle);
            if t > now {
                return;
            }
            if t == self.next_state {
                self.next_state += STATE_PERIOD_S;
                let frame = match self.db() {
                    Some(db) => radar_state(db, &self.config),
                    None => continue,
                };
                self.sent(frame, t);
            } else if t == self.next_version {
                self.next_version += VERSION_PERIOD_S;
                let frame = match self.db() {
                    Some(db) => version(db),
                    None => continue,
                };
                self.sent(frame, t);
            } else {
                self.next_cycle += CYCLE_PERIOD_S;
                self.cycle(t);
            }
        }
    }

    /// One measurement cycle at `t`, queued in order.
    fn cycle(&mut self, t: f64) {
        if self.config.output == OutputType::None {
            return;
        }
        let counter = (self.counts.cycles & 0xFFFF) as u16;
        self.counts.cycles = self.counts.cycles.saturating_add(1);
        let drop_one =
            self.drop_frame_every != 0 && self.counts.cycles.is_multiple_of(self.drop_frame_every);
        let seen = targets(&self.spheres, &self.mount, t, self.config.max_distance_m);
        let frames = match self.config.output {
            OutputType::Clusters => {
                let mut found = clusters(&seen, self.config.max_distance_m);
                for d in &mut found {
                    self.jitter(d);
                }
                self.db()
                    .map(|db| cluster_cycle(db, &self.config, counter, &found, drop_one))
            }
            _ => {
                let objects = self.objects(&seen);
                self.db()
                    .map(|db| object_cycle(db, &self.config, counter, &objects, drop_one))
            }
        };
        match frames {
            Some(Ok(frames)) => frames.into_iter().for_each(|f| self.tx.push_stream(t, f)),
            Some(Err(_)) => self.counts.encode_errors += 1,
            None => {}
        }
    }

    fn objects(&mut self, seen: &[super::scene::Target]) -> Vec<Object> {
        let mut now_tracked = vec![false; self.tracked.len()];
        let objects = seen
            .iter()
            .map(|target| {
                if let Some(flag) = now_tracked.get_mut(target.index) {
                    *flag = true;
                }
                let new = !self.tracked.get(target.index).copied().unwrap_or(false);
                Object {
                    target: *target,
                    long: target.centre.x + self.gaussian() * POSITION_NOISE_M,
                    lat: target.centre.y + self.gaussian() * POSITION_NOISE_M,
                    vlong: target.velocity.x + self.gaussian() * VELOCITY_NOISE_MPS,
                    vlat: target.velocity.y + self.gaussian() * VELOCITY_NOISE_MPS,
                    new,
                }
            })
            .collect();
        self.tracked = now_tracked;
        objects
    }

    fn jitter(&mut self, d: &mut Detection) {
        d.long += self.gaussian() * POSITION_NOISE_M;
        d.lat += self.gaussian() * POSITION_NOISE_M;
        if d.moving {
            d.vlong += self.gaussian() * VELOCITY_NOISE_MPS;
            d.vlat += self.gaussian() * VELOCITY_NOISE_MPS;
        }
    }

    /// A standard normal draw (Box–Muller).
    fn gaussian(&mut self) -> f64 {
        let u1 = 1.0 - self.rng.random::<f64>();
        let u2 = self.rng.random::<f64>();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// Moves `next` past work staler than [`MAX_STALL_S`] at `now`, by whole
/// periods; returns how many periods were skipped.
fn skip_stale(next: &mut f64, period: f64, now: f64) -> u64 {
    let behind = now - MAX_STALL_S - *next;
    if behind <= 0.0 {
        return 0;
    }
    let periods = (behind / period).ceil();
    *next += periods * period;
    periods as u64
}

impl CanDeviceEmulator for Ars408Emulator {
    fn model(&self) -> &'static str {
        "ars408"
    }

    fn receive(&mut self, frame: &CanFrame, now: f64) {
        self.generate(now);
        if frame.remote || frame.extended {
            self.counts.ignored += 1;
            return;
        }
        let Some(db) = self.dbs.get(usize::from(self.config.sensor_id)) else {
            return;
        };
        match db.decode(frame) {
            Some(Ok(message)) if message.spec.name == "RadarConfiguration" => {
                self.config.apply(&message);
            }
            _ => self.counts.ignored += 1,
        }
    }

    fn poll(&mut self, now: f64, out: &mut Vec<(f64, CanFrame)>) {
        self.generate(now);
        self.tx.send_until(now, out);
    }
}
