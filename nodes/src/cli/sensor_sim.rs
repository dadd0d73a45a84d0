//! `shroud sensor-sim`: a simulated range sensor streaming a scene as the
//! serial protocol or SLCAN to a pseudo-terminal (or an existing port), or
//! writing a candump log; or, with `--device`, an emulated real device
//! (Hokuyo, RPLIDAR, Benewake) on a pseudo-terminal.

use crate::args::EmulatorArgs;
use crate::ingest::pty::Pty;
use crate::ingest::run_emulator;
use crate::ingest::sim::{CandumpWriter, ScanSink, SerialSensorWriter, SlcanWriter};
use anyhow::{bail, Context, Result};
use clap::{Args, ValueEnum};
use shroud_drivers::can::{
    format_candump_line, CanSensorConfig, CandumpRecord, MAX_CAN_POINTS, MAX_EXTENDED_ID,
    MAX_STANDARD_ID,
};
use shroud_drivers::serial::{PointEncoding, SerialEncoder, MAX_FRAME_POINTS};
use shroud_drivers::Scan;
use shroud_emulators::can_device::CAN_MODELS;
use shroud_sim::Scene;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// What the simulated sensor speaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SimFormat {
    /// The serial range-sensor protocol (binary frames).
    Serial,
    /// The CAN range-sensor protocol through an SLCAN (Lawicel ASCII) adapter.
    Slcan,
    /// The CAN range-sensor protocol as a candump log file (written as fast as possible).
    Candump,
    /// A CAN --device on a SocketCAN interface (--port IFACE, e.g. vcan0).
    Socketcan,
}

/// Coordinates on the serial wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SimEncoding {
    /// f32 metres.
    F32,
    /// i32 millimetres.
    I32mm,
    /// i16 millimetres (±32.767 m).
    I16mm,
}

#[derive(Debug, Clone, Args)]
pub struct SensorSimArgs {
    /// serial or slcan (to a pseudo-terminal, or --port), or candump (to
    /// --output). With a CAN --device: slcan (an emulated SLCAN adapter on a
    /// pseudo-terminal), candump (--duration seconds of the device's traffic
    /// into --output) or socketcan (on the interface --port names).
    #[arg(long, alias = "transport", value_enum, default_value_t = SimFormat::Serial)]
    pub format: SimFormat,
    /// Write to this serial port instead of creating a pseudo-terminal.
    #[arg(long)]
    pub port: Option<String>,
    /// Baud rate of --port.
    #[arg(long, default_value_t = 115_200)]
    pub baud: u32,
    /// The candump log to write.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// moving-spheres, terrain or table-top.
    #[arg(long, default_value = "moving-spheres")]
    pub scene: String,
    /// Points a scan.
    #[arg(long, default_value_t = 2000)]
    pub points: usize,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Scans a second (the scene's time advances by 1/rate a scan).
    #[arg(long, default_value_t = 10.0)]
    pub rate: f64,
    /// Scans to send; 0 means until interrupted (serial and slcan only).
    #[arg(long, default_value_t = 0)]
    pub scans: u64,
    /// Serial coordinate encoding.
    #[arg(long, value_enum, default_value_t = SimEncoding::F32)]
    pub encoding: SimEncoding,
    /// Points a serial frame carries (1..=1024).
    #[arg(long, default_value_t = 256)]
    pub points_per_frame: usize,
    /// CAN id of the sensor's START message (hex with 0x, or decimal).
    #[arg(long, default_value = "0x300", value_parser = parse_can_id)]
    pub can_id: u32,
    /// Use 29-bit CAN identifiers.
    #[arg(long)]
    pub extended: bool,
    /// Interface name written in the candump log.
    #[arg(long, default_value = "can0")]
    pub interface: String,
    /// Corrupt every n-th scan (serial, slcan, and emulated devices), to
    /// exercise a reader's error handling; 0 = never.
    #[arg(long, default_value_t = 0)]
    pub corrupt_every: u64,
    /// Emulate this real device on a pseudo-terminal instead (urg-04lx,
    /// utm-30lx, rplidar-a1, rplidar-a2, tfmini, tfmini-s, tfmini-plus,
    /// tf-luna, tf02-pro; on CAN: ars408, tf03-can, tfmini-i-can,
    /// tf02-i-can, tf02-can): it answers the device's command set and
    /// measures --world (the radar: moving spheres) from --mount (and
    /// --rangefinder). --scene and --rate do not apply.
    #[arg(long)]
    pub device: Option<String>,
    #[command(flatten)]
    pub emulator: EmulatorArgs,
}

impl Default for SensorSimArgs {
    fn default() -> Self {
        Self {
            format: SimFormat::Serial,
            port: None,
            baud: 115_200,
            output: None,
            scene: "moving-spheres".into(),
            points: 2000,
            seed: 1,
            rate: 10.0,
            scans: 0,
            encoding: SimEncoding::F32,
            points_per_frame: 256,
            can_id: 0x300,
            extended: false,
            interface: "can0".into(),
            corrupt_every: 0,
            device: None,
            emulator: EmulatorArgs::default(),
        }
    }
}

fn parse_can_id(s: &str) -> Result<u32, String> {
    let parsed = match s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        Some(hex) => u32::from_str_radix(hex, 16),
        None => s.parse(),
    };
    parsed.map_err(|e| format!("bad CAN id {s:?}: {e}"))
}

/// Runs the simulator until `--scans` are sent (or forever): prints where it
/// writes, then streams.
pub fn run_sensor_sim(args: &SensorSimArgs) -> Result<()> {
    let never = AtomicBool::new(false);
    run_sensor_sim_with(args, &never, &mut |target| {
        match &args.device {
            Some(model) => println!("sensor-sim: {model} on {}", target.display()),
            None => println!(
                "sensor-sim: {:?} sensor on {}",
                args.format,
                target.display()
            ),
        }
        let _ = std::io::stdout().flush();
    })
}

/// [`run_sensor_sim`] with a stop flag and a callback told the path written
/// to (the pty slave, the port, or the log) before the first scan.
pub fn run_sensor_sim_with(
    args: &SensorSimArgs,
    stop: &AtomicBool,
    ready: &mut dyn FnMut(&Path),
) -> Result<()> {
    if let Some(model) = &args.device {
        return run_device_emulator(args, model, stop, ready);
    }
    if args.format == SimFormat::Socketcan {
        bail!("--format socketcan runs a CAN --device (ars408, tf03-can, ...) on an interface");
    }
    let scene = Scene::by_name(&args.scene, args.points, args.seed)?;
    if !(args.rate.is_finite() && args.rate > 0.0) {
        bail!("--rate must be positive, got {}", args.rate);
    }
    let sensor = CanSensorConfig {
        base_id: args.can_id,
        extended: args.extended,
    };
    if args.format != SimFormat::Serial {
        let max = if args.extended {
            MAX_EXTENDED_ID
        } else {
            MAX_STANDARD_ID
        };
        if args.can_id.checked_add(3).is_none_or(|last| last > max) {
            bail!(
                "--can-id {:#x}: the sensor's 4 ids must fit in {max:#x}",
                args.can_id
            );
        }
        if args.points > MAX_CAN_POINTS {
            bail!(
                "a CAN scan carries at most {MAX_CAN_POINTS} points, --points is {}",
                args.points
            );
        }
    }
    if args.format == SimFormat::Serial && !(1..=MAX_FRAME_POINTS).contains(&args.points_per_frame)
    {
        bail!("--points-per-frame must be in 1..={MAX_FRAME_POINTS}");
    }
    let encoding = match args.encoding {
        SimEncoding::F32 => PointEncoding::F32Metres,
        SimEncoding::I32mm => PointEncoding::I32Millimetres,
        SimEncoding::I16mm => PointEncoding::I16Millimetres,
    };
    let encoder = SerialEncoder::new(encoding, args.points_per_frame);
    if args.format == SimFormat::Candump {
        let Some(path) = &args.output else {
            bail!("--format candump needs --output FILE");
        };
        if args.scans == 0 {
            bail!("--format candump needs --scans N (the log is written as fast as possible)");
        }
        let file = std::fs::File::create(path)
            .with_context(|| format!("cannot create {}", path.display()))?;
        let mut sink = CandumpWriter::new(std::io::BufWriter::new(file), sensor, &args.interface);
        ready(path);
        return stream(&scene, args, stop, &mut sink, false);
    }
    let (out, _pty): (Box<dyn Write + Send>, Option<Pty>) = match &args.port {
        Some(port) => {
            let port = serialport::new(port, args.baud)
                .timeout(Duration::from_millis(50))
                .open()
                .with_context(|| format!("cannot open serial port {port}"))?;
            ready(Path::new(args.port.as_deref().unwrap_or_default()));
            (Box::new(port), None)
        }
        None => {
            let pty = Pty::open().context("cannot create a pseudo-terminal")?;
            pty.set_nonblocking()?;
            let master = pty.master_clone()?;
            ready(pty.slave_path());
            (Box::new(master), Some(pty))
        }
    };
    let mut sink: Box<dyn ScanSink> = match args.format {
        SimFormat::Serial => {
            let mut w = SerialSensorWriter::new(out, encoder);
            w.corrupt_every = args.corrupt_every;
            Box::new(w)
        }
        _ => {
            let mut w = SlcanWriter::new(out, sensor);
            w.corrupt_every = args.corrupt_every;
            Box::new(w)
        }
    };
    stream(&scene, args, stop, sink.as_mut(), true)
}

/// An emulated device on a pty until stopped or `--duration` passes.
fn run_device_emulator(
    args: &SensorSimArgs,
    model: &str,
    stop: &AtomicBool,
    ready: &mut dyn FnMut(&Path),
) -> Result<()> {
    let can = CAN_MODELS.contains(&model);
    match args.format {
        SimFormat::Candump if can => return write_can_log(args, model, stop, ready),
        SimFormat::Socketcan if can => return run_on_socketcan(args, model, stop, ready),
        SimFormat::Candump | SimFormat::Socketcan => bail!(
            "--format {:?} applies to the CAN models ({})",
            args.format,
            CAN_MODELS.join(", ")
        ),
        SimFormat::Serial | SimFormat::Slcan => {}
    }
    if args.port.is_some() {
        bail!(
            "--device emulates on a pseudo-terminal; --port is for --format serial|slcan|socketcan"
        );
    }
    let mut make = args.emulator.maker(model, args.corrupt_every, args.seed)?;
    let stats = run_emulator(&mut make, &args.emulator.line(), stop, ready, &mut |_| {})
        .context("emulated device")?;
    tracing::info!("sensor-sim: {model} done: {stats:?}");
    Ok(())
}

/// `--duration` seconds of a CAN device's traffic as a candump log, written
/// as fast as possible with stamps from now on: what `candump -L` would have
/// logged with the device alone on the bus, configured as it powers up.
fn write_can_log(
    args: &SensorSimArgs,
    model: &str,
    stop: &AtomicBool,
    ready: &mut dyn FnMut(&Path),
) -> Result<()> {
    let Some(path) = &args.output else {
        bail!("--format candump needs --output FILE");
    };
    let Some(duration) = args.emulator.duration.filter(|d| d.is_finite() && *d > 0.0) else {
        bail!("--format candump needs --duration SECONDS (the log is written as fast as possible)");
    };
    args.emulator.check_line()?;
    args.emulator.refuse_line_options("candump")?;
    if args.port.is_some() {
        bail!("--format candump writes --output; --port is for --format serial|slcan|socketcan");
    }
    let mut device = args.emulator.can_maker(model, args.seed)?()?;
    let file =
        std::fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    let mut log = std::io::BufWriter::new(file);
    ready(path);
    let start_ns = crate::transport::unix_ns();
    let mut frames = Vec::new();
    let step = 0.01;
    let mut now = 0.0;
    let mut written = 0u64;
    while now < duration && !stop.load(std::sync::atomic::Ordering::Relaxed) {
        now = (now + step).min(duration);
        frames.clear();
        device.poll(now, &mut frames);
        for (t, frame) in &frames {
            let record = CandumpRecord {
                stamp_ns: start_ns + (t * 1e9) as u64,
                interface: args.interface.clone(),
                frame: *frame,
            };
            writeln!(log, "{}", format_candump_line(&record))
                .with_context(|| format!("writing {}", path.display()))?;
            written += 1;
        }
    }
    log.flush()
        .with_context(|| format!("writing {}", path.display()))?;
    tracing::info!(
        "sensor-sim: {model}: {written} frames in {}",
        path.display()
    );
    Ok(())
}

/// A CAN device on a SocketCAN interface (`--port`, e.g. `vcan0`) in real
/// time, answering the frames other nodes send it, until stopped or
/// `--duration` passes.
fn run_on_socketcan(
    args: &SensorSimArgs,
    model: &str,
    stop: &AtomicBool,
    ready: &mut dyn FnMut(&Path),
) -> Result<()> {
    use crate::ingest::{CanSource, SocketCanSource};
    let Some(interface) = &args.port else {
        bail!("--format socketcan needs --port IFACE (e.g. vcan0)");
    };
    args.emulator.check_line()?;
    args.emulator.refuse_line_options("socketcan")?;
    let mut device = args.emulator.can_maker(model, args.seed)?()?;
    let mut bus = SocketCanSource::open(interface).map_err(|e| anyhow::anyhow!("{e}"))?;
    ready(Path::new(interface));
    let start = Instant::now();
    let mut frames = Vec::new();
    while !stop.load(std::sync::atomic::Ordering::Relaxed) {
        let now = start.elapsed().as_secs_f64();
        if args.emulator.duration.is_some_and(|d| now >= d) {
            break;
        }
        // A raw socket does not receive its own frames (CAN_RAW_RECV_OWN_MSGS
        // is off by default): the device hears only the other nodes.
        while let Some(received) = bus
            .recv(Duration::from_millis(1))
            .map_err(|e| anyhow::anyhow!("{e}"))?
        {
            device.receive(&received.frame, now);
        }
        frames.clear();
        device.poll(now, &mut frames);
        for (_, frame) in &frames {
            bus.send(frame)
                .with_context(|| format!("sending to {interface}"))?;
        }
    }
    Ok(())
}

/// Generates and writes scans: paced at `--rate` with wall-clock stamps, or
/// (for logs) unpaced with stamps `1/rate` apart.
fn stream(
    scene: &Scene,
    args: &SensorSimArgs,
    stop: &AtomicBool,
    sink: &mut dyn ScanSink,
    paced: bool,
) -> Result<()> {
    let period = Duration::from_secs_f64(1.0 / args.rate);
    let start = Instant::now();
    let start_ns = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64);
    let mut k: u64 = 0;
    while (args.scans == 0 || k < args.scans) && !stop.load(std::sync::atomic::Ordering::Relaxed) {
        let time = k as f64 / args.rate;
        let points = scene.generate(time)?;
        let stamp_ns = if paced {
            SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos() as u64)
        } else {
            start_ns + (time * 1e9) as u64
        };
        sink.write_scan(&Scan::new(k as u32, stamp_ns, points))
            .with_context(|| format!("writing scan {k}"))?;
        k += 1;
        if paced {
            let due = start + period.mul_f64(k as f64);
            crate::ingest::sleep_unless_stopped(
                due.saturating_duration_since(Instant::now()),
                stop,
            );
        }
    }
    if sink.dropped() > 0 {
        tracing::warn!(
            "sensor-sim: {} bytes dropped (nobody was reading)",
            sink.dropped()
        );
    }
    Ok(())
}
