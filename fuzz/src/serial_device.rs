//! Serial device drivers (`DeviceDriver`) under fuzz input, and seeds
//! recorded from the serial device emulators (`shroud_emulators`).
//!
//! An input is a byte choosing the driver's configuration, then what the
//! device sends, as records `[step_ms, len, len bytes]`:
//! the clock advances `step_ms`, the driver receives the bytes, then is
//! polled (as the node calls it). What the driver writes is dropped: a
//! driver is a deterministic state machine of its input and clock, so a
//! recorded device side replays the recorded session.

use shroud_drivers::device::{DeviceDriver, DriverOutput, HostTime, ReadWindow, StampBound};
use shroud_emulators::device::{emulator, EmulatorOptions, RayReturn, RaySource};

/// Where the clock starts (monotonic and Unix).
const ORIGIN: HostTime = HostTime::new(1_000_000_000, 1_700_000_000_000_000_000);
/// The recorder's clock step.
const STEP_MS: u8 = 2;
/// The most rays a scan of any supported device has (a UTM-30LX multi-echo
/// scan has 1081 steps of 3 echoes; an RPLIDAR revolution at most 8192
/// samples): a bound on what a driver may deliver.
const MAX_RAYS: usize = 1 << 15;

/// A target's drivers: configuration `choice` (any byte) of its device kind.
pub type MakeDriver = fn(choice: u8) -> Box<dyn DeviceDriver>;

/// Runs the driver `data` chooses on the records of `data` and checks what it
/// says: every byte counted, one `scans` count per delivered scan, scans of
/// a bounded size, stamps inside their own time bounds, and reasons that say
/// something. Each record is one read, called when the one before returned.
pub fn run(make: MakeDriver, data: &[u8]) {
    let Some((&choice, mut rest)) = data.split_first() else {
        return;
    };
    let mut driver = make(choice);
    let mut now = ORIGIN;
    let mut out = Vec::new();
    let (mut fed, mut scans) = (0u64, 0u64);
    driver.connect(now, &mut out);
    let mut previous_read: Option<HostTime> = None;
    while let [step, len, tail @ ..] = rest {
        let (bytes, after) = tail.split_at(usize::from(*len).min(tail.len()));
        now = now.plus_ns(u64::from(*step) * 1_000_000);
        let window = ReadWindow {
            after: previous_read,
            returned: now,
        };
        driver.receive_read(bytes, window, &mut out);
        previous_read = Some(now);
        driver.poll(now, &mut out);
        fed += bytes.len() as u64;
        scans += out.drain(..).map(|o| check(&o)).sum::<u64>();
        rest = after;
    }
    driver.shutdown(&mut out);
    assert_eq!(driver.stats().bytes, fed, "bytes counted by the driver");
    assert_eq!(driver.stats().scans, scans, "scans counted by the driver");
}

/// Checks one output; 1 for a scan.
fn check(output: &DriverOutput) -> u64 {
    match output {
        DriverOutput::Scan(scan) => {
            assert!(
                scan.rays.len() <= MAX_RAYS,
                "a scan of {} rays",
                scan.rays.len()
            );
            if let StampBound::Within {
                earliest_ns,
                latest_ns,
            } = scan.stamp_bound
            {
                assert!(
                    earliest_ns <= scan.stamp_ns && scan.stamp_ns <= latest_ns,
                    "stamp {} outside its bound [{earliest_ns}, {latest_ns}]",
                    scan.stamp_ns
                );
            }
            1
        }
        DriverOutput::Reconnect(reason) => {
            assert!(!reason.is_empty(), "a reconnect without a reason");
            0
        }
        _ => 0,
    }
}

/// A round room: every ray meets a wall 1.5 to 2.5 m away.
struct Room;

impl RaySource for Room {
    fn cast(&self, angle: f64, _time: f64, max_range: f64) -> Option<RayReturn> {
        let range = 2.0 + 0.5 * (3.0 * angle).sin();
        (range <= max_range).then_some(RayReturn {
            range,
            reflectance: 0.6,
        })
    }
}

/// The device side of `seconds` of a session between driver `choice` and
/// the emulator of `model`, as an input of [`run`].
pub fn record(model: &str, make: MakeDriver, choice: u8, seconds: f64) -> Vec<u8> {
    let mut device =
        emulator(model, Box::new(Room), &EmulatorOptions::default()).expect("an emulated model");
    let mut driver = make(choice);
    let (mut now, mut out, mut input) = (ORIGIN, Vec::new(), vec![choice]);
    driver.connect(now, &mut out);
    let steps = (seconds * 1000.0 / f64::from(STEP_MS)) as usize;
    for _ in 0..steps {
        now = now.plus_ns(u64::from(STEP_MS) * 1_000_000);
        let t = now.since(ORIGIN) as f64 * 1e-9;
        for o in out.drain(..) {
            match o {
                DriverOutput::Write(bytes) => device.receive(&bytes, t),
                DriverOutput::SetDtr(asserted) => device.set_dtr(asserted, t),
                _ => {}
            }
        }
        let mut sent = Vec::new();
        device.poll(t, &mut sent);
        // The first record carries the clock step, the rest of a long burst none.
        let mut step = STEP_MS;
        for chunk in sent.chunks(255).chain(sent.is_empty().then_some(&[][..])) {
            input.extend([step, chunk.len() as u8]);
            input.extend_from_slice(chunk);
            driver.receive(chunk, now, &mut out);
            driver.poll(now, &mut out);
            step = 0;
        }
    }
    input
}
