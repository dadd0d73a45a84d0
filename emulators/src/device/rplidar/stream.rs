//! One scan session: the sample clock, waiting for stable rotation, and the
//! packing of samples into standard nodes or express capsules as the
//! session's answer type requires.
//!
//! Samples are taken every `us_per_sample` of the mode; a packet leaves when
//! its last sample has been taken. Without FORCE_SCAN, output pauses while
//! the motor is not turning steadily at its target speed (protocol PDF §3
//! "Scanning Status"); FORCE_SCAN samples whatever the motor does.
//!
//! Every sample is cast along exactly the angle a decoder following the SDK
//! (`handler_normalnode.cpp`, `handler_capsules.cpp`) reports for it, so a
//! decoded scan matches the world the rays saw.

use super::capsule::{self, LegacySample, CAPSULE_LEN, MAX_DTHETA_Q3};
use super::faults::FaultInjector;
use super::measure::{Measurer, Sample};
use super::model::StreamFormat;
use super::motor::Motor;
use super::node::Node;
use super::protocol::FULL_TURN_Q6;
use super::rejects::{RejectCounts, RejectKind};
use super::tx::TxBuffer;
use crate::device::RaySource;

/// Scan output older than this at a poll is skipped rather than generated:
/// a host that stops reading for longer loses the data, as its receive
/// buffer would overflow on a real line.
const MAX_STALL_S: f64 = 1.0;

/// What a session needs from the rest of the device.
pub(crate) struct StreamContext<'a> {
    pub motor: &'a Motor,
    pub rays: &'a dyn RaySource,
    pub measurer: &'a mut Measurer,
    pub faults: &'a mut FaultInjector,
    pub tx: &'a mut TxBuffer,
    pub rejects: &'a mut RejectCounts,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Stream {
    format: StreamFormat,
    sample_s: f64,
    force: bool,
    /// Sample j of the current run is taken at `origin + (j + 1) · sample_s`
    /// (a sample is complete one sample period after its run starts).
    origin: f64,
    /// Index, within the run, of the next packet to send.
    next_packet: u64,
    /// Motor phase at the previous standard sample, to spot a new turn.
    prev_phase: Option<f64>,
    /// The next capsule carries the S ("new scan") bit.
    new_scan: bool,
}

impl Stream {
    /// A session started at `now` whose samples last `us_per_sample` µs.
    pub(crate) fn new(format: StreamFormat, us_per_sample: u32, force: bool, now: f64) -> Self {
        Self {
            format,
            sample_s: f64::from(us_per_sample.max(1)) * 1e-6,
            force,
            origin: now,
            next_packet: 0,
            prev_phase: None,
            new_scan: true,
        }
    }

    fn samples(&self) -> usize {
        self.format.samples_per_packet()
    }

    fn packet_s(&self) -> f64 {
        self.sample_s * self.samples() as f64
    }

    /// Time of the first sample of packet `packet` of the current run.
    fn packet_start(&self, packet: u64) -> f64 {
        let samples_before = packet as f64 * self.samples() as f64;
        self.origin + (samples_before + 1.0) * self.sample_s
    }

    /// Starts a new run of samples at `origin`: the next capsule opens a new
    /// scan and the turn detection starts afresh.
    fn restart(&mut self, origin: f64) {
        self.origin = origin;
        self.next_packet = 0;
        self.new_scan = true;
        self.prev_phase = None;
    }

    /// The motor's target changed at `now`: a capsule under way is dropped
    /// (its samples would straddle the change).
    pub(crate) fn on_motor_change(&mut self, now: f64) {
        if self.format != StreamFormat::Standard && self.packet_start(self.next_packet) < now {
            self.restart(now);
        }
    }

    /// Sends every packet whose last sample is due by `now`.
    pub(crate) fn advance(&mut self, now: f64, ctx: &mut StreamContext<'_>) {
        self.skip_stall(now, ctx.rejects);
        let last_offset = self.sample_s * (self.samples() - 1) as f64;
        loop {
            let start = self.packet_start(self.next_packet);
            if start + last_offset > now {
                break;
            }
            if !self.force && !ctx.motor.is_stable_at(start) {
                match ctx.motor.stable_from() {
                    Some(stable) if stable > start => {
                        self.restart(stable);
                        continue;
                    }
                    _ => {
                        self.restart(now.max(start));
                        break;
                    }
                }
            }
            self.send_packet(start, ctx);
            self.next_packet += 1;
        }
    }

    fn skip_stall(&mut self, now: f64, rejects: &mut RejectCounts) {
        let behind = now - MAX_STALL_S - self.packet_start(self.next_packet);
        if behind <= 0.0 {
            return;
        }
        let skipped = (behind / self.packet_s()).ceil();
        rejects.add(RejectKind::StalledHost, skipped as u64);
        self.restart(self.packet_start(self.next_packet) + skipped * self.packet_s());
    }

    fn send_packet(&mut self, start: f64, ctx: &mut StreamContext<'_>) {
        let faults = ctx.faults.next_packet();
        ctx.tx.send(&faults.garbage, ctx.rejects);
        match self.format {
            StreamFormat::Standard => {
                let node = self.node(start, ctx);
                ctx.tx.send(&node.encode(faults.corrupt), ctx.rejects);
            }
            StreamFormat::Capsule | StreamFormat::DenseCapsule => {
                let mut capsule = self.capsule(start, ctx);
                if faults.corrupt {
                    capsule::break_checksum(&mut capsule);
                }
                ctx.tx.send(&capsule, ctx.rejects);
                self.new_scan = false;
            }
        }
    }

    /// The standard node sampled at `t`: its angle is the encoder angle less
    /// the parallax, S set when the encoder passed 0° since the last node.
    fn node(&mut self, t: f64, ctx: &mut StreamContext<'_>) -> Node {
        let phase = ctx.motor.phase_at(t);
        let start = self.prev_phase.is_some_and(|prev| phase < prev);
        self.prev_phase = Some(phase);
        let encoder = ctx.motor.angle_deg_at(t);
        let angle_q6 = q6(encoder - ctx.measurer.parallax_deg(ctx.rays, encoder, t));
        let sample = ctx
            .measurer
            .measure(ctx.rays, f64::from(angle_q6) / 64.0, t);
        Node {
            angle_q6,
            distance_q2: saturate_u16(sample.distance_mm * 4.0),
            quality: sample.quality,
            start,
        }
    }

    /// The capsule whose first sample is at `t0`. Its start angle is the
    /// encoder angle then; the next capsule's start angle, which the decoder
    /// interpolates towards, is the encoder angle one packet later.
    fn capsule(&mut self, t0: f64, ctx: &mut StreamContext<'_>) -> [u8; CAPSULE_LEN] {
        let start_q6 = q6(ctx.motor.angle_deg_at(t0));
        let next_q6 = q6(ctx.motor.angle_deg_at(t0 + self.packet_s()));
        let samples: Vec<(Sample, u8)> = (0..self.samples())
            .map(|k| self.capsule_sample(t0, k, start_q6, next_q6, ctx))
            .collect();
        match self.format {
            StreamFormat::Capsule => {
                let mut legacy = [LegacySample::default(); capsule::LEGACY_SAMPLES];
                for (slot, (sample, dtheta_q3)) in legacy.iter_mut().zip(&samples) {
                    *slot = LegacySample {
                        distance_mm: saturate_u16(sample.distance_mm.round()),
                        dtheta_q3: *dtheta_q3,
                    };
                }
                capsule::legacy(start_q6, self.new_scan, &legacy)
            }
            _ => {
                let mut dense = [0u16; capsule::DENSE_SAMPLES];
                for (slot, (sample, _)) in dense.iter_mut().zip(&samples) {
                    *slot = saturate_u16(sample.distance_mm.round());
                }
                capsule::dense(start_q6, self.new_scan, &dense)
            }
        }
    }

    /// Sample `k` of the capsule starting at `t0`, with its dθ. Legacy
    /// capsules choose dθ so that the decoded angle (interpolated − dθ) lands
    /// on the encoder angle less the parallax; dense capsules have no dθ and
    /// measure along the interpolated angle.
    fn capsule_sample(
        &self,
        t0: f64,
        k: usize,
        start_q6: u16,
        next_q6: u16,
        ctx: &mut StreamContext<'_>,
    ) -> (Sample, u8) {
        let t = t0 + self.sample_s * k as f64;
        let interpolated = capsule::interpolated_q16(start_q6, next_q6, k, self.samples());
        let dtheta_q3 = if self.format == StreamFormat::Capsule {
            let encoder = ctx.motor.angle_deg_at(t);
            let wanted = encoder - ctx.measurer.parallax_deg(ctx.rays, encoder, t);
            dtheta_q3(interpolated as f64 / 65536.0 - wanted)
        } else {
            0
        };
        let angle_q6 = capsule::decoded_angle_q6(interpolated, dtheta_q3);
        let sample = ctx
            .measurer
            .measure(ctx.rays, f64::from(angle_q6) / 64.0, t);
        (sample, dtheta_q3)
    }
}

/// A clockwise angle in degrees as q6, wrapped into [0, 360°).
fn q6(deg: f64) -> u16 {
    let q6 = (deg * 64.0).round();
    let q6 = if q6.is_finite() { q6 as i64 } else { 0 };
    u16::try_from(q6.rem_euclid(FULL_TURN_Q6)).unwrap_or(0)
}

/// The unsigned q3 dθ closest to `behind_deg` (wrapped into ±180°), within
/// 0..=63.
fn dtheta_q3(behind_deg: f64) -> u8 {
    let wrapped = (behind_deg + 180.0).rem_euclid(360.0) - 180.0;
    let q3 = (wrapped * 8.0).round().clamp(0.0, f64::from(MAX_DTHETA_Q3));
    q3 as u8
}

fn saturate_u16(value: f64) -> u16 {
    if value.is_nan() {
        0
    } else {
        value.round().clamp(0.0, f64::from(u16::MAX)) as u16
    }
}
