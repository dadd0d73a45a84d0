//! RPLIDAR scan streams below the driver (`StreamDecoder`): standard nodes,
//! express and dense capsules. An input is the format (first byte), the
//! chunking (second byte), then the stream; the events (samples, losses,
//! restarts) and counts do not depend on the chunking when every chunk
//! arrives at the same time.

use crate::check::{same, stream, Chunks};
use crate::serial_device::{record, MakeDriver};
use shroud_drivers::device::{DeviceStats, HostTime};
use shroud_drivers::rplidar::stream::{SampleFormat, StreamDecoder, StreamEvent};
use shroud_drivers::rplidar::timing::SampleClock;
use shroud_drivers::rplidar::{RplidarConfig, RplidarDriver, ScanMode};

const FORMATS: [SampleFormat; 3] = [
    SampleFormat::Standard,
    SampleFormat::Express,
    SampleFormat::Dense,
];
const NOW: HostTime = HostTime::new(5_000_000_000, 1_700_000_000_000_000_000);

pub fn run(data: &[u8]) {
    let Some((&format, rest)) = data.split_first() else {
        return;
    };
    let format = FORMATS[usize::from(format) % FORMATS.len()];
    let (seed, bytes) = stream(rest);
    let whole = decode(format, [bytes].into_iter());
    same(
        &whole,
        &decode(format, Chunks::new(seed, bytes)),
        "events of the whole stream and of its chunks",
    );
}

fn decode<'a>(
    format: SampleFormat,
    chunks: impl Iterator<Item = &'a [u8]>,
) -> (Vec<StreamEvent>, DeviceStats) {
    let mut decoder = StreamDecoder::new(format, SampleClock::new(128 * 256, 115_200));
    let (mut stats, mut events) = (DeviceStats::default(), Vec::new());
    chunks.for_each(|c| decoder.feed(c, NOW, &mut stats, &mut events));
    (events, stats)
}

/// Streams recorded from the RPLIDAR emulators: the bytes after the last
/// scan descriptor (`A5 5A .. .. .. 40 type`) of a session.
pub fn seeds() -> Vec<Vec<u8>> {
    let sessions = [
        (0u8, ScanMode::Standard, "rplidar-a1"),
        (1, ScanMode::Express, "rplidar-a1"),
        (2, ScanMode::Dense, "rplidar-a2"),
    ];
    sessions
        .iter()
        .filter_map(|&(format, mode, model)| {
            let make: MakeDriver = match mode {
                ScanMode::Standard => standard,
                ScanMode::Express => express,
                _ => dense,
            };
            let device_bytes = payloads(&record(model, make, 0, 1.2));
            let start = device_bytes.windows(2).rposition(|w| w == [0xA5, 0x5A])? + 7;
            let scan = device_bytes.get(start..)?;
            let mut seed = vec![format, 17];
            seed.extend_from_slice(&scan[..scan.len().min(3000)]);
            Some(seed)
        })
        .collect()
}

fn driver(mode: ScanMode) -> Box<dyn shroud_drivers::device::DeviceDriver> {
    Box::new(RplidarDriver::new(RplidarConfig {
        scan_mode: mode,
        ..RplidarConfig::default()
    }))
}

fn standard(_: u8) -> Box<dyn shroud_drivers::device::DeviceDriver> {
    driver(ScanMode::Standard)
}

fn express(_: u8) -> Box<dyn shroud_drivers::device::DeviceDriver> {
    driver(ScanMode::Express)
}

fn dense(_: u8) -> Box<dyn shroud_drivers::device::DeviceDriver> {
    driver(ScanMode::Dense)
}

/// The device bytes of a recorded input (its records' payloads, joined).
fn payloads(input: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut rest = &input[1..];
    while let [_, len, tail @ ..] = rest {
        let (bytes, after) = tail.split_at(usize::from(*len).min(tail.len()));
        out.extend_from_slice(bytes);
        rest = after;
    }
    out
}
