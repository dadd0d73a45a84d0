//! Property tests: arbitrary input never panics and never breaks the scan
//! invariants; a stream split anywhere decodes the same; a single mutated
//! byte never yields a scan with a hole (it is dropped and counted).

use proptest::prelude::*;

use super::sim::*;
use crate::device::DeviceStats;
use crate::device::{DeviceDriver, DeviceState, DriverOutput, Ray};
use crate::rplidar::angle::rep103;
use crate::rplidar::node::valid_first;
use crate::rplidar::reader::ResponseReader;
use crate::rplidar::stream::{SampleFormat, StreamDecoder, StreamEvent};
use crate::rplidar::{RplidarConfig, RplidarDriver};

fn check_scan_invariants(out: &[DriverOutput], max_rays: usize) {
    for scan in scans(out) {
        assert!(!scan.rays.is_empty() && scan.rays.len() <= max_rays);
        assert_eq!(scan.rays[0].offset_ns, 0);
        assert!(scan
            .rays
            .windows(2)
            .all(|w| w[0].offset_ns <= w[1].offset_ns));
        for ray in &scan.rays {
            let pi = std::f32::consts::PI;
            assert!(ray.angle > -pi && ray.angle <= pi, "{}", ray.angle);
            assert!(ray.range.is_nan() || ray.range > 0.0);
        }
    }
}

/// A driver streaming `format` (standard / legacy express from an A2; dense
/// from an S1-like device).
fn streaming(format: SampleFormat) -> Harness {
    let mut device = a2_device(Vec::new());
    let config = match format {
        SampleFormat::Standard => RplidarConfig {
            scan_mode: crate::rplidar::ScanMode::Standard,
            ..RplidarConfig::default()
        },
        SampleFormat::Express => RplidarConfig::default(),
        SampleFormat::Dense => {
            device.info = info_payload(0x61, 1, 2, 18);
            device.modes = vec![("Standard", 0x81, 250 << 8), ("DenseBoost", 0x85, 108 << 8)];
            device.typical = 1;
            RplidarConfig::default()
        }
    };
    let mut h = Harness::new(RplidarDriver::new(config));
    device.run(&mut h, 40);
    assert_eq!(h.driver.state(), &DeviceState::Streaming);
    h
}

fn a2_device(stream: Vec<u8>) -> FakeLidar {
    FakeLidar {
        info: info_payload(0x28, 1, 20, 5),
        health: [0, 0, 0],
        sample_rate: Some([0xFC, 0x01, 0xFE, 0x00]),
        modes: Vec::new(),
        typical: 0,
        board_flag: Some(1),
        stream,
    }
}

/// `cases` cases; failures are not persisted to files (the source tree is
/// shared).
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

fn format_strategy() -> impl Strategy<Value = SampleFormat> {
    prop_oneof![
        Just(SampleFormat::Standard),
        Just(SampleFormat::Express),
        Just(SampleFormat::Dense),
    ]
}

proptest! {
    #![proptest_config(config(64))]

    #[test]
    fn random_bytes_never_panic_while_configuring(
        bytes in proptest::collection::vec(any::<u8>(), 0..600),
        chunk in 1usize..64,
    ) {
        let mut h = Harness::new(RplidarDriver::new(RplidarConfig::default()));
        h.connect();
        h.wait(100);
        let mut out = Vec::new();
        for part in bytes.chunks(chunk) {
            out.extend(h.feed(part));
            out.extend(h.wait(300));
        }
        check_scan_invariants(&out, 8192);
        prop_assert_eq!(h.driver.stats().bytes, bytes.len() as u64);
        let mut reader = ResponseReader::default();
        let mut rest = bytes.as_slice();
        while !rest.is_empty() {
            let fed = reader.feed(rest);
            prop_assert!(fed.consumed > 0);
            rest = &rest[fed.consumed..];
        }
    }

    #[test]
    fn random_bytes_never_panic_while_streaming(
        format in format_strategy(),
        bytes in proptest::collection::vec(any::<u8>(), 0..3000),
        chunk in 1usize..300,
    ) {
        let mut h = streaming(format);
        let mut out = Vec::new();
        for part in bytes.chunks(chunk) {
            out.extend(h.feed(part));
        }
        check_scan_invariants(&out, 8192);
    }

}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn a_mutated_byte_never_yields_a_scan_with_a_hole(
        format in format_strategy(),
        position in any::<prop::sample::Index>(),
        value in any::<u8>(),
    ) {
        let clean = stream_of(format);
        let mut mutated = clean.clone();
        let at = position.index(mutated.len());
        prop_assume!(mutated[at] != value);
        mutated[at] = value;
        let (reference, clean_stats) = decode(format, &[&clean]);
        let (got, stats) = decode(format, &[&mutated]);
        let delivered: usize = got.iter().map(|r| r.rays.len()).sum();
        let expected: usize = reference.iter().map(|r| r.rays.len()).sum();
        // Standard nodes do not protect their S flag: a mutation that turns
        // a valid byte0 into another valid one with S flipped moves a
        // boundary undetectably (revolutions merge or split, without holes).
        let flipped_start = format == SampleFormat::Standard
            && at % 5 == 0
            && valid_first(value)
            && (value ^ clean[at]) & 1 == 1;
        if delivered < expected && !flipped_start {
            // A damaged first revolution is dropped as partial: a note, not an error.
            let dropped = |s: &DeviceStats| s.total_errors() + s.notes("partial_revolution");
            prop_assert!(dropped(&stats) > dropped(&clean_stats), "drops are counted");
        }
        match format {
            SampleFormat::Standard => {
                let all = all_rays(format, &clean);
                for rev in &got {
                    prop_assert!(is_window_of(&rev.rays, &all), "a scan with a hole");
                }
            }
            _ => {
                // Checksummed: every scan is one of the clean ones, in order.
                let mut rest = reference.iter();
                for rev in &got {
                    prop_assert!(
                        rest.any(|r| same_rays(&r.rays, &rev.rays)),
                        "a scan that is not a clean revolution"
                    );
                }
            }
        }
    }

    #[test]
    fn a_mutated_transcript_never_panics_nor_yields_a_short_revolution(
        position in any::<prop::sample::Index>(),
        value in any::<u8>(),
    ) {
        let mut bytes = a2_transcript(express_stream(2, 21));
        let at = position.index(bytes.len());
        bytes[at] = value;
        let mut h = Harness::new(RplidarDriver::new(RplidarConfig::default()));
        h.connect();
        let mut out = h.wait(100);
        out.extend(h.feed(&bytes));
        for _ in 0..4 {
            out.extend(h.wait(1000));
        }
        check_scan_invariants(&out, 8192);
        prop_assert!(scans(&out).iter().all(|s| s.rays.len() == 24 * 32));
    }
}

fn stream_of(format: SampleFormat) -> Vec<u8> {
    match format {
        SampleFormat::Standard => standard_stream(3, 120, 31),
        SampleFormat::Express => express_stream(2, 32),
        SampleFormat::Dense => dense_stream(2, 33),
    }
}

/// Every sample of a clean stream as a ray (offsets zeroed).
fn all_rays(format: SampleFormat, bytes: &[u8]) -> Vec<Ray> {
    let mut decoder = StreamDecoder::new(format, clock());
    let (mut stats, mut events) = (DeviceStats::default(), Vec::new());
    decoder.feed(bytes, t(0), &mut stats, &mut events);
    events
        .into_iter()
        .filter_map(|e| match e {
            StreamEvent::Sample(s) => Some(Ray {
                angle: rep103(s.heading_q16),
                range: if s.distance_q2 == 0 {
                    f32::NAN
                } else {
                    (f64::from(s.distance_q2) / 4000.0) as f32
                },
                intensity: s.quality.map(f32::from),
                offset_ns: 0,
            }),
            _ => None,
        })
        .collect()
}

/// Whether `rays` is a contiguous run of `all` with at most one ray changed
/// (the mutated node itself; standard nodes carry no checksum).
fn is_window_of(rays: &[Ray], all: &[Ray]) -> bool {
    let strip = |r: &Ray| Ray { offset_ns: 0, ..*r };
    (0..all.len().saturating_sub(rays.len()) + 1).any(|start| {
        let window = &all[start..start + rays.len()];
        let differing = window
            .iter()
            .zip(rays)
            .filter(|(a, b)| !same_ray(a, &strip(b)))
            .count();
        differing <= 1
    })
}

/// What an A2 (firmware 1.20, PWM board) sends in answer to a whole connect,
/// back to back, followed by `stream`.
fn a2_transcript(stream: Vec<u8>) -> Vec<u8> {
    let device = a2_device(stream);
    [
        device.answer(&[0xA5, 0x52]),
        device.answer(&[0xA5, 0x50]),
        device.answer(&[0xA5, 0x59]),
        device.answer(&[0xA5, 0xFF, 0x04, 0, 0, 0, 0, 0x5E]),
        device.answer(&[0xA5, 0x82, 0x05, 0, 0, 0, 0, 0, 0x22]),
    ]
    .concat()
}

fn run_split(bytes: &[u8], at: usize) -> String {
    let mut h = Harness::new(RplidarDriver::new(RplidarConfig::default()));
    h.connect();
    let mut out = h.wait(100);
    out.extend(h.feed(&bytes[..at]));
    out.extend(h.feed(&bytes[at..]));
    // NaN ranges make `==` false on equal scans; Debug text compares them.
    format!("{out:?} {}", h.driver.stats())
}

#[test]
fn a_transcript_split_at_every_position_gives_identical_output() {
    let bytes = a2_transcript(express_stream(1, 41));
    let whole = run_split(&bytes, 0);
    assert!(whole.contains("Scan("), "the transcript yields scans");
    for at in 1..=bytes.len() {
        assert_eq!(run_split(&bytes, at), whole, "split at {at}");
    }
}

#[test]
fn standard_and_dense_streams_split_at_every_position_decode_the_same() {
    for (format, bytes) in [
        (SampleFormat::Standard, standard_stream(2, 60, 42)),
        (SampleFormat::Dense, dense_stream(1, 43)),
    ] {
        let whole = format!("{:?}", decode(format, &[&bytes]));
        assert!(whole.contains("rays"));
        for at in 1..bytes.len() {
            let split = format!("{:?}", decode(format, &[&bytes[..at], &bytes[at..]]));
            assert_eq!(split, whole, "{format:?} split at {at}");
        }
    }
}
