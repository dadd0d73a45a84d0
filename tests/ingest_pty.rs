//! Sensor ingest over real devices: pseudo-terminals (libc::openpty) carrying the
//! serial protocol and SLCAN to the serialport-based readers, unplugging and
//! replugging them, candump replay from a file, the in-memory bus, and a
//! SocketCAN open (skipped when the kernel has no CAN interface).

use shroud_drivers::can::{CanFrame, CanSensorConfig};
use shroud_drivers::serial::{PointEncoding, SerialEncoder};
use shroud_drivers::{ErrorKind, Scan};
use shroud_nodes::cli::sensor_sim::{run_sensor_sim_with, SensorSimArgs, SimFormat};
use shroud_nodes::ingest::pty::Pty;
use shroud_nodes::ingest::sim::{CandumpWriter, ScanSink, SerialSensorWriter, SlcanWriter};
use shroud_nodes::ingest::{
    memory_bus, run_can_reader, run_serial_reader, BackoffConfig, CanReaderConfig, CanSource,
    CanSourceSpec, ReaderStats, SerialReaderConfig, SlcanSource, SocketCanSource, SourceError,
};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::{Duration, Instant};
use tracing_subscriber::util::SubscriberInitExt;

const DEADLINE: Duration = Duration::from_secs(20);

fn scan(sequence: u32, n: usize) -> Scan {
    let points = (0..n)
        .map(|i| {
            let t = i as f32 * 0.01 + sequence as f32;
            [t.sin(), t.cos(), 0.5 + 0.001 * (i % 100) as f32]
        })
        .collect();
    Scan::new(
        sequence,
        1_700_000_000_000_000_000 + u64::from(sequence),
        points,
    )
}

fn fast_backoff() -> BackoffConfig {
    BackoffConfig {
        initial: Duration::from_millis(20),
        max: Duration::from_millis(100),
    }
}

/// Log lines of one thread, captured from `tracing`.
#[derive(Clone, Default)]
struct Logs(Arc<Mutex<Vec<u8>>>);

impl Logs {
    fn text(&self) -> String {
        String::from_utf8_lossy(&self.0.lock().unwrap()).into_owned()
    }

    fn run<T>(&self, f: impl FnOnce() -> T) -> T {
        let logs = self.clone();
        let _guard = tracing_subscriber::fmt()
            .with_max_level(tracing_subscriber::filter::LevelFilter::DEBUG)
            .with_ansi(false)
            .with_writer(move || logs.clone())
            .set_default();
        f()
    }
}

impl Write for Logs {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A reader running on its own thread, collecting scans.
struct Running {
    stop: Arc<AtomicBool>,
    scans: Arc<Mutex<Vec<Scan>>>,
    logs: Logs,
    handle: thread::JoinHandle<Result<ReaderStats, String>>,
}

impl Running {
    fn serial(config: SerialReaderConfig) -> Self {
        Self::spawn(move |on_scan, stop| {
            run_serial_reader(&config, on_scan, stop).map_err(|e| e.to_string())
        })
    }

    fn can(
        mut open: impl FnMut() -> Result<Box<dyn CanSource>, SourceError> + Send + 'static,
        config: CanReaderConfig,
    ) -> Self {
        Self::spawn(move |on_scan, stop| {
            run_can_reader(&mut open, &config, on_scan, stop).map_err(|e| e.to_string())
        })
    }

    fn spawn(
        run: impl FnOnce(&mut dyn FnMut(Scan, &ReaderStats), &AtomicBool) -> Result<ReaderStats, String>
            + Send
            + 'static,
    ) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let scans = Arc::new(Mutex::new(Vec::new()));
        let logs = Logs::default();
        let handle = {
            let (stop, scans, logs) = (stop.clone(), scans.clone(), logs.clone());
            thread::spawn(move || {
                logs.run(|| run(&mut |scan, _| scans.lock().unwrap().push(scan), &stop))
            })
        };
        Self {
            stop,
            scans,
            logs,
            handle,
        }
    }

    /// Waits until `done(scans, logs)` holds (or panics after the deadline).
    fn wait_for(&self, what: &str, done: impl Fn(&[Scan], &str) -> bool) {
        let start = Instant::now();
        while !done(&self.scans.lock().unwrap(), &self.logs.text()) {
            assert!(
                !self.handle.is_finished(),
                "reader ended while waiting for {what}"
            );
            assert!(
                start.elapsed() < DEADLINE,
                "timed out waiting for {what}; logs:\n{}",
                self.logs.text()
            );
            thread::sleep(Duration::from_millis(10));
        }
    }

    fn scans(&self) -> Vec<Scan> {
        self.scans.lock().unwrap().clone()
    }

    /// Sets the stop flag and checks the reader ends promptly.
    fn stop(self) -> (ReaderStats, Vec<Scan>, String) {
        let asked = Instant::now();
        self.stop.store(true, Ordering::Relaxed);
        let stats = self
            .handle
            .join()
            .expect("reader panicked")
            .expect("reader failed");
        assert!(
            asked.elapsed() < Duration::from_secs(2),
            "stop took {:?}",
            asked.elapsed()
        );
        let scans = self.scans.lock().unwrap().clone();
        (stats, scans, self.logs.text())
    }

    /// Waits for a reader that ends by itself (its source finished).
    fn join(self) -> (ReaderStats, Vec<Scan>, String) {
        let start = Instant::now();
        while !self.handle.is_finished() {
            assert!(start.elapsed() < DEADLINE, "reader did not finish");
            thread::sleep(Duration::from_millis(10));
        }
        let stats = self
            .handle
            .join()
            .expect("reader panicked")
            .expect("reader failed");
        let scans = self.scans.lock().unwrap().clone();
        (stats, scans, self.logs.text())
    }
}

fn path_str(path: &Path) -> String {
    path.to_str().expect("UTF-8 path").to_owned()
}

#[test]
fn ingest_serial_scans_cross_a_real_pty_intact_despite_garbage_and_truncation() {
    let pty = Pty::open().unwrap();
    pty.set_nonblocking().unwrap();
    let slave = path_str(pty.slave_path());
    let mut config = SerialReaderConfig::new(&slave, 921_600);
    config.backoff = fast_backoff();
    let reader = Running::serial(config);

    let mut writer = SerialSensorWriter::new(
        pty.master_clone().unwrap(),
        SerialEncoder::new(PointEncoding::F32Metres, 100),
    );
    let sent: Vec<Scan> = (0..6).map(|s| scan(s, 450)).collect();
    let mut total = 0;
    let size = |s: &Scan| {
        SerialEncoder::new(PointEncoding::F32Metres, 100)
            .encode(s)
            .unwrap()
            .len()
    };
    total += size(&sent[0]) + size(&sent[1]) + size(&sent[2]) + size(&sent[3]) + size(&sent[5]);
    writer.write_scan(&sent[0]).unwrap();
    writer.write_scan(&sent[1]).unwrap();
    // Garbage mid-stream, then a frame cut short by the next scan.
    let garbage = b"\x00\xFFnoise\xA5\x5A\x01junk";
    writer.write_raw(garbage).unwrap();
    total += garbage.len();
    let lost = SerialEncoder::new(PointEncoding::F32Metres, 100)
        .encode(&scan(99, 50))
        .unwrap();
    writer.write_raw(&lost[..lost.len() / 2]).unwrap();
    total += lost.len() / 2;
    for s in &sent[2..4] {
        writer.write_scan(s).unwrap();
    }
    // Another encoding, with intensity, in 1-byte writes.
    let mut with_intensity = scan(4, 300);
    with_intensity.intensity = Some((0..300).map(|i| i as f32).collect());
    let bytes = SerialEncoder::new(PointEncoding::I16Millimetres, 64)
        .encode(&with_intensity)
        .unwrap();
    total += bytes.len();
    for b in &bytes {
        writer.write_raw(std::slice::from_ref(b)).unwrap();
    }
    writer.write_scan(&sent[5]).unwrap();
    assert_eq!(writer.dropped_bytes, 0);

    reader.wait_for("6 scans", |scans, _| scans.len() >= 6);
    let (stats, scans, _) = reader.stop();
    let sequences: Vec<u32> = scans.iter().map(|s| s.sequence).collect();
    assert_eq!(sequences, vec![0, 1, 2, 3, 4, 5]);
    for i in [0, 1, 2, 3, 5] {
        assert_eq!(scans[i], sent[i], "scan {i} arrives bit for bit");
    }
    assert_eq!(scans[4].intensity, with_intensity.intensity);
    for (a, b) in scans[4]
        .points
        .iter()
        .flatten()
        .zip(with_intensity.points.iter().flatten())
    {
        assert!((a - b).abs() <= 5e-4);
    }
    assert_eq!(stats.scans, 6);
    assert_eq!(stats.opens, 1);
    assert_eq!(stats.disconnects, 0);
    assert!(stats.decoder.errors(ErrorKind::Garbage) >= 1, "{stats}");
    assert_eq!(stats.decoder.errors(ErrorKind::Truncated), 1, "{stats}");
    assert_eq!(stats.decoder.errors(ErrorKind::MissingFrame), 0, "{stats}");
    assert_eq!(stats.bytes_read, total as u64, "every byte read once");
    assert_eq!(stats.decoder.input, total as u64);
}

#[test]
fn ingest_unplugging_the_pty_is_logged_counted_and_stop_stays_prompt() {
    let pty = Pty::open().unwrap();
    let slave = path_str(pty.slave_path());
    let mut config = SerialReaderConfig::new(&slave, 115_200);
    config.backoff = fast_backoff();
    let reader = Running::serial(config);
    let mut master = pty.into_master();
    let encoder = SerialEncoder::new(PointEncoding::I32Millimetres, 64);
    master
        .write_all(&encoder.encode(&scan(1, 200)).unwrap())
        .unwrap();
    reader.wait_for("the first scan", |scans, _| scans.len() == 1);
    // Half a scan, then the device is unplugged.
    let next = encoder.encode(&scan(2, 200)).unwrap();
    master.write_all(&next[..next.len() / 2]).unwrap();
    thread::sleep(Duration::from_millis(100));
    drop(master);
    reader.wait_for("a logged disconnect and failed reopens", |_, logs| {
        logs.contains("serial sensor disconnected") && logs.contains("cannot open serial sensor")
    });
    thread::sleep(Duration::from_millis(150));
    let (stats, scans, logs) = reader.stop();
    assert_eq!(scans.len(), 1);
    assert_eq!(stats.disconnects, 1, "{stats}");
    assert_eq!(stats.opens, 1);
    assert!(stats.open_failures >= 2, "kept trying: {stats}");
    // The half-sent scan is counted, not delivered.
    let lost = stats.decoder.errors(ErrorKind::Truncated)
        + stats.decoder.errors(ErrorKind::IncompleteScan);
    assert!(lost >= 1, "{stats}");
    assert!(logs.contains("WARN"), "{logs}");
    assert!(logs.contains("serial reader stopped"), "{logs}");
}

#[test]
fn ingest_a_replugged_device_behind_a_stable_path_is_reopened() {
    // Like /dev/serial/by-id/...: a symlink that is missing, then points at a
    // device, then at another after a replug.
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("sensor");
    let mut config = SerialReaderConfig::new(&path_str(&link), 115_200);
    config.backoff = fast_backoff();
    let reader = Running::serial(config);
    reader.wait_for("failed opens", |_, logs| {
        logs.contains("cannot open serial sensor")
    });

    let encoder = SerialEncoder::default();
    let first = Pty::open().unwrap();
    std::os::unix::fs::symlink(first.slave_path(), &link).unwrap();
    let mut master = first.into_master();
    master
        .write_all(&encoder.encode(&scan(1, 10)).unwrap())
        .unwrap();
    reader.wait_for("scan 1", |scans, _| scans.len() == 1);
    drop(master);
    reader.wait_for("the disconnect", |_, logs| {
        logs.contains("serial sensor disconnected")
    });

    let second = Pty::open().unwrap();
    std::fs::remove_file(&link).unwrap();
    std::os::unix::fs::symlink(second.slave_path(), &link).unwrap();
    let mut master = second.into_master();
    // Written before the reader is back: a pty keeps it for the next opener.
    master
        .write_all(&encoder.encode(&scan(2, 10)).unwrap())
        .unwrap();
    reader.wait_for("scan 2 after the replug", |scans, _| scans.len() == 2);
    let (stats, scans, _) = reader.stop();
    assert_eq!(scans, vec![scan(1, 10), scan(2, 10)]);
    assert_eq!(stats.opens, 2, "{stats}");
    assert_eq!(stats.disconnects, 1, "{stats}");
    assert!(stats.open_failures >= 1, "{stats}");
}

#[test]
fn ingest_bad_reader_settings_are_errors_not_retries() {
    let stop = AtomicBool::new(false);
    let config = SerialReaderConfig::new("/dev/null", 0);
    assert!(run_serial_reader(&config, &mut |_, _| {}, &stop).is_err());
    let missing = CanSourceSpec::Candump {
        path: "/nonexistent/run.log".into(),
        pace: shroud_nodes::ingest::ReplayPace::AsFastAsPossible,
        interface: None,
    };
    let error = run_can_reader(
        &mut || missing.open(),
        &CanReaderConfig::default(),
        &mut |_, _| {},
        &stop,
    )
    .unwrap_err();
    assert!(
        error.to_string().contains("/nonexistent/run.log"),
        "{error}"
    );
}

#[test]
fn ingest_slcan_over_a_pty_end_to_end() {
    let pty = Pty::open().unwrap();
    pty.set_nonblocking().unwrap();
    let slave = path_str(pty.slave_path());
    let sensor = CanSensorConfig {
        base_id: 0x18FF_0000,
        extended: true,
    };
    let config = CanReaderConfig {
        sensor,
        backoff: fast_backoff(),
    };
    let open_path = slave.clone();
    let reader = Running::can(
        move || {
            Ok(
                Box::new(SlcanSource::open(&open_path, 115_200, Some(500_000))?)
                    as Box<dyn CanSource>,
            )
        },
        config,
    );
    // The reader configures the adapter: close, 500 kbit/s, open.
    let mut master = pty.master_clone().unwrap();
    let mut commands = Vec::new();
    let start = Instant::now();
    while !commands.ends_with(b"O\r") {
        let mut buf = [0u8; 64];
        match master.read(&mut buf) {
            Ok(n) => commands.extend_from_slice(&buf[..n]),
            // WouldBlock: nothing yet; EIO (5): the reader has not opened the slave yet.
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock || e.raw_os_error() == Some(5) => {
                thread::sleep(Duration::from_millis(5))
            }
            Err(e) => panic!("{e}"),
        }
        assert!(start.elapsed() < DEADLINE, "no open commands: {commands:?}");
    }
    assert_eq!(commands, b"C\rS6\rO\r");

    let mut writer = SlcanWriter::new(pty.master_clone().unwrap(), sensor);
    writer.write_scan(&scan(1, 40)).unwrap();
    // A foreign device, a garbage line and an adapter error between scans.
    writer
        .write_frames(&[CanFrame::new(0x123, false, &[1, 2]).unwrap()])
        .unwrap();
    writer.write_raw(b"t12\r\x07zzz\r").unwrap();
    writer.write_scan(&scan(2, 40)).unwrap();
    writer.corrupt_every = 1;
    writer.write_scan(&scan(3, 40)).unwrap();
    writer.corrupt_every = 0;
    writer.write_scan(&scan(4, 40)).unwrap();
    reader.wait_for("scans 1, 2 and 4", |scans, _| scans.len() >= 3);
    let (stats, scans, _) = reader.stop();
    assert_eq!(
        scans.iter().map(|s| s.sequence).collect::<Vec<_>>(),
        vec![1, 2, 4]
    );
    for (got, n) in scans.iter().zip([1, 2, 4]) {
        let want = scan(n, 40);
        assert_eq!(got.stamp_ns, want.stamp_ns);
        for (a, b) in got
            .points
            .iter()
            .flatten()
            .zip(want.points.iter().flatten())
        {
            assert!((a - b).abs() <= 5e-4);
        }
    }
    assert_eq!(stats.decoder.errors(ErrorKind::UnknownId), 1, "{stats}");
    assert!(stats.transport.errors(ErrorKind::BadSlcan) >= 3, "{stats}");
    assert_eq!(stats.transport.errors(ErrorKind::SlcanNak), 1, "{stats}");
    // Scan 3 was corrupted: its loss shows in the decoder's counters.
    assert!(stats.decoder.total_errors() >= 2, "{stats}");
    // Dropping the source closes the channel.
    let mut tail = Vec::new();
    let _ = master.read_to_end(&mut tail);
    assert!(tail.ends_with(b"C\r"), "{tail:?}");
}

#[test]
fn ingest_sensor_sim_cli_streams_serial_and_slcan_to_a_pty() {
    for format in [SimFormat::Serial, SimFormat::Slcan] {
        let args = SensorSimArgs {
            format,
            points: 500,
            rate: 50.0,
            scans: 0,
            scene: "terrain".into(),
            ..SensorSimArgs::default()
        };
        let sim_stop = Arc::new(AtomicBool::new(false));
        let (path_tx, path_rx) = std::sync::mpsc::channel::<PathBuf>();
        let sim = {
            let sim_stop = sim_stop.clone();
            thread::spawn(move || {
                run_sensor_sim_with(&args, &sim_stop, &mut |p| {
                    path_tx.send(p.to_owned()).unwrap()
                })
                .map_err(|e| e.to_string())
            })
        };
        let slave = path_str(&path_rx.recv_timeout(DEADLINE).unwrap());
        let reader = match format {
            SimFormat::Serial => Running::serial(SerialReaderConfig::new(&slave, 115_200)),
            _ => {
                let spec: CanSourceSpec = format!("slcan:{slave}").parse().unwrap();
                Running::can(move || spec.open(), CanReaderConfig::default())
            }
        };
        reader.wait_for("3 scans from the simulator", |scans, _| scans.len() >= 3);
        sim_stop.store(true, Ordering::Relaxed);
        sim.join().unwrap().unwrap();
        let scans = reader.scans();
        assert!(scans.iter().all(|s| s.points.len() == 500), "{format:?}");
        assert!(scans.windows(2).all(|w| w[0].sequence < w[1].sequence));
        // The simulator ending is the device going away.
        reader.wait_for("the disconnect", |_, logs| logs.contains("disconnected"));
        let (stats, _, _) = reader.stop();
        assert_eq!(stats.disconnects, 1, "{format:?}: {stats}");
    }
}

#[test]
fn ingest_candump_replay_from_a_temp_file() {
    let dir = tempfile::tempdir().unwrap();
    let log = dir.path().join("run.log");
    let sensor = CanSensorConfig::default();
    {
        let mut writer = CandumpWriter::new(std::fs::File::create(&log).unwrap(), sensor, "can0");
        for s in 0..5 {
            let mut sc = scan(s, 30);
            sc.stamp_ns = 1_700_000_000_000_000_000 + u64::from(s) * 50_000_000; // 20 Hz
            writer.write_scan(&sc).unwrap();
            if s == 1 {
                writeln!(writer.out, "this is not a candump line").unwrap();
                writeln!(writer.out, "(1700000000.100000) can1 123#00").unwrap();
            }
        }
    }
    // As fast as possible.
    let spec: CanSourceSpec = format!("candump:{}@max", log.display()).parse().unwrap();
    let start = Instant::now();
    let (stats, scans, _) = Running::can(move || spec.open(), CanReaderConfig::default()).join();
    let fast = start.elapsed();
    assert_eq!(
        scans.iter().map(|s| s.sequence).collect::<Vec<_>>(),
        vec![0, 1, 2, 3, 4]
    );
    assert_eq!(scans[3].stamp_ns, 1_700_000_000_150_000_000);
    assert_eq!(stats.transport.errors(ErrorKind::BadCandump), 1, "{stats}");
    assert_eq!(stats.decoder.errors(ErrorKind::UnknownId), 1, "{stats}");
    assert_eq!(stats.opens, 1);
    // In real time the 5 scans span 200 ms of stamps; at 2x speed, 100 ms.
    for (speed, least) in [(1.0, 190), (2.0, 95)] {
        let spec = CanSourceSpec::Candump {
            path: log.clone(),
            pace: shroud_nodes::ingest::ReplayPace::RealTime { speed },
            interface: Some("can0".into()),
        };
        let start = Instant::now();
        let (stats, scans, _) =
            Running::can(move || spec.open(), CanReaderConfig::default()).join();
        let took = start.elapsed();
        assert_eq!(scans.len(), 5);
        assert_eq!(
            stats.decoder.errors(ErrorKind::UnknownId),
            0,
            "can1 filtered out"
        );
        assert!(
            took >= Duration::from_millis(least),
            "{speed}x took {took:?}"
        );
        assert!(
            took < Duration::from_millis(least * 5 + 1000),
            "{speed}x took {took:?}"
        );
        assert!(fast < took);
    }
    // The simulator writes the same logs.
    let sim_log = dir.path().join("sim.log");
    let args = SensorSimArgs {
        format: SimFormat::Candump,
        output: Some(sim_log.clone()),
        scans: 4,
        points: 100,
        ..SensorSimArgs::default()
    };
    run_sensor_sim_with(&args, &AtomicBool::new(false), &mut |_| {}).unwrap();
    let spec: CanSourceSpec = format!("candump:{}@max", sim_log.display())
        .parse()
        .unwrap();
    let (stats, scans, _) = Running::can(move || spec.open(), CanReaderConfig::default()).join();
    assert_eq!(scans.len(), 4);
    assert!(scans.iter().all(|s| s.points.len() == 100));
    assert_eq!(stats.decoder.total_errors(), 0, "{stats}");
}

#[test]
fn ingest_in_memory_bus() {
    let (tx, bus) = memory_bus();
    let sensor = CanSensorConfig {
        base_id: 0x500,
        extended: false,
    };
    let mut bus = Some(bus);
    let reader = Running::can(
        move || match bus.take() {
            Some(bus) => Ok(Box::new(bus) as Box<dyn CanSource>),
            None => Err(SourceError::Finished("memory-bus".into())),
        },
        CanReaderConfig {
            sensor,
            backoff: fast_backoff(),
        },
    );
    let sender = thread::spawn(move || {
        for s in 0..3 {
            let frames = sensor.encode(&scan(s, 25)).unwrap();
            for (i, f) in frames.iter().enumerate() {
                if s == 1 && i == 5 {
                    continue; // a lost frame
                }
                assert!(tx.send(*f));
                if i % 7 == 0 {
                    assert!(tx.send(CanFrame::new(0x100, false, &[0xAA]).unwrap()));
                }
            }
        }
    });
    let (stats, scans, _) = reader.join();
    sender.join().unwrap();
    assert_eq!(
        scans.iter().map(|s| s.sequence).collect::<Vec<_>>(),
        vec![0, 2]
    );
    assert_eq!(stats.decoder.errors(ErrorKind::MissingFrame), 1, "{stats}");
    assert!(stats.decoder.errors(ErrorKind::UnknownId) >= 9, "{stats}");
    assert_eq!(stats.frames_received, stats.decoder.input);
}

#[test]
fn ingest_socketcan_when_an_interface_exists() {
    for interface in ["can0", "vcan0"] {
        // The real open call, every time.
        let mut source = match SocketCanSource::open(interface) {
            Ok(source) => source,
            Err(error) => {
                println!("skipping: no CAN interface ({error})");
                continue;
            }
        };
        // A frame sent on one socket reaches the others on the interface.
        let sender = SocketCanSource::open(interface).unwrap();
        let sensor = CanSensorConfig::default();
        for f in sensor.encode(&scan(7, 5)).unwrap() {
            sender.send(&f).unwrap();
        }
        let mut frames = Vec::new();
        let start = Instant::now();
        while frames.len() < 8 && start.elapsed() < Duration::from_secs(2) {
            if let Some(timed) = source.recv(Duration::from_millis(100)).unwrap() {
                let f = timed.frame;
                if sensor.classify(&f).is_some() {
                    frames.push(f);
                }
            }
        }
        assert_eq!(frames, sensor.encode(&scan(7, 5)).unwrap(), "{interface}");
        return;
    }
}
