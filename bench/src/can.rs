//! `shroud-bench can`: how fast the CAN device layer decodes. First the
//! generic DBC codec against a decoder of the ARS408's 0x701
//! Cluster_1_General shifted by hand; then whole drivers (an ARS408 sending
//! clusters with quality, three TF03-CAN on one bus) on recorded emulator
//! traffic, and how long a cycle takes from its last frame to an encoded cloud.
//!
//! As in `bench devices`: each driver first runs against its emulator in
//! memory on a simulated 1 ms clock (no real time passes). Every frame is
//! recorded with its send time, which is also its receive time, as a
//! SocketCAN stamp would be, and so is every frameless poll that made the
//! driver act. A driver is a deterministic state machine, so a fresh one given
//! the same calls after the same `connect` yields the same clouds (checked,
//! cloud by cloud). Timing that replay on the real clock therefore measures
//! the driver alone, without the emulator.

use super::encode::encode_timed;
use super::{median, timed, BenchArgs};
use anyhow::{anyhow, bail, ensure, Context, Result};
use shroud_drivers::ars408::{Ars408Config, Ars408Driver, RadarSettings};
use shroud_drivers::assembly::MountPose;
use shroud_drivers::benewake_can::{
    BenewakeCanConfig, BenewakeCanDriver, BenewakeCanModel, RangefinderConfig,
};
use shroud_drivers::can::CanFrame;
use shroud_drivers::can_device::{
    CanDeviceDriver, CanDriverOutput, FrameClock, SensorCloud, TimedFrame,
};
use shroud_drivers::dbc::{builtin, CanDatabase};
use shroud_drivers::device::{DeviceState, HostTime};
use shroud_emulators::can_device::ars408::CYCLE_PERIOD_S;
use shroud_emulators::can_device::benewake::BenewakeCanModel as EmulatedBenewake;
use shroud_emulators::can_device::{
    can_emulator, CanDeviceEmulator, CanEmulatorOptions, CanWorld, RangefinderSpec,
};
use shroud_graph::metrics::{LatencySummary, Percentiles};
use shroud_nodes::transport::PayloadWriter;
use shroud_sim::{Bvh, MovingSpheres, TableTop, DEFAULT_CYLINDER_SEGMENTS};
use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;
use std::sync::Arc;
use std::time::Instant;

/// The simulated clock's step. A frameless poll happens at most this often;
/// every frame is fed at its own send time.
const STEP_NS: u64 = 1_000_000;
/// Where the simulated clock starts (monotonic and Unix), fixed so that
/// recording and replays agree to the nanosecond.
const ORIGIN: HostTime = HostTime::new(1_000_000_000, 1_700_000_000_000_000_000);
/// Simulated seconds of traffic recorded, full and `--quick`.
const RECORD_S: f64 = 5.0;
const QUICK_RECORD_S: f64 = 2.0;
/// Wall time one decode sample aims at (a pass over a few thousand frames
/// takes well under a millisecond, too short to time alone).
const DECODE_SAMPLE_MS: f64 = 20.0;
const QUICK_DECODE_SAMPLE_MS: f64 = 5.0;
/// The source name in the encoded clouds.
const SOURCE: &str = "bench/can";
/// The ARS408's cluster general message at sensor id 0 (sensors.md §2.2).
const CLUSTER_GENERAL_ID: u32 = 0x701;
/// Its signals in the order of [`ClusterGeneral::values`], as the builtin
/// DBC names them.
const CLUSTER_GENERAL_SIGNALS: [&str; 7] = [
    "ID", "DistLong", "DistLat", "VrelLong", "VrelLat", "DynProp", "RCS",
];
/// How far the hand-shifted values may be from the DBC's.
const SAME_VALUE: f64 = 1e-9;

/// One CAN device (or bus of devices) under test.
struct CanDevice {
    label: &'static str,
    /// The emulator's model name (`shroud_emulators::can_device::CAN_MODELS`).
    model: &'static str,
    options: fn() -> CanEmulatorOptions,
    driver: fn() -> Result<Box<dyn CanDeviceDriver>>,
    /// Cycles per second the real device(s) send.
    device_hz: f64,
}

/// Rates: one ARS408 measurement cycle every 72 ms (the emulator's
/// `CYCLE_PERIOD_S`); Benewake TF03-CAN 100 Hz out of the box (sensors.md
/// §2.1; the emulator's `rate_hz`), the three units taking turns.
fn devices() -> [CanDevice; 2] {
    [
        CanDevice {
            label: "ars408 (clusters + quality)",
            model: "ars408",
            options: CanEmulatorOptions::default,
            driver: ars408_driver,
            device_hz: 1.0 / CYCLE_PERIOD_S,
        },
        CanDevice {
            label: "3x tf03-can, one bus",
            model: "tf03-can",
            options: tf03_options,
            driver: tf03_driver,
            device_hz: EmulatedBenewake::Tf03.rate_hz(),
        },
    ]
}

/// As `shroud node can --device ars408` sets it up by default (clusters,
/// quality on, extended information off, configured on connect), mounted
/// where the emulator's radar sits, so that the clouds are in the scene's
/// frame.
fn ars408_driver() -> Result<Box<dyn CanDeviceDriver>> {
    let config = Ars408Config {
        settings: Some(RadarSettings {
            send_quality: Some(true),
            send_ext_info: Some(false),
            ..RadarSettings::default()
        }),
        mount: CanEmulatorOptions::default().radar_mount,
        ..Ars408Config::default()
    };
    let database = builtin("ars408").context("no builtin DBC \"ars408\"")?;
    Ok(Box::new(Ars408Driver::new(config, database)?))
}

/// Three rangefinders 1.5 m above the table top looking down, at three ids
/// (as the end-to-end test `can_three_tf03_rangefinders_on_one_bus...`).
const TF03_UNITS: [(&str, u32, [f64; 3]); 3] = [
    ("a", 0x003, [0.0, 0.0, 1.5]),
    ("b", 0x013, [0.2, 0.0, 1.5]),
    ("c", 0x023, [0.0, 0.2, 1.5]),
];

fn looking_down(at: [f64; 3]) -> MountPose {
    MountPose::from_xyz_rpy(at, [0.0, FRAC_PI_2, 0.0])
}

fn tf03_options() -> CanEmulatorOptions {
    CanEmulatorOptions {
        rangefinders: TF03_UNITS
            .iter()
            .map(|&(_, id, at)| RangefinderSpec {
                id,
                extended: false,
                mount: looking_down(at),
            })
            .collect(),
        ..CanEmulatorOptions::default()
    }
}

fn tf03_driver() -> Result<Box<dyn CanDeviceDriver>> {
    let sensors = TF03_UNITS
        .iter()
        .map(|&(name, id, at)| RangefinderConfig {
            id,
            extended: false,
            ..RangefinderConfig::new(name, BenewakeCanModel::Tf03, looking_down(at))
        })
        .collect();
    Ok(Box::new(BenewakeCanDriver::new(BenewakeCanConfig::new(
        sensors,
    ))?))
}

/// Seconds of simulated time since [`ORIGIN`] (the emulator's clock).
fn seconds(at: HostTime) -> f64 {
    at.since(ORIGIN) as f64 * 1e-9
}

/// A frame the emulator finished sending at `t` simulated seconds, as a
/// SocketCAN node reads it: stamped and received then.
fn timed_frame(frame: CanFrame, t: f64) -> TimedFrame {
    let ns = (t.max(0.0) * 1e9).round() as u64;
    TimedFrame {
        frame,
        stamp_ns: ORIGIN.unix_ns + ns,
        clock: FrameClock::Kernel,
        received: ORIGIN.plus_ns(ns),
    }
}

/// One recorded call: a frame (`receive`, then `poll` at its time, as
/// `run_can_device` does after every frame), or a `poll` alone that made
/// the driver act.
enum Call {
    Frame(TimedFrame),
    Poll(HostTime),
}

fn feed(driver: &mut dyn CanDeviceDriver, call: &Call, outputs: &mut Vec<CanDriverOutput>) {
    match call {
        Call::Frame(frame) => {
            driver.receive(frame, outputs);
            driver.poll(frame.received, outputs);
        }
        Call::Poll(at) => driver.poll(*at, outputs),
    }
}

/// What the in-memory session did.
#[derive(Default)]
struct Recording {
    calls: Vec<Call>,
    clouds: Vec<SensorCloud>,
    end: HostTime,
    /// Frames the driver sent (configuration).
    sent: u64,
    notes: Vec<String>,
}

impl Recording {
    fn frames(&self) -> impl Iterator<Item = &TimedFrame> {
        self.calls.iter().filter_map(|c| match c {
            Call::Frame(f) => Some(f),
            Call::Poll(_) => None,
        })
    }
}

/// Carries out the driver's outputs: frames to the emulator, clouds into
/// `rec`, faults noted there.
fn deliver(
    outputs: &mut Vec<CanDriverOutput>,
    emulator: &mut dyn CanDeviceEmulator,
    now: f64,
    rec: &mut Recording,
) {
    for output in outputs.drain(..) {
        match output {
            CanDriverOutput::Send(frame) => {
                rec.sent += 1;
                emulator.receive(&frame, now);
            }
            CanDriverOutput::Cloud(cloud) => rec.clouds.push(cloud),
            CanDriverOutput::Health { ok: false, detail } => {
                rec.notes.push(format!("{now:.3} s: unhealthy: {detail}"));
            }
            CanDriverOutput::State(state @ DeviceState::Recovering(_)) => {
                rec.notes.push(format!("{now:.3} s: {state:?}"));
            }
            CanDriverOutput::State(_)
            | CanDriverOutput::Identity(_)
            | CanDriverOutput::Health { .. } => {}
        }
    }
}

/// Runs `device`'s driver against its emulator for `duration_s` simulated
/// seconds, recording every call that fed the driver.
fn record(device: &CanDevice, world: &CanWorld, duration_s: f64) -> Result<Recording> {
    let mut emulator =
        can_emulator(device.model, &(device.options)(), world.clone()).map_err(|e| anyhow!(e))?;
    let mut driver = (device.driver)()?;
    let mut rec = Recording::default();
    let mut outputs = Vec::new();
    driver.connect(ORIGIN, true, &mut outputs);
    deliver(&mut outputs, emulator.as_mut(), 0.0, &mut rec);
    let steps = (duration_s * 1e9 / STEP_NS as f64).ceil() as u64;
    let mut sent = Vec::new();
    for step in 1..=steps {
        let at = ORIGIN.plus_ns(step * STEP_NS);
        let now = seconds(at);
        emulator.poll(now, &mut sent);
        for (t, frame) in sent.drain(..) {
            let call = Call::Frame(timed_frame(frame, t));
            feed(driver.as_mut(), &call, &mut outputs);
            rec.calls.push(call);
            deliver(&mut outputs, emulator.as_mut(), now, &mut rec);
        }
        let before = driver.stats().clone();
        driver.poll(at, &mut outputs);
        if !outputs.is_empty() || driver.stats() != &before {
            rec.calls.push(Call::Poll(at));
        }
        deliver(&mut outputs, emulator.as_mut(), now, &mut rec);
        rec.end = at;
    }
    let stats = driver.stats();
    for (kind, n) in stats.error_counts() {
        rec.notes.push(format!("driver error {kind}: {n}"));
    }
    for (kind, n) in stats.note_counts() {
        rec.notes.push(format!("driver note {kind}: {n}"));
    }
    for (kind, n) in stats.invalid_reading_counts() {
        rec.notes.push(format!("invalid readings {kind}: {n}"));
    }
    if rec.sent > 0 {
        rec.notes
            .push(format!("configuration frames sent: {}", rec.sent));
    }
    ensure!(
        rec.clouds.len() >= 2,
        "{}: {} clouds in {duration_s:.1} simulated s ({stats})",
        device.label,
        rec.clouds.len()
    );
    Ok(rec)
}

/// A fresh driver, connected as in the recording (writable: its
/// configuration frames are dropped, the radar's answers are recorded).
fn connected(
    device: &CanDevice,
    outputs: &mut Vec<CanDriverOutput>,
) -> Result<Box<dyn CanDeviceDriver>> {
    let mut driver = (device.driver)()?;
    driver.connect(ORIGIN, true, outputs);
    outputs.clear();
    Ok(driver)
}

/// Feeds the recorded calls to a fresh driver; returns its clouds and the
/// wall time of the feeding (ms), construction and `connect` excluded.
fn replay(device: &CanDevice, calls: &[Call]) -> Result<(Vec<SensorCloud>, f64)> {
    let mut outputs = Vec::new();
    let mut driver = connected(device, &mut outputs)?;
    Ok(timed(|| {
        let mut clouds = Vec::new();
        for call in calls {
            feed(driver.as_mut(), call, &mut outputs);
            for output in outputs.drain(..) {
                if let CanDriverOutput::Cloud(cloud) = output {
                    clouds.push(cloud);
                }
            }
        }
        clouds
    }))
}

/// Wall times (µs) from the start of the call that completed each cycle (the
/// `receive` of its last frame, or the poll that timed it out) to its encoded
/// cloud: driver, `Scan::to_view` and `PayloadWriter::encode` (the copy
/// path), as `shroud node can` does before `put` (nodes/src/node/can.rs,
/// scan_publisher.rs).
fn publish_latencies(device: &CanDevice, calls: &[Call], into: &mut Vec<f64>) -> Result<()> {
    let mut outputs = Vec::new();
    let mut driver = connected(device, &mut outputs)?;
    let writer = PayloadWriter::new(false, 0);
    let mut sequence = 0u64;
    for call in calls {
        let start = Instant::now();
        feed(driver.as_mut(), call, &mut outputs);
        for output in outputs.drain(..) {
            let CanDriverOutput::Cloud(cloud) = output else {
                continue;
            };
            encode_timed(&cloud.scan, SOURCE, sequence, start, &writer, into)?;
            sequence += 1;
        }
    }
    Ok(())
}

/// Whether two cloud lists are identical (floats compared by bits).
fn check_same(recorded: &[SensorCloud], replayed: &[SensorCloud]) -> Result<()> {
    ensure!(
        recorded.len() == replayed.len(),
        "the replay made {} clouds, the recording {}",
        replayed.len(),
        recorded.len()
    );
    for (i, (a, b)) in recorded.iter().zip(replayed).enumerate() {
        if cloud_bits(a) != cloud_bits(b) {
            bail!("the replay's cloud {i} differs from the recording's");
        }
    }
    Ok(())
}

/// A cloud's stamps and values, floats as their bits (so that NaN equals
/// NaN).
type CloudBits<'a> = (
    u32,
    u64,
    HostTime,
    Vec<[u32; 3]>,
    Option<Vec<u32>>,
    Vec<(&'a str, Vec<u32>)>,
);

fn cloud_bits(c: &SensorCloud) -> CloudBits<'_> {
    let s = &c.scan;
    let floats = |v: &[f32]| -> Vec<u32> { v.iter().map(|x| x.to_bits()).collect() };
    (
        s.sequence,
        s.stamp_ns,
        c.received,
        s.points.iter().map(|p| p.map(f32::to_bits)).collect(),
        s.intensity.as_deref().map(floats),
        s.channels
            .iter()
            .map(|ch| (ch.name.as_str(), floats(&ch.values)))
            .collect(),
    )
}

/// Cluster_1_General's values, shifted out by hand with the byte formulas
/// of tier4/ars408_driver and Apollo's conti_radar (sensors.md §2.2).
#[derive(Debug, Clone, Copy, PartialEq)]
struct ClusterGeneral {
    id: f64,
    dist_long: f64,
    dist_lat: f64,
    vrel_long: f64,
    vrel_lat: f64,
    dyn_prop: f64,
    rcs: f64,
}

impl ClusterGeneral {
    /// `None` unless a standard 8-byte data frame on 0x701 (the checks the
    /// DBC's lookup and length test make).
    fn decode(frame: &CanFrame) -> Option<Self> {
        if frame.id != CLUSTER_GENERAL_ID || frame.extended || frame.remote || frame.len < 8 {
            return None;
        }
        let [d0, d1, d2, d3, d4, d5, d6, d7] = frame.data.map(u32::from);
        Some(Self {
            id: f64::from(d0),
            dist_long: f64::from((d1 << 5) | (d2 >> 3)) * 0.2 - 500.0,
            dist_lat: f64::from(((d2 & 3) << 8) | d3) * 0.2 - 102.3,
            vrel_long: f64::from((d4 << 2) | (d5 >> 6)) * 0.25 - 128.0,
            vrel_lat: f64::from(((d5 & 0x3F) << 3) | (d6 >> 5)) * 0.25 - 64.0,
            dyn_prop: f64::from(d6 & 7),
            rcs: f64::from(d7) * 0.5 - 64.0,
        })
    }

    /// In the order of [`CLUSTER_GENERAL_SIGNALS`].
    fn values(&self) -> [f64; 7] {
        [
            self.id,
            self.dist_long,
            self.dist_lat,
            self.vrel_long,
            self.vrel_lat,
            self.dyn_prop,
            self.rcs,
        ]
    }
}

/// Checks that the hand-shifted decoder reads every 0x701 frame as the DBC
/// does, so that comparing their speeds is comparing equal work.
fn check_hand_matches_dbc(db: &CanDatabase, generals: &[CanFrame]) -> Result<()> {
    for (i, frame) in generals.iter().enumerate() {
        let hand = ClusterGeneral::decode(frame)
            .with_context(|| format!("0x701 frame {i}: the hand decoder refused it"))?;
        let decoded = db
            .decode(frame)
            .with_context(|| format!("0x701 frame {i}: not in the DBC"))??;
        for (name, value) in CLUSTER_GENERAL_SIGNALS.iter().zip(hand.values()) {
            let dbc = decoded
                .get(name)
                .with_context(|| format!("the DBC's Cluster_1_General has no {name}"))?;
            ensure!(
                (dbc - value).abs() <= SAME_VALUE,
                "0x701 frame {i} {:02X?}: {name} is {dbc} by the DBC, {value} by hand",
                frame.data
            );
        }
    }
    Ok(())
}

/// Median ns per frame of `decode` over `frames`: each of `samples` samples
/// runs as many passes as make about `sample_ms` (found by a first, warm-up
/// pass).
fn ns_per_frame(
    frames: &[CanFrame],
    samples: usize,
    sample_ms: f64,
    mut decode: impl FnMut(&CanFrame),
) -> f64 {
    let mut pass = || frames.iter().for_each(|f| decode(black_box(f)));
    let ((), warm_ms) = timed(&mut pass);
    let passes = (sample_ms / warm_ms.max(1e-6)).ceil().clamp(1.0, 1e6) as usize;
    let mut per_frame: Vec<f64> = (0..samples)
        .map(|_| {
            let ((), ms) = timed(|| (0..passes).for_each(|_| pass()));
            ms * 1e6 / (passes * frames.len()).max(1) as f64
        })
        .collect();
    median(&mut per_frame)
}

/// One line of the decoder table.
struct DecodeRow {
    label: &'static str,
    frames: usize,
    ns_per_frame: f64,
    /// Decodes the same 0x701 frames as the hand-shifted decoder.
    only_0x701: bool,
}

fn measure_decoders(rec: &Recording, args: &BenchArgs) -> Result<Vec<DecodeRow>> {
    let (samples, sample_ms) = if args.quick {
        (3, QUICK_DECODE_SAMPLE_MS)
    } else {
        (args.runs.max(1), DECODE_SAMPLE_MS)
    };
    let db = builtin("ars408").context("no builtin DBC \"ars408\"")?;
    let general = db
        .message_by_id(CLUSTER_GENERAL_ID, false)
        .context("the builtin ARS408 DBC has no 0x701")?;
    let all: Vec<CanFrame> = rec.frames().map(|f| f.frame).collect();
    let generals: Vec<CanFrame> = all
        .iter()
        .copied()
        .filter(|f| f.id == CLUSTER_GENERAL_ID && !f.extended)
        .collect();
    ensure!(!generals.is_empty(), "the recording has no 0x701 frame");
    check_hand_matches_dbc(&db, &generals)?;
    let generic = |f: &CanFrame| {
        black_box(db.decode(f));
    };
    Ok(vec![
        DecodeRow {
            label: "CanDatabase::decode, every frame (all ids, all signals)",
            frames: all.len(),
            ns_per_frame: ns_per_frame(&all, samples, sample_ms, generic),
            only_0x701: false,
        },
        DecodeRow {
            label: "CanDatabase::decode, 0x701 only (id lookup + 7 signals)",
            frames: generals.len(),
            ns_per_frame: ns_per_frame(&generals, samples, sample_ms, generic),
            only_0x701: true,
        },
        DecodeRow {
            label: "MessageSpec::decode, 0x701 only (message found once)",
            frames: generals.len(),
            ns_per_frame: ns_per_frame(&generals, samples, sample_ms, |f| {
                let _ = black_box(general.decode(f));
            }),
            only_0x701: true,
        },
        DecodeRow {
            label: "hand-shifted 0x701 (tier4/Apollo byte formulas)",
            frames: generals.len(),
            ns_per_frame: ns_per_frame(&generals, samples, sample_ms, |f| {
                black_box(ClusterGeneral::decode(f));
            }),
            only_0x701: true,
        },
    ])
}

/// One line of the driver table.
struct DriverRow {
    label: &'static str,
    frames: usize,
    simulated_s: f64,
    first_cycle_s: f64,
    cycles: usize,
    points_per_cycle: f64,
    device_hz: f64,
    recorded_hz: f64,
    recorded_frames_per_s: f64,
    replay_ms: f64,
    publish_us: Option<LatencySummary>,
    notes: Vec<String>,
}

fn measure_driver(device: &CanDevice, rec: Recording, args: &BenchArgs) -> Result<DriverRow> {
    let repetitions = if args.quick { 3 } else { args.runs.max(1) };
    let mut times = Vec::with_capacity(repetitions);
    for _ in 0..repetitions {
        let (clouds, ms) = replay(device, &rec.calls)?;
        check_same(&rec.clouds, &clouds).map_err(|e| anyhow!("{}: {e}", device.label))?;
        times.push(ms);
    }
    let mut latencies = Vec::new();
    for _ in 0..repetitions {
        publish_latencies(device, &rec.calls, &mut latencies)?;
    }
    let mut publish = Percentiles::new(latencies.len());
    latencies.iter().for_each(|l| publish.push(*l));
    let (Some(first), Some(last)) = (rec.clouds.first(), rec.clouds.last()) else {
        bail!("{}: no cloud recorded", device.label);
    };
    let (first, last) = (first.received, last.received);
    let streaming_s = last.since(first) as f64 * 1e-9;
    let streamed = rec
        .frames()
        .filter(|f| {
            let t = f.received.monotonic_ns;
            t > first.monotonic_ns && t <= last.monotonic_ns
        })
        .count();
    let mut points: Vec<f64> = rec
        .clouds
        .iter()
        .map(|c| c.scan.points.len() as f64)
        .collect();
    Ok(DriverRow {
        label: device.label,
        frames: rec.frames().count(),
        simulated_s: seconds(rec.end),
        first_cycle_s: seconds(first),
        cycles: rec.clouds.len(),
        points_per_cycle: median(&mut points),
        device_hz: device.device_hz,
        recorded_hz: (rec.clouds.len() - 1) as f64 / streaming_s,
        recorded_frames_per_s: streamed as f64 / streaming_s,
        replay_ms: median(&mut times),
        publish_us: publish.summary(),
        notes: rec.notes,
    })
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let duration_s = if args.quick { QUICK_RECORD_S } else { RECORD_S };
    let table = TableTop::default().mesh(DEFAULT_CYLINDER_SEGMENTS)?;
    let world = CanWorld {
        spheres: MovingSpheres::default(),
        mesh: Some(Arc::new(Bvh::build(&table)?)),
    };
    let mut decoders = Vec::new();
    let mut drivers = Vec::new();
    for device in &devices() {
        let rec = record(device, &world, duration_s)?;
        if device.model == "ars408" {
            decoders = measure_decoders(&rec, args)?;
            eprintln!("measured the DBC decoders");
        }
        drivers.push(measure_driver(device, rec, args)?);
        eprintln!("measured {}", device.label);
    }
    let repetitions = if args.quick { 3 } else { args.runs.max(1) };
    print_decoders(&decoders, repetitions);
    print_drivers(&drivers, repetitions, duration_s);
    Ok(())
}

fn print_decoders(rows: &[DecodeRow], repetitions: usize) {
    println!(
        "DBC decode: the frames an emulated ARS408 sent (clusters + quality, moving-spheres \
         scene), decoded on the real clock, median of {repetitions} samples of repeated \
         passes. The hand-shifted decoder reads 0x701 Cluster_1_General with the byte \
         formulas of sensors.md §2.2; its values were checked equal to the DBC's \
         (within 1e-9) on every 0x701 frame.\n"
    );
    println!("| decoder | frames | frames/s | ns/frame | x hand-shifted |");
    println!("|---|---:|---:|---:|---:|");
    let hand = rows.last().map_or(f64::NAN, |r| r.ns_per_frame);
    for r in rows {
        let ratio = if r.only_0x701 {
            format!("{:.1}x", r.ns_per_frame / hand)
        } else {
            "-".to_owned()
        };
        println!(
            "| {} | {} | {:.2} M | {:.1} | {ratio} |",
            r.label,
            r.frames,
            1e3 / r.ns_per_frame,
            r.ns_per_frame,
        );
    }
    println!();
}

fn print_drivers(rows: &[DriverRow], repetitions: usize, duration_s: f64) {
    println!(
        "CAN device drivers: each against its emulator in memory for {duration_s:.0} \
         simulated s on a 1 ms clock (every frame received at its send time), the recorded \
         frames and acting polls then replayed into a fresh driver on the real clock (median \
         of {repetitions}, clouds checked identical to the recording's). Device rates: the \
         recording's, between its first and last cycle (nominal cycles/s in brackets). Last \
         frame -> encoded: from the receive() that completed a cycle through Scan::to_view \
         and PayloadWriter::encode (copy path); in-process only, zenoh transit not \
         included.\n"
    );
    println!("| device (mode) | frames | simulated s (1st cycle at) | cycles | points/cycle | device cycles/s (nominal) | device frames/s | replay | decode cycles/s | decode frames/s | x device rate | last frame -> encoded p50 | p99 |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let decode_s = r.replay_ms * 1e-3;
        let cycles_per_s = r.cycles as f64 / decode_s;
        let (p50, p99) = r
            .publish_us
            .map_or((f64::NAN, f64::NAN), |l| (l.p50, l.p99));
        println!(
            "| {} | {} | {:.2} ({:.3}) | {} | {:.0} | {:.2} ({:.1}) | {:.0} | {:.2} ms | {:.0} | {:.0} | {:.0}x | {:.1} us | {:.1} us |",
            r.label,
            r.frames,
            r.simulated_s,
            r.first_cycle_s,
            r.cycles,
            r.points_per_cycle,
            r.recorded_hz,
            r.device_hz,
            r.recorded_frames_per_s,
            r.replay_ms,
            cycles_per_s,
            r.frames as f64 / decode_s,
            cycles_per_s / r.device_hz,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hand_decoder_reads_the_research_notes_golden_frame() {
        // 701#034FB2048020018A: id 3, 10.0 m long, 0.9 m lat, vrel 0/0,
        // DynProp 1, RCS 5.0 (sensors.md §2.2, computed by hand).
        let data = [0x03, 0x4F, 0xB2, 0x04, 0x80, 0x20, 0x01, 0x8A];
        let frame = CanFrame::new(0x701, false, &data).unwrap();
        let got = ClusterGeneral::decode(&frame).unwrap().values();
        let want = [3.0, 10.0, 0.9, 0.0, 0.0, 1.0, 5.0];
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-9, "{got:?}");
        }
        let db = builtin("ars408").unwrap();
        check_hand_matches_dbc(&db, &[frame]).unwrap();
        let other = CanFrame::new(0x702, false, &data).unwrap();
        assert!(ClusterGeneral::decode(&other).is_none());
    }
}
