//! `shroud-bench devices`: how fast the real-device drivers (Hokuyo SCIP,
//! RPLIDAR, Benewake) decode their streams, and how long a scan takes from
//! its last byte to an encoded cloud message.
//!
//! Each driver first runs against its emulator in memory on a simulated clock
//! (1 ms steps, no real time passes), and every chunk the emulator sent is
//! recorded with its time, as is every byteless poll that made the driver act.
//! A driver is a deterministic state machine, so a fresh one given the same
//! calls after `connect` at the same start yields the same scans (checked,
//! scan by scan): timing that replay on the real clock measures decoding
//! alone, without the emulator or the simulated line.

use super::encode::encode_timed;
use super::{median, timed, BenchArgs};
use anyhow::{bail, ensure, Result};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use shroud_drivers::assembly::{AssemblyConfig, CloudAssembler, MountPose, MovingMount};
use shroud_drivers::benewake::{BenewakeConfig, BenewakeDriver, BenewakeModel};
use shroud_drivers::device::{
    DeviceDriver, DeviceState, DeviceStats, DriverOutput, HostTime, RangeScan,
};
use shroud_drivers::rplidar::{RplidarConfig, RplidarDriver, ScanMode};
use shroud_drivers::scip::{ScanCommand, ScipConfig, ScipDriver};
use shroud_emulators::device::{emulator, EmulatorOptions, MeshRays, SerialDeviceEmulator};
use shroud_graph::metrics::{LatencySummary, Percentiles};
use shroud_nodes::transport::PayloadWriter;
use shroud_sim::{Bvh, TableTop, DEFAULT_CYLINDER_SEGMENTS};
use std::sync::Arc;
use std::time::Instant;

/// The simulated clock's step: the node polls at least every 50 ms and reads
/// whatever the port holds; 1 ms keeps chunks small, as a busy port's are.
const STEP_NS: u64 = 1_000_000;
/// Where the simulated clock starts (monotonic and Unix), fixed so that
/// recording and replays agree to the nanosecond.
const ORIGIN: HostTime = HostTime::new(1_000_000_000, 1_700_000_000_000_000_000);
/// Simulated seconds allowed for a handshake (RPLIDAR spin-up, SCIP `TM`
/// round trips) on top of the scans' own time.
const HANDSHAKE_ALLOWANCE_S: f64 = 20.0;
/// The port's opening rate, as `shroud node serial` opens it for every kind
/// here (nodes/src/args/device.rs, `port_baud`).
const OPENING_BAUD: u32 = 115_200;
/// Rounds of driver outputs carried out per step (a reconnect's `connect`
/// makes a second round).
const MAX_ROUNDS: usize = 4;
/// The source name in the encoded clouds.
const SOURCE: &str = "bench/devices";

/// One device under test: its emulator, its driver as the node would
/// configure it, and the rate the device itself runs at.
struct Device {
    model: &'static str,
    mode: &'static str,
    driver: fn() -> Box<dyn DeviceDriver>,
    /// Scans (readings, for a rangefinder) per second the real device sends.
    device_hz: f64,
    /// Scans to record, full and `--quick`.
    scans: usize,
    quick_scans: usize,
}

/// Rates: URG-04LX 100 ms/scan, UTM-30LX 25 ms/scan (Hokuyo spec sheets;
/// research notes §1.1); RPLIDAR A1M8 5.5 Hz and A2M8 10 Hz typical (Slamtec
/// datasheets; the emulators' `rotation_hz`); TFmini Plus at most 1000 Hz
/// (Benewake manual, frame rate 1-1000 Hz), the rate the driver sets here.
const DEVICES: [Device; 5] = [
    Device {
        model: "urg-04lx",
        mode: "MD",
        driver: scip_md,
        device_hz: 10.0,
        scans: 100,
        quick_scans: 20,
    },
    Device {
        model: "utm-30lx",
        mode: "ME (intensity)",
        driver: scip_me,
        device_hz: 40.0,
        scans: 100,
        quick_scans: 20,
    },
    Device {
        model: "rplidar-a1",
        mode: "express",
        driver: rplidar_express,
        device_hz: 5.5,
        scans: 100,
        quick_scans: 20,
    },
    Device {
        model: "rplidar-a2",
        mode: "auto",
        driver: rplidar_auto,
        device_hz: 10.0,
        scans: 100,
        quick_scans: 20,
    },
    Device {
        model: "tfmini-plus",
        mode: "1000 Hz",
        driver: tfmini_plus_1khz,
        device_hz: 1000.0,
        scans: 2000,
        quick_scans: 400,
    },
];

fn scip_md() -> Box<dyn DeviceDriver> {
    Box::new(ScipDriver::new(ScipConfig::default()))
}

/// As `--scip-scan me` configures it (intensity on).
fn scip_me() -> Box<dyn DeviceDriver> {
    Box::new(ScipDriver::new(ScipConfig {
        scan: ScanCommand::Me,
        intensity: true,
        ..ScipConfig::default()
    }))
}

fn rplidar_express() -> Box<dyn DeviceDriver> {
    Box::new(RplidarDriver::new(RplidarConfig {
        scan_mode: ScanMode::Express,
        ..RplidarConfig::default()
    }))
}

fn rplidar_auto() -> Box<dyn DeviceDriver> {
    Box::new(RplidarDriver::new(RplidarConfig::default()))
}

fn tfmini_plus_1khz() -> Box<dyn DeviceDriver> {
    Box::new(BenewakeDriver::new(BenewakeConfig {
        model: BenewakeModel::TfminiPlus,
        frame_rate: Some(1000),
        ..BenewakeConfig::default()
    }))
}

/// 2.5 m above the table, pitched 90° so that the sensor's +x looks straight
/// down: a lidar's scan plane is vertical (world y-z), a rangefinder's beam
/// hits the table top.
fn mount() -> MovingMount {
    MovingMount::fixed(MountPose::from_xyz_rpy(
        [0.0, 0.0, 2.5],
        [0.0, std::f64::consts::FRAC_PI_2, 0.0],
    ))
}

/// Seconds of simulated time since [`ORIGIN`] (the emulator's clock).
fn seconds(at: HostTime) -> f64 {
    at.since(ORIGIN) as f64 * 1e-9
}

/// One recorded call: bytes handed to `receive` then a `poll`, or (no bytes)
/// a `poll` alone that made the driver act.
struct Chunk {
    at: HostTime,
    bytes: Vec<u8>,
}

/// What the in-memory session did.
#[derive(Default)]
struct Recording {
    chunks: Vec<Chunk>,
    scans: Vec<RangeScan>,
    end: HostTime,
    stats: DeviceStats,
    notes: Vec<String>,
}

impl Recording {
    fn stream_bytes(&self) -> u64 {
        self.chunks.iter().map(|c| c.bytes.len() as u64).sum()
    }
}

/// The serial line between a driver and its emulator, in memory: bytes
/// garbled both ways while the host's rate is not the device's UART rate,
/// as the pty line of `sensor-sim` does (nodes/src/ingest/emulated_device.rs).
struct Line {
    device: Box<dyn SerialDeviceEmulator>,
    host_baud: u32,
    noise: Pcg64Mcg,
    garbled: u64,
    flushes: u64,
}

impl Line {
    fn new(device: Box<dyn SerialDeviceEmulator>) -> Self {
        Self {
            device,
            host_baud: OPENING_BAUD,
            noise: Pcg64Mcg::seed_from_u64(0x5eed),
            garbled: 0,
            flushes: 0,
        }
    }

    fn wrong_baud(&self) -> bool {
        self.device.uart_baud().is_some_and(|b| b != self.host_baud)
    }

    /// What the device sent up to `at`.
    fn read(&mut self, at: HostTime, bytes: &mut Vec<u8>) {
        self.device.poll(seconds(at), bytes);
        if self.wrong_baud() && !bytes.is_empty() {
            self.garbled += bytes.len() as u64;
            bytes.iter_mut().for_each(|b| *b = self.noise.random());
        }
    }

    /// Carries out the driver's outputs in order, close to the node's port
    /// (nodes/src/ingest/device_port.rs): scans into `rec`, faults noted
    /// there, a reconnect as a fresh `connect` (the device stays powered, as
    /// behind a reopened USB port). Unlike the port, the outputs after a
    /// reconnect are dropped: the bench counts no reconnects in normal runs
    /// and fails its replay check if one changes the scans.
    fn apply(
        &mut self,
        driver: &mut dyn DeviceDriver,
        outputs: &mut Vec<DriverOutput>,
        at: HostTime,
        rec: &mut Recording,
    ) {
        let now = seconds(at);
        for _ in 0..MAX_ROUNDS {
            for output in std::mem::take(outputs) {
                match output {
                    DriverOutput::Write(bytes) if self.wrong_baud() => {
                        self.garbled += bytes.len() as u64;
                    }
                    DriverOutput::Write(bytes) => self.device.receive(&bytes, now),
                    DriverOutput::SetBaud(baud) => self.host_baud = baud,
                    DriverOutput::SetDtr(asserted) => self.device.set_dtr(asserted, now),
                    // Nothing waits between the emulator and the driver here.
                    DriverOutput::FlushInput => self.flushes += 1,
                    DriverOutput::Scan(scan) => rec.scans.push(scan),
                    DriverOutput::Health { ok: false, detail } => {
                        rec.notes.push(format!("{now:.3} s: unhealthy: {detail}"));
                    }
                    DriverOutput::State(state @ DeviceState::Recovering(_)) => {
                        rec.notes.push(format!("{now:.3} s: {state:?}"));
                    }
                    DriverOutput::Reconnect(reason) => {
                        rec.notes.push(format!("{now:.3} s: reconnect: {reason}"));
                        driver.connect(at, outputs);
                        break;
                    }
                    DriverOutput::State(_)
                    | DriverOutput::Identity(_)
                    | DriverOutput::Health { .. } => {}
                }
            }
            if outputs.is_empty() {
                return;
            }
        }
    }
}

/// Runs `device`'s driver against its emulator until `wanted` scans (or the
/// time allowed runs out), recording every call that fed the driver.
fn record(device: &Device, world: &Arc<Bvh>, wanted: usize) -> Result<Recording> {
    let rays = MeshRays::new(world.clone(), mount(), ORIGIN.unix_ns).map_err(anyhow::Error::msg)?;
    let emulated = emulator(device.model, Box::new(rays), &EmulatorOptions::default())
        .map_err(anyhow::Error::msg)?;
    let mut line = Line::new(emulated);
    let mut driver = (device.driver)();
    let mut rec = Recording::default();
    let mut outputs = Vec::new();
    driver.connect(ORIGIN, &mut outputs);
    line.apply(driver.as_mut(), &mut outputs, ORIGIN, &mut rec);
    let allowed_s = HANDSHAKE_ALLOWANCE_S + 3.0 * wanted as f64 / device.device_hz;
    let steps = (allowed_s * 1e9 / STEP_NS as f64).ceil() as u64;
    let mut stats = driver.stats().clone();
    let mut bytes = Vec::new();
    for step in 1..=steps {
        let at = ORIGIN.plus_ns(step * STEP_NS);
        rec.end = at;
        line.read(at, &mut bytes);
        if !bytes.is_empty() {
            driver.receive(&bytes, at, &mut outputs);
        }
        driver.poll(at, &mut outputs);
        if !bytes.is_empty() || !outputs.is_empty() || driver.stats() != &stats {
            stats = driver.stats().clone();
            rec.chunks.push(Chunk {
                at,
                bytes: std::mem::take(&mut bytes),
            });
        }
        line.apply(driver.as_mut(), &mut outputs, at, &mut rec);
        if rec.scans.len() >= wanted {
            break;
        }
    }
    rec.stats = driver.stats().clone();
    if line.garbled > 0 {
        rec.notes
            .push(format!("{} bytes garbled by a baud mismatch", line.garbled));
    }
    // Every driver flushes once at connect; more means it started over.
    if line.flushes > 1 {
        rec.notes.push(format!("{} input flushes", line.flushes));
    }
    if rec.scans.len() < wanted {
        rec.notes.push(format!(
            "only {} of {wanted} scans in {allowed_s:.0} simulated s",
            rec.scans.len()
        ));
    }
    ensure!(
        !rec.scans.is_empty(),
        "{}: no scan in {allowed_s:.0} simulated s ({})",
        device.model,
        rec.stats
    );
    Ok(rec)
}

/// Feeds the recorded calls to a fresh driver; returns its scans and the
/// wall time of the feeding (ms), the driver's construction and `connect`
/// excluded.
fn replay(device: &Device, chunks: &[Chunk]) -> (Vec<RangeScan>, f64) {
    let mut driver = (device.driver)();
    let mut outputs = Vec::new();
    driver.connect(ORIGIN, &mut outputs);
    outputs.clear();
    timed(|| {
        let mut scans = Vec::new();
        for chunk in chunks {
            feed(driver.as_mut(), chunk, &mut outputs);
            for output in outputs.drain(..) {
                if let DriverOutput::Scan(scan) = output {
                    scans.push(scan);
                }
            }
        }
        scans
    })
}

/// One recorded call: `receive` (if bytes) then `poll`, and a reconnect's
/// `connect` (its writes go nowhere: the device's answers are recorded).
fn feed(driver: &mut dyn DeviceDriver, chunk: &Chunk, outputs: &mut Vec<DriverOutput>) {
    if !chunk.bytes.is_empty() {
        driver.receive(&chunk.bytes, chunk.at, outputs);
    }
    driver.poll(chunk.at, outputs);
    // What follows a reconnect is dropped, as [`Line::apply`] does.
    if let Some(i) = outputs
        .iter()
        .position(|o| matches!(o, DriverOutput::Reconnect(_)))
    {
        outputs.truncate(i);
        driver.connect(chunk.at, outputs);
    }
}

/// Wall times (µs) from the start of the `receive` that completed each scan
/// to its encoded cloud: driver, `CloudAssembler::push_scan` (fixed mount, a
/// cloud per scan), `Scan::to_view` and `PayloadWriter::encode` (the copy
/// path), as `shroud node serial` does before `put` (nodes/src/node/device.rs,
/// scan_publisher.rs). Scans without a valid ray make no cloud.
fn publish_latencies(device: &Device, chunks: &[Chunk], into: &mut Vec<f64>) -> Result<()> {
    let mut driver = (device.driver)();
    let mut assembler = CloudAssembler::new(AssemblyConfig::fixed(mount()))?;
    let writer = PayloadWriter::new(false, 0);
    let (mut outputs, mut clouds) = (Vec::new(), Vec::new());
    driver.connect(ORIGIN, &mut outputs);
    outputs.clear();
    let mut sequence = 0u64;
    for chunk in chunks {
        let start = Instant::now();
        feed(driver.as_mut(), chunk, &mut outputs);
        for output in outputs.drain(..) {
            let DriverOutput::Scan(scan) = output else {
                continue;
            };
            assembler.push_scan(scan, &mut clouds);
            for cloud in clouds.drain(..) {
                encode_timed(&cloud.cloud, SOURCE, sequence, start, &writer, into)?;
                sequence += 1;
            }
        }
    }
    Ok(())
}

/// Whether two scan lists are identical (NaN ranges compared by bits).
fn check_same(recorded: &[RangeScan], replayed: &[RangeScan]) -> Result<()> {
    ensure!(
        recorded.len() == replayed.len(),
        "the replay decoded {} scans, the recording {}",
        replayed.len(),
        recorded.len()
    );
    let bits = |s: &RangeScan| -> Vec<(u32, u32, Option<u32>, u32)> {
        s.rays
            .iter()
            .map(|r| {
                (
                    r.angle.to_bits(),
                    r.range.to_bits(),
                    r.intensity.map(f32::to_bits),
                    r.offset_ns,
                )
            })
            .collect()
    };
    for (i, (a, b)) in recorded.iter().zip(replayed).enumerate() {
        let same = (a.sequence, a.stamp_ns, a.received) == (b.sequence, b.stamp_ns, b.received)
            && bits(a) == bits(b);
        if !same {
            bail!("the replay's scan {i} differs from the recording's");
        }
    }
    Ok(())
}

/// What consecutive scans' stamps say: the typical period (ms), the gaps
/// of more than 1.5 periods (scans the device sent that the driver did not
/// deliver, or a change of rate), and the scans stamped no later than the
/// one before; each as (simulated s of the later scan's arrival, ms from the
/// earlier stamp).
type StampSteps = (f64, Vec<(f64, f64)>, Vec<(f64, f64)>);

fn stamp_steps(scans: &[RangeScan]) -> StampSteps {
    let steps: Vec<(f64, f64)> = scans
        .windows(2)
        .map(|w| {
            let ns = w[1].stamp_ns as f64 - w[0].stamp_ns as f64;
            (seconds(w[1].received), ns * 1e-6)
        })
        .collect();
    let typical = median(&mut steps.iter().map(|d| d.1).collect::<Vec<_>>());
    let gaps = steps
        .iter()
        .copied()
        .filter(|d| d.1 > 1.5 * typical)
        .collect();
    let repeats = steps.into_iter().filter(|d| d.1 <= 0.0).collect();
    (typical, gaps, repeats)
}

/// The first few of `steps`, for a note.
fn list_steps(steps: &[(f64, f64)]) -> String {
    let listed: Vec<String> = steps
        .iter()
        .take(5)
        .map(|(at, ms)| format!("{ms:.2} ms after the scan before, received at {at:.3} s"))
        .collect();
    let more = if steps.len() > 5 { "; ..." } else { "" };
    format!("{}{more}", listed.join("; "))
}

/// One line of the table.
struct Row {
    label: String,
    stream_bytes: u64,
    simulated_s: f64,
    first_scan_s: f64,
    scans: usize,
    stream_bytes_per_s: f64,
    recorded_hz: f64,
    rays_per_scan: f64,
    replay_ms: f64,
    device_hz: f64,
    publish_us: Option<LatencySummary>,
    notes: Vec<String>,
}

fn measure(device: &Device, world: &Arc<Bvh>, args: &BenchArgs) -> Result<Row> {
    let (wanted, repetitions) = if args.quick {
        (device.quick_scans, 3)
    } else {
        (device.scans, args.runs.max(1))
    };
    let mut rec = record(device, world, wanted)?;
    let mut times = Vec::with_capacity(repetitions);
    for _ in 0..repetitions {
        let (scans, ms) = replay(device, &rec.chunks);
        check_same(&rec.scans, &scans).map_err(|e| anyhow::anyhow!("{}: {e}", device.model))?;
        times.push(ms);
    }
    let mut latencies = Vec::new();
    for _ in 0..repetitions {
        publish_latencies(device, &rec.chunks, &mut latencies)?;
    }
    let mut publish = Percentiles::new(latencies.len());
    latencies.iter().for_each(|l| publish.push(*l));
    describe_losses(&mut rec);
    let (Some(first), Some(last)) = (rec.scans.first(), rec.scans.last()) else {
        bail!("{}: no scan recorded", device.model);
    };
    let (first, last) = (first.received, last.received);
    let streaming_s = last.since(first) as f64 * 1e-9;
    let streamed: u64 = rec
        .chunks
        .iter()
        .filter(|c| {
            c.at.monotonic_ns > first.monotonic_ns && c.at.monotonic_ns <= last.monotonic_ns
        })
        .map(|c| c.bytes.len() as u64)
        .sum();
    let mut rays: Vec<f64> = rec.scans.iter().map(|s| s.rays.len() as f64).collect();
    Ok(Row {
        label: format!("{} ({})", device.model, device.mode),
        stream_bytes: rec.stream_bytes(),
        simulated_s: seconds(rec.end),
        first_scan_s: seconds(first),
        scans: rec.scans.len(),
        stream_bytes_per_s: streamed as f64 / streaming_s,
        recorded_hz: (rec.scans.len() - 1) as f64 / streaming_s,
        rays_per_scan: median(&mut rays),
        replay_ms: median(&mut times),
        device_hz: device.device_hz,
        publish_us: publish.summary(),
        notes: rec.notes,
    })
}

/// Notes the driver's error counters and any gap in the scans' stamps.
fn describe_losses(rec: &mut Recording) {
    for (kind, n) in rec.stats.error_counts() {
        rec.notes.push(format!("driver error {kind}: {n}"));
    }
    let (period_ms, gaps, repeats) = stamp_steps(&rec.scans);
    if !gaps.is_empty() {
        rec.notes.push(format!(
            "{} stamp gaps over 1.5 typical periods ({period_ms:.2} ms): {}",
            gaps.len(),
            list_steps(&gaps)
        ));
    }
    if !repeats.is_empty() {
        rec.notes.push(format!(
            "{} scans stamped no later than the scan before: {}",
            repeats.len(),
            list_steps(&repeats)
        ));
    }
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let world = Arc::new(Bvh::build(
        &TableTop::default().mesh(DEFAULT_CYLINDER_SEGMENTS)?,
    )?);
    let mut rows = Vec::new();
    for device in &DEVICES {
        let row = measure(device, &world, args)?;
        eprintln!("measured {}", row.label);
        rows.push(row);
    }
    let repetitions = if args.quick { 3 } else { args.runs.max(1) };
    print_table(&rows, repetitions);
    Ok(())
}

fn print_table(rows: &[Row], repetitions: usize) {
    println!(
        "Device drivers: each against its emulator in memory on a simulated 1 ms clock \
         (table-top world, mount 2.5 m up looking down), the recorded byte chunks then \
         replayed into a fresh driver on the real clock (median of {repetitions}, scans \
         checked identical to the recording's). Stream rate = bytes the device sent \
         between its first and last scan / simulated seconds. Last byte -> encoded: from \
         the receive() that completed a scan through CloudAssembler::push_scan (fixed \
         mount, a cloud per scan), Scan::to_view and PayloadWriter::encode (copy path); \
         in-process only, zenoh transit not included.\n"
    );
    println!("| device (mode) | stream bytes | simulated s (1st scan at) | scans | rays/scan | device stream | scans/s in sim (device's) | replay | decode MB/s | decode scans/s | x device rate | last byte -> encoded p50 | p99 |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let decode_s = r.replay_ms * 1e-3;
        let scans_per_s = r.scans as f64 / decode_s;
        let (p50, p99) = r
            .publish_us
            .map(|l| (l.p50, l.p99))
            .unwrap_or((f64::NAN, f64::NAN));
        println!(
            "| {} | {} | {:.2} ({:.3}) | {} | {:.0} | {:.1} KB/s | {:.2} ({}) | {:.2} ms | {:.0} | {:.0} | {:.0}x | {:.1} us | {:.1} us |",
            r.label,
            r.stream_bytes,
            r.simulated_s,
            r.first_scan_s,
            r.scans,
            r.rays_per_scan,
            r.stream_bytes_per_s / 1e3,
            r.recorded_hz,
            r.device_hz,
            r.replay_ms,
            r.stream_bytes as f64 / decode_s / 1e6,
            scans_per_s,
            scans_per_s / r.device_hz,
            p50,
            p99,
        );
    }
    for r in rows.iter().filter(|r| !r.notes.is_empty()) {
        println!("\n{}:", r.label);
        for note in &r.notes {
            println!("- {note}");
        }
    }
}
