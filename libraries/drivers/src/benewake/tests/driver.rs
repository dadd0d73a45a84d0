//! The driver's state machine on scripted byte streams: connect, configure,
//! stream, time out, reconnect.

use std::time::Duration;

use super::support::{
    frame, identity_value, reconnect_reason, reply_to, scans, writes, Bench, EPOCH_NS,
};
use crate::benewake::{encode_frame, BenewakeConfig, BenewakeModel, Command, DistanceUnit};
use crate::device::{DeviceDriver, DeviceState, DriverOutput};

const VERSION: &[u8] = &[0x5A, 0x04, 0x01, 0x5F];
const FORMAT_CM: &[u8] = &[0x5A, 0x05, 0x05, 0x01, 0x65];
const FORMAT_MM: &[u8] = &[0x5A, 0x05, 0x05, 0x06, 0x6A];
const ENABLE: &[u8] = &[0x5A, 0x05, 0x07, 0x01, 0x67];
const RATE_100: &[u8] = &[0x5A, 0x06, 0x03, 0x64, 0x00, 0xC7];
const SAVE: &[u8] = &[0x5A, 0x04, 0x11, 0x6F];
const TRIGGER: &[u8] = &[0x5A, 0x04, 0x04, 0x62];

fn states(out: &[DriverOutput]) -> Vec<DeviceState> {
    out.iter()
        .filter_map(|o| match o {
            DriverOutput::State(s) => Some(s.clone()),
            _ => None,
        })
        .collect()
}

fn streaming_bench(config: BenewakeConfig) -> Bench {
    let mut bench = Bench::new(config);
    bench.handshake();
    assert_eq!(bench.driver.state(), &DeviceState::Streaming);
    bench
}

#[test]
fn scripted_connect_with_the_version_reply_among_frames() {
    let mut bench = Bench::new(BenewakeConfig::default());
    let out = bench.connect();
    assert_eq!(
        out,
        [
            DriverOutput::SetBaud(115_200),
            DriverOutput::FlushInput,
            DriverOutput::State(DeviceState::Connecting),
            DriverOutput::Write(VERSION.to_vec()),
        ]
    );
    assert_eq!(bench.driver.kind(), "tfmini");

    // The tail of a frame, two frames, the version reply, a frame, split
    // across three reads in awkward places.
    let mut stream = frame(16, 288, 0)[3..].to_vec();
    stream.extend(frame(100, 500, 2248));
    stream.extend(frame(101, 500, 2248));
    stream.extend(reply_to(Command::Version));
    stream.extend(frame(102, 500, 2248));
    let first = bench.feed(&stream[..10]);
    assert!(first.is_empty());
    bench.wait_ms(5);
    let second = bench.feed(&stream[10..28]);
    assert!(second.is_empty(), "the reply is not complete yet");
    bench.wait_ms(5);
    let third = bench.feed(&stream[28..]);
    assert_eq!(states(&third), [DeviceState::Configuring]);
    assert_eq!(writes(&third), [FORMAT_CM.to_vec()]);
    assert!(scans(&third).is_empty(), "no readings before configured");

    let mut echo = FORMAT_CM.to_vec();
    echo.extend(frame(103, 500, 2248));
    assert_eq!(writes(&bench.feed(&echo)), [ENABLE.to_vec()]);
    let out = bench.feed(ENABLE);
    assert_eq!(states(&out), [DeviceState::Streaming]);
    assert_eq!(
        identity_value(&out, "model").as_deref(),
        Some("tfmini-plus")
    );
    assert_eq!(
        identity_value(&out, "firmware").as_deref(),
        Some("9.50.112")
    );
    assert_eq!(
        identity_value(&out, "frame_rate_hz").as_deref(),
        Some("device setting")
    );
    assert_eq!(identity_value(&out, "unit").as_deref(), Some("cm"));
    assert_eq!(identity_value(&out, "max_range_m").as_deref(), Some("12"));

    let delivered = scans(&bench.feed(&frame(250, 700, 2248)));
    assert_eq!(delivered.len(), 1);
    let scan = &delivered[0];
    assert_eq!(scan.sequence, 0);
    assert_eq!(scan.rays.len(), 1);
    assert_eq!(scan.rays[0].range, 2.5);
    assert_eq!(scan.rays[0].intensity, Some(700.0));
    assert_eq!(scan.received, bench.now);
    // Back-dated by 90 bits at 115200 baud.
    assert_eq!(scan.stamp_ns, bench.now.unix_ns - 781_250);
    assert_eq!(
        bench.driver.last_reading().and_then(|r| r.temperature_c),
        Some(25.0)
    );

    let stats = bench.driver.stats();
    assert_eq!(stats.commands, 3);
    assert_eq!(stats.handshakes, 1);
    assert_eq!(stats.scans, 1);
    assert_eq!(stats.errors("partial_frame"), 1);
    assert_eq!(stats.notes("frame_while_configuring"), 4);
    assert_eq!(stats.total_errors(), 1);
    assert_eq!(stats.bytes, stream.len() as u64 + 14 + 5 + 9);
}

#[test]
fn frame_rate_and_save_are_sent_when_configured() {
    let config = BenewakeConfig {
        frame_rate: Some(100),
        save: true,
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    let out = bench.handshake();
    assert_eq!(
        writes(&out),
        [VERSION, RATE_100, FORMAT_CM, ENABLE, SAVE].map(<[u8]>::to_vec)
    );
    assert_eq!(
        identity_value(&out, "frame_rate_hz").as_deref(),
        Some("100")
    );
    assert_eq!(bench.driver.stats().commands, 5);
    assert_eq!(bench.driver.stats().errors("save_failed"), 0);
}

#[test]
fn a_failed_save_is_counted() {
    let config = BenewakeConfig {
        save: true,
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    bench.connect();
    bench.feed(&reply_to(Command::Version));
    bench.feed(FORMAT_CM);
    assert_eq!(writes(&bench.feed(ENABLE)), [SAVE.to_vec()]);
    let out = bench.feed(&encode_frame(0x11, &[1]));
    assert_eq!(states(&out), [DeviceState::Streaming]);
    assert_eq!(bench.driver.stats().errors("save_failed"), 1);
}

#[test]
fn millimetres_on_a_tfmini_plus() {
    let config = BenewakeConfig {
        unit: DistanceUnit::Millimetre,
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    let out = bench.handshake();
    assert!(writes(&out).contains(&FORMAT_MM.to_vec()));
    assert_eq!(identity_value(&out, "unit").as_deref(), Some("mm"));
    let scan = &scans(&bench.feed(&frame(1234, 500, 0)))[0];
    assert_eq!(scan.rays[0].range, 1.234);
}

#[test]
fn millimetres_fall_back_to_centimetres_where_unsupported() {
    let config = BenewakeConfig {
        model: BenewakeModel::TfLuna,
        unit: DistanceUnit::Millimetre,
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    let out = bench.handshake();
    assert!(writes(&out).contains(&FORMAT_CM.to_vec()));
    assert_eq!(identity_value(&out, "unit").as_deref(), Some("cm"));
    assert_eq!(
        scans(&bench.feed(&frame(123, 500, 0)))[0].rays[0].range,
        1.23
    );
}

#[test]
fn a_silent_port_fails_the_version_request() {
    let mut bench = Bench::new(BenewakeConfig::default());
    bench.connect();
    assert!(bench.wait_ms(499).is_empty());
    let out = bench.wait_ms(1);
    assert_eq!(states(&out), [DeviceState::Disconnected]);
    assert!(reconnect_reason(&out).unwrap().contains("version"));
    let stats = bench.driver.stats();
    assert_eq!((stats.reconnects, stats.handshakes), (1, 0));
    assert_eq!(stats.errors("timeout"), 1);
    // Nothing more until the node reconnects.
    assert!(bench.wait_ms(10_000).is_empty());
}

#[test]
fn a_device_that_streams_but_never_answers_is_alive() {
    let config = BenewakeConfig {
        frame_rate: Some(50),
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    bench.connect();
    let mut all = Vec::new();
    for _ in 0..200 {
        all.extend(bench.wait_ms(10));
        all.extend(bench.feed(&frame(300, 900, 2248)));
    }
    assert_eq!(
        writes(&all),
        [
            Command::FrameRate(50).encode(),
            FORMAT_CM.to_vec(),
            ENABLE.to_vec()
        ]
    );
    assert_eq!(bench.driver.state(), &DeviceState::Streaming);
    assert_eq!(identity_value(&all, "firmware").as_deref(), Some("unknown"));
    assert_eq!(
        identity_value(&all, "frame_rate_hz").as_deref(),
        Some("50 (unconfirmed)")
    );
    let stats = bench.driver.stats();
    assert_eq!(stats.errors("command_unanswered"), 4);
    assert!(stats.scans > 0);
    assert_eq!(reconnect_reason(&all), None);
}

#[test]
fn stale_replies_are_unexpected() {
    let mut bench = streaming_bench(BenewakeConfig::default());
    bench.feed(ENABLE);
    assert_eq!(bench.driver.stats().errors("unexpected_reply"), 1);
    // A reply that does not answer the pending step is not taken for it.
    let mut bench = Bench::new(BenewakeConfig::default());
    bench.connect();
    assert!(writes(&bench.feed(FORMAT_CM)).is_empty());
    assert_eq!(bench.driver.stats().errors("unexpected_reply"), 1);
    assert_eq!(bench.driver.state(), &DeviceState::Connecting);
}

#[test]
fn invalid_readings_are_nan_rays_and_counted() {
    let mut bench = streaming_bench(BenewakeConfig::default());
    let mut bytes = Vec::new();
    bytes.extend(frame(0, 50, 0)); // weak
    bytes.extend(frame(0, 65535, 0)); // saturated
    bytes.extend(frame(1500, 500, 0)); // beyond 12 m
    bytes.extend(frame(0, 500, 0)); // zero
    bytes.extend(frame(300, 500, 0)); // valid
    let delivered = scans(&bench.feed(&bytes));
    assert_eq!(delivered.len(), 5);
    let valid: Vec<bool> = delivered.iter().map(|s| s.valid_rays() == 1).collect();
    assert_eq!(valid, [false, false, false, false, true]);
    assert!(delivered[..4].iter().all(|s| s.rays[0].range.is_nan()));
    let sequences: Vec<u32> = delivered.iter().map(|s| s.sequence).collect();
    assert_eq!(sequences, [0, 1, 2, 3, 4]);
    let stats = bench.driver.stats();
    assert_eq!(stats.invalid_readings("weak_return"), 1);
    assert_eq!(stats.invalid_readings("saturated"), 1);
    assert_eq!(stats.invalid_readings("out_of_range"), 2);
    assert_eq!(stats.scans, 5);
}

#[test]
fn a_frame_with_a_bad_sum_is_never_a_reading() {
    let mut bench = streaming_bench(BenewakeConfig::default());
    let mut bad = frame(300, 500, 0);
    bad[8] = bad[8].wrapping_add(1);
    assert!(scans(&bench.feed(&bad)).is_empty());
    assert_eq!(bench.driver.stats().errors("bad_checksum"), 1);
}

#[test]
fn a_silent_stream_reconnects_after_the_timeout() {
    let mut bench = streaming_bench(BenewakeConfig::default());
    for _ in 0..10 {
        bench.wait_ms(100);
        assert_eq!(scans(&bench.feed(&frame(300, 500, 0))).len(), 1);
    }
    assert!(bench.wait_ms(300).is_empty());
    let out = bench.wait_ms(1);
    assert_eq!(
        reconnect_reason(&out).as_deref(),
        Some("no data frame for 300 ms")
    );
    assert_eq!(states(&out), [DeviceState::Disconnected]);
    assert_eq!(bench.driver.stats().reconnects, 1);
    // Bytes before the next connect are ignored.
    assert!(bench.feed(&frame(300, 500, 0)).is_empty());
}

#[test]
fn a_slow_frame_rate_stretches_the_stream_timeout() {
    let config = BenewakeConfig {
        frame_rate: Some(10),
        ..BenewakeConfig::default()
    };
    let mut bench = streaming_bench(config);
    assert!(bench.wait_ms(1000).is_empty());
    assert!(reconnect_reason(&bench.wait_ms(1)).is_some());
}

#[test]
fn reconnect_runs_the_handshake_again_and_keeps_counting() {
    let mut bench = streaming_bench(BenewakeConfig::default());
    bench.feed(&frame(300, 500, 0));
    bench.wait_ms(400);
    assert_eq!(bench.driver.state(), &DeviceState::Disconnected);
    let out = bench.handshake();
    assert_eq!(writes(&out)[0], VERSION);
    let scan = &scans(&bench.feed(&frame(300, 500, 0)))[0];
    assert_eq!(scan.sequence, 1);
    let stats = bench.driver.stats();
    assert_eq!((stats.handshakes, stats.reconnects, stats.scans), (2, 1, 2));
}

#[test]
fn original_tfmini_only_listens() {
    let config = BenewakeConfig {
        model: BenewakeModel::Tfmini,
        frame_rate: Some(100),
        save: true,
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    let out = bench.connect();
    assert!(writes(&out).is_empty());
    assert_eq!(states(&out), [DeviceState::Connecting]);
    bench.wait_ms(100);
    let out = bench.feed(&frame(300, 0, 0x0007));
    assert_eq!(states(&out), [DeviceState::Streaming]);
    assert_eq!(identity_value(&out, "model").as_deref(), Some("tfmini"));
    assert_eq!(
        identity_value(&out, "frame_rate_hz").as_deref(),
        Some("device setting")
    );
    assert_eq!(scans(&out).len(), 1);
    assert_eq!(bench.driver.last_reading().unwrap().temperature_c, None);
    assert_eq!(bench.driver.stats().commands, 0);
}

#[test]
fn original_tfmini_that_never_speaks_reconnects() {
    let config = BenewakeConfig {
        model: BenewakeModel::Tfmini,
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    bench.connect();
    assert!(bench.wait_ms(300).is_empty());
    assert!(reconnect_reason(&bench.wait_ms(1)).is_some());
    assert_eq!(bench.driver.stats().commands, 0);
}

#[test]
fn trigger_mode_triggers_each_reading() {
    let config = BenewakeConfig {
        frame_rate: Some(0),
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    let out = bench.handshake();
    assert_eq!(
        identity_value(&out, "frame_rate_hz").as_deref(),
        Some("0 (trigger mode)")
    );
    assert_eq!(writes(&out).last().map(Vec::as_slice), Some(TRIGGER));
    // The frame answers the trigger; the poll after it sends the next.
    let out = bench.feed(&frame(300, 500, 0));
    assert_eq!(scans(&out).len(), 1);
    assert_eq!(writes(&out), [TRIGGER.to_vec()]);
    // Unanswered for reply_timeout: sent again.
    assert!(writes(&bench.wait_ms(250)).is_empty());
    assert_eq!(writes(&bench.wait_ms(250)), [TRIGGER.to_vec()]);
    assert_eq!(bench.driver.stats().errors("trigger_unanswered"), 1);
}

#[test]
fn shutdown_sends_nothing() {
    let mut bench = streaming_bench(BenewakeConfig::default());
    let commands = bench.driver.stats().commands;
    let mut out = Vec::new();
    bench.driver.shutdown(&mut out);
    assert_eq!(out, [DriverOutput::State(DeviceState::Disconnected)]);
    assert_eq!(bench.driver.stats().commands, commands);
}

#[test]
fn every_write_is_counted() {
    let config = BenewakeConfig {
        frame_rate: Some(0),
        save: true,
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    let mut all = bench.handshake();
    for _ in 0..5 {
        all.extend(bench.feed(&frame(300, 500, 0)));
        all.extend(bench.wait_ms(600));
    }
    assert_eq!(bench.driver.stats().commands, writes(&all).len() as u64);
}

#[test]
fn reply_timeout_and_stream_timeout_are_configurable() {
    let config = BenewakeConfig {
        reply_timeout: Duration::from_millis(50),
        stream_timeout: Duration::from_secs(2),
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    bench.connect();
    assert!(reconnect_reason(&bench.wait_ms(50)).is_some());
    let mut bench = streaming_bench(bench.driver.config().clone());
    assert!(bench.wait_ms(2000).is_empty());
    assert!(reconnect_reason(&bench.wait_ms(1)).is_some());
}

#[test]
fn stamps_use_the_configured_baud() {
    let config = BenewakeConfig {
        baud: 921_600,
        ..BenewakeConfig::default()
    };
    let mut bench = Bench::new(config);
    let out = bench.handshake();
    assert_eq!(out[0], DriverOutput::SetBaud(921_600));
    let scan = &scans(&bench.feed(&frame(300, 500, 0)))[0];
    assert_eq!(scan.stamp_ns, EPOCH_NS + bench.now.monotonic_ns - 97_656);
}

#[test]
fn a_read_window_bounds_each_readings_time_and_stamps_the_middle() {
    use crate::device::{ReadWindow, StampBound};
    let mut bench = streaming_bench(BenewakeConfig {
        link_latency: Duration::from_millis(2),
        ..BenewakeConfig::default()
    });
    const MS: u64 = 1_000_000;
    let wire = 781_250;
    let after = bench.now.plus_ns(10 * MS);
    let returned = after.plus_ns(30 * MS);
    // Three frames and a corrupted one in a read 30 ms after the previous
    // read's call, at the factory 100 Hz.
    let mut bytes = Vec::new();
    bytes.extend(frame(300, 500, 0));
    let mut bad = frame(300, 500, 0);
    bad[8] = bad[8].wrapping_add(1);
    bytes.extend(bad);
    bytes.extend(frame(310, 500, 0));
    bytes.extend(frame(320, 500, 0));
    let mut out = Vec::new();
    let window = ReadWindow {
        after: Some(after),
        returned,
    };
    bench.driver.receive_read(&bytes, window, &mut out);
    let delivered = scans(&out);
    assert_eq!(delivered.len(), 3);
    let bounds: Vec<(u64, u64)> = delivered
        .iter()
        .map(|s| match s.stamp_bound {
            StampBound::Within {
                earliest_ns,
                latest_ns,
            } => {
                assert_eq!(s.stamp_ns, earliest_ns + (latest_ns - earliest_ns) / 2);
                (earliest_ns, latest_ns)
            }
            other => panic!("{other:?}"),
        })
        .collect();
    let earliest = after.unix_ns - wire - 2 * MS;
    let latest = returned.unix_ns - wire;
    assert_eq!(bounds[2], (earliest, latest));
    // One frame after it: at least 9.8 ms older, at most 10.2 ms.
    assert_eq!(bounds[1], (earliest - 10_200_000, latest - 9_800_000));
    // Two frames and a corrupted one (a frame slot) after the first.
    assert_eq!(bounds[0], (earliest - 30_600_000, latest - 19_600_000));
    // The first read after opening has no earlier read: no bound.
    let mut out = Vec::new();
    bench.driver.receive_read(
        &frame(300, 500, 0),
        ReadWindow::returned_at(returned.plus_ns(MS)),
        &mut out,
    );
    assert_eq!(scans(&out)[0].stamp_bound, StampBound::Unbounded);
    // Without read times the stamp is the old back-dating, untracked.
    let plain = scans(&bench.feed(&frame(300, 500, 0)));
    assert_eq!(plain[0].stamp_bound, StampBound::Untracked);
}
