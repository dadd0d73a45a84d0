//! CAN device drivers (`CanDeviceDriver`) under fuzz input, and seeds
//! recorded from the CAN device emulators (`shroud_emulators`).
//!
//! An input is a byte choosing the driver's configuration, then the frames
//! on the bus as [`crate::can_records`]: the clock advances each record's
//! step, the driver receives the frame (stamped on arrival), then is polled.

use crate::can_records::{record as frame_record, records};
use shroud_drivers::can_device::{CanDeviceDriver, CanDriverOutput, FrameClock, TimedFrame};
use shroud_drivers::device::HostTime;
use shroud_emulators::can_device::{can_emulator, CanEmulatorOptions, CanWorld};

const ORIGIN: HostTime = HostTime::new(1_000_000_000, 1_700_000_000_000_000_000);
/// The most points one cycle's cloud may hold (an ARS408 cluster list has at
/// most 255 near and 255 far clusters; a bus at most 16 rangefinders).
const MAX_CLOUD_POINTS: usize = 510;

/// A target's drivers: configuration `choice` (any byte) of its device kind.
pub type MakeDriver = fn(choice: u8) -> Box<dyn CanDeviceDriver>;

/// Runs the driver `data` chooses on its frames and checks its clouds: of a
/// bounded size, never older than the frame that started them.
pub fn run(make: MakeDriver, data: &[u8]) {
    let Some((&choice, rest)) = data.split_first() else {
        return;
    };
    let mut driver = make(choice);
    let (mut now, mut out) = (ORIGIN, Vec::new());
    driver.connect(now, true, &mut out);
    for r in records(rest) {
        now = now.plus_ns(u64::from(r.step_ms) * 1_000_000);
        driver.receive(&timed(r.frame, now), &mut out);
        driver.poll(now, &mut out);
        out.drain(..).for_each(|o| check(&o, now));
    }
    driver.disconnect(&mut out);
    out.drain(..).for_each(|o| check(&o, now));
}

fn timed(frame: shroud_drivers::can::CanFrame, now: HostTime) -> TimedFrame {
    TimedFrame {
        frame,
        stamp_ns: now.unix_ns,
        clock: FrameClock::HostReceipt,
        received: now,
    }
}

fn check(output: &CanDriverOutput, now: HostTime) {
    if let CanDriverOutput::Cloud(cloud) = output {
        let points = cloud.scan.points.len();
        assert!(points <= MAX_CLOUD_POINTS, "a cloud of {points} points");
        assert!(
            cloud.received.monotonic_ns <= now.monotonic_ns,
            "a cloud received in the future"
        );
    }
}

/// The bus side of `seconds` of a session between driver `choice` and the
/// emulator of `model`, as an input of [`run`].
pub fn record(model: &str, make: MakeDriver, choice: u8, seconds: f64) -> Vec<u8> {
    let mut device = can_emulator(model, &CanEmulatorOptions::default(), CanWorld::default())
        .expect("an emulated model");
    let mut driver = make(choice);
    let (mut now, mut out, mut input) = (ORIGIN, Vec::new(), vec![choice]);
    driver.connect(now, true, &mut out);
    let mut last_ms = 0u64;
    for ms in 0..(seconds * 1000.0) as u64 {
        let t = ms as f64 * 1e-3;
        for o in out.drain(..) {
            if let CanDriverOutput::Send(frame) = o {
                device.receive(&frame, t);
            }
        }
        let mut sent = Vec::new();
        device.poll(t, &mut sent);
        for (_, frame) in sent {
            let step = u8::try_from(ms - last_ms).unwrap_or(u8::MAX);
            last_ms = ms;
            now = ORIGIN.plus_ns(ms * 1_000_000);
            input.extend(frame_record(&frame, step));
            driver.receive(&timed(frame, now), &mut out);
            driver.poll(now, &mut out);
        }
    }
    input
}
