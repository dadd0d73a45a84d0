//! State-machine tests of the measurement loop: scans, stamps, faults,
//! recovery, intensity fallback, polling, timeouts.

use super::support::*;
use crate::device::{DeviceDriver, DeviceState, DriverOutput};
use crate::scip::*;

const STEP_NS: f64 = 100e6 / 1024.0;

#[test]
fn scan_rays_follow_the_urg04lx_geometry() {
    let mut rig = Rig::streaming();
    let out = rig.feed(&rig.md_scan(120));
    let [scan] = scans(&out).try_into().unwrap();
    assert_eq!(scan.sequence, 0);
    assert_eq!(scan.received, rig.now);
    assert_eq!(scan.rays.len(), 682);
    let first = scan.rays[0];
    assert!(first.range.is_nan(), "5 mm is an error code below DMIN");
    assert!(scan.rays[1].range.is_nan(), "6000 mm is above DMAX");
    assert_eq!(scan.rays[21].range, 5.432);
    assert_eq!(scan.rays[2].range, 1.002);
    assert_eq!(scan.valid_rays(), 680);
    assert!(!scan.has_intensity());
    let angle = |step: f64| ((step - 384.0) * std::f64::consts::TAU / 1024.0) as f32;
    assert_eq!(first.angle, angle(44.0));
    assert_eq!(scan.rays[340].angle, angle(384.0));
    assert_eq!(scan.rays[340].angle, 0.0, "AFRT is straight ahead");
    assert!(scan.rays[681].angle > 2.09, "counter-clockwise is positive");
    assert_eq!(first.offset_ns, 0);
    assert_eq!(scan.rays[681].offset_ns, (681.0 * STEP_NS).round() as u32);
}

#[test]
fn scan_stamp_is_the_first_ray_on_the_host_clock() {
    let mut rig = Rig::streaming();
    let stamp_ms = rig.device_ms() - 120;
    let out = rig.feed(&rig.md_scan(120));
    let [scan] = scans(&out).try_into().unwrap();
    // The timestamp marks the rear centre; step 44 is 172 steps later.
    let delay = (172.0 * STEP_NS).round() as u64;
    assert_eq!(scan.stamp_ns, rig.unix_at(u64::from(stamp_ms)) + delay);
    assert_eq!(rig.driver.stats().errors("clock_mismatch"), 0);
}

#[test]
fn stamps_survive_the_sensor_clock_wrap() {
    let mut rig = Rig::new(ScipConfig::default());
    rig.dev0 = (1 << 24) - 200; // wraps 200 ms after MONO0
    rig.bring_up();
    rig.feed(&reply(MD_FULL, "00", &[]));
    let mut stamps = Vec::new();
    for _ in 0..5 {
        rig.advance_ms(100);
        let out = rig.feed(&rig.md_scan(120));
        let [scan] = scans(&out).try_into().unwrap();
        let unwrapped = rig.dev0 + (rig.now.monotonic_ns - MONO0) / 1_000_000 - 120;
        let delay = (172.0 * STEP_NS).round() as u64;
        assert_eq!(scan.stamp_ns, rig.unix_at(unwrapped) + delay);
        stamps.push(scan.stamp_ns);
    }
    assert!(rig.device_ms() < 1000, "the sensor clock wrapped");
    for pair in stamps.windows(2) {
        assert_eq!(pair[1] - pair[0], 100_000_000);
    }
    assert_eq!(rig.driver.stats().errors("clock_mismatch"), 0);
}

#[test]
fn nonsense_sensor_time_falls_back_to_arrival_stamps() {
    let mut rig = Rig::streaming();
    // A timestamp 5 s in the future of the mapped clock.
    let future = (rig.device_ms() + 5_000) & 0xFF_FFFF;
    let out = rig.feed(&streamed_scan(MD_FULL, future, &urg04lx_values(), 3));
    let [scan] = scans(&out).try_into().unwrap();
    let sweep = (681.0 * STEP_NS).round() as u64;
    assert_eq!(scan.stamp_ns, rig.now.unix_ns - sweep);
    assert_eq!(rig.driver.stats().errors("clock_mismatch"), 1);
    // Until the next sync, even a sane timestamp is not trusted.
    rig.advance_ms(100);
    let out = rig.feed(&rig.md_scan(120));
    assert_eq!(scans(&out)[0].stamp_ns, rig.now.unix_ns - sweep);
    assert_eq!(rig.driver.stats().errors("clock_mismatch"), 1);
}

#[test]
fn without_tm_sync_stamps_come_from_arrival() {
    let config = ScipConfig {
        tm_round_trips: 0,
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    let out = rig.bring_up();
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("MD0044072501000\n")
    );
    let pairs = identity(&rig.feed(&reply(MD_FULL, "00", &[]))).unwrap();
    assert!(identity_value(&pairs, "clock_sync")
        .unwrap()
        .starts_with("none"));
    let out = rig.feed(&rig.md_scan(120));
    let sweep = (681.0 * STEP_NS).round() as u64;
    assert_eq!(scans(&out)[0].stamp_ns, rig.now.unix_ns - sweep);
}

#[test]
fn sensor_without_tm_streams_unsynced() {
    let mut rig = Rig::new(ScipConfig::default());
    rig.connect();
    rig.feed(&reply("QT", "00", &[]));
    rig.feed(&vv_reply());
    rig.feed(URG04LX_PP.as_bytes());
    rig.feed(&ii_reply("Sensor works well."));
    let out = rig.feed(&reply("TM0", "0E", &[]));
    assert_eq!(writes(&out), ["MD0044072501000\n"]);
    assert_eq!(rig.driver.stats().errors("device_error_unsupported"), 1);
}

#[test]
fn scans_with_a_bad_line_are_dropped_whole() {
    let mut rig = Rig::streaming();
    let mut bytes = rig.md_scan(120);
    // Flip a data character in the fifth line (checksum now wrong).
    let at = bytes.len() - 200;
    bytes[at] = if bytes[at] == b'0' { b'1' } else { b'0' };
    assert!(scans(&rig.feed(&bytes)).is_empty());
    assert_eq!(rig.driver.stats().errors("bad_checksum"), 1);
    // A scan cut short (one data line lost).
    let text = String::from_utf8(rig.md_scan(120)).unwrap();
    let mut lines: Vec<&str> = text.split('\n').collect();
    lines.remove(10);
    assert!(scans(&rig.feed(lines.join("\n").as_bytes())).is_empty());
    assert_eq!(rig.driver.stats().errors("incomplete_scan"), 1);
    // The stream goes on.
    assert_eq!(scans(&rig.feed(&rig.md_scan(120))).len(), 1);
    assert_eq!(rig.driver.stats().scans, 1);
}

#[test]
fn oversize_line_drops_the_scan() {
    let mut rig = Rig::streaming();
    let text = String::from_utf8(rig.md_scan(120)).unwrap();
    let long = "0".repeat(MAX_LINE_LEN + 1);
    let bad = text.replacen("99b\n", &format!("99b\n{long}\n"), 1);
    assert!(scans(&rig.feed(bad.as_bytes())).is_empty());
    assert_eq!(rig.driver.stats().errors("oversize_line"), 1);
    assert_eq!(rig.driver.stats().errors("incomplete_scan"), 1);
}

#[test]
fn status_98_is_counted_and_streaming_continues() {
    let mut rig = Rig::streaming();
    assert!(rig.feed(&reply(MD_FULL, "98", &[])).is_empty());
    assert_eq!(rig.driver.stats().errors("device_resumed"), 1);
    assert_eq!(scans(&rig.feed(&rig.md_scan(120))).len(), 1);
    assert_eq!(rig.driver.state(), &DeviceState::Streaming);
}

#[test]
fn abnormal_state_reboots_with_rb_twice_then_reconnects() {
    let mut rig = Rig::streaming();
    let out = rig.feed(&reply(MD_FULL, "0L", &[]));
    assert!(matches!(&out[0], DriverOutput::State(DeviceState::Recovering(r)) if r.contains("0L")));
    assert!(out
        .iter()
        .any(|o| matches!(o, DriverOutput::Health { ok: false, .. })));
    assert_eq!(writes(&out), ["RB\n"]);
    assert_eq!(rig.driver.stats().errors("device_error_abnormal"), 1);
    // Scans still in flight are ignored.
    assert!(scans(&rig.feed(&rig.md_scan(120))).is_empty());
    assert_eq!(writes(&rig.feed(b"RB\n01Q\n\n")), ["RB\n"]);
    let out = rig.feed(b"RB\n00P\n\n");
    let reason = reconnect_reason(&out).unwrap();
    assert!(
        reason.starts_with("rebooted the sensor (RB twice)"),
        "{reason}"
    );
    assert_eq!(rig.driver.state(), &DeviceState::Disconnected);
}

#[test]
fn silent_reboot_still_sends_rb_twice_then_reconnects() {
    let mut rig = Rig::streaming();
    rig.feed(&reply(MD_FULL, "0L", &[]));
    assert_eq!(writes(&rig.advance_ms(1_000)), ["RB\n"]);
    assert!(reconnect_reason(&rig.advance_ms(1_000)).is_some());
}

#[test]
fn repeated_hardware_trouble_reboots() {
    let mut rig = Rig::streaming();
    assert!(rig.feed(&reply(MD_FULL, "52", &[])).is_empty());
    // A good scan in between resets the run.
    assert_eq!(scans(&rig.feed(&rig.md_scan(120))).len(), 1);
    assert!(rig.feed(&reply(MD_FULL, "52", &[])).is_empty());
    assert!(rig.feed(&reply(MD_FULL, "53", &[])).is_empty());
    let out = rig.feed(&reply(MD_FULL, "54", &[]));
    assert_eq!(writes(&out), ["RB\n"]);
    assert_eq!(rig.driver.stats().errors("device_error_hardware"), 4);
    assert!(matches!(rig.driver.state(), DeviceState::Recovering(_)));
}

#[test]
fn stalled_stream_reconnects() {
    let mut rig = Rig::streaming();
    rig.feed(&rig.md_scan(120));
    // Default: max(3 x 100 ms, 500 ms).
    assert!(rig.advance_ms(499).is_empty());
    let out = rig.advance_ms(1);
    assert_eq!(
        reconnect_reason(&out).as_deref(),
        Some("no scan from the sensor for 500 ms")
    );
    assert_eq!(rig.driver.stats().errors("timeout"), 1);
}

#[test]
fn unexpected_echo_in_the_stream_is_counted() {
    let mut rig = Rig::streaming();
    assert!(rig.feed(&reply("GD0044072501", "00", &[])).is_empty());
    assert_eq!(rig.driver.stats().errors("unexpected_echo"), 1);
}

#[test]
fn intensity_falls_back_to_md_and_is_asked_again_next_connect() {
    let config = ScipConfig {
        intensity: true,
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    let out = rig.bring_up();
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("ME0044072501000\n")
    );
    // The URG-04LX does not know ME.
    let out = rig.feed(&reply("ME0044072501000", "0E", &[]));
    assert_eq!(writes(&out), ["MD0044072501000\n"]);
    assert_eq!(rig.driver.stats().errors("intensity_unsupported"), 1);
    let pairs = identity(&rig.feed(&reply(MD_FULL, "00", &[]))).unwrap();
    let note = identity_value(&pairs, "intensity").unwrap();
    assert!(
        note.starts_with("unsupported (ME rejected with status 0E"),
        "{note}"
    );
    assert_eq!(scans(&rig.feed(&rig.md_scan(120))).len(), 1);
    // Next connect: ME again.
    let out = rig.bring_up();
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("ME0044072501000\n")
    );
}

#[test]
fn me_scans_carry_intensity() {
    let config = ScipConfig {
        scan: ScanCommand::Me,
        start_step: Some(380),
        end_step: Some(389),
        cluster: 2,
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    rig.bring_up();
    let pairs = identity(&rig.feed(&reply("ME0380038902000", "00", &[]))).unwrap();
    assert_eq!(identity_value(&pairs, "intensity").as_deref(), Some("yes"));
    let values = [1000, 11, 1100, 12, 1200, 13, 1300, 14, 1400, 15];
    let stamp = rig.device_ms() - 100;
    let out = rig.feed(&streamed_scan("ME0380038902000", stamp, &values, 3));
    let [scan] = scans(&out).try_into().unwrap();
    assert_eq!(scan.rays.len(), 5);
    assert!(scan.has_intensity());
    assert_eq!(scan.rays[4].intensity, Some(15.0));
    assert_eq!(scan.rays[4].range, 1.4);
    // Cluster 2: ray i is step 380 + 2i.
    let angle = |step: f64| ((step - 384.0) * std::f64::consts::TAU / 1024.0) as f32;
    assert_eq!(scan.rays[2].angle, angle(384.0));
    assert_eq!(scan.rays[1].offset_ns, (2.0 * STEP_NS).round() as u32);
}

#[test]
fn steps_are_clamped_to_the_sensor_range() {
    let config = ScipConfig {
        start_step: Some(0),
        end_step: Some(5000),
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    let out = rig.bring_up();
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("MD0044072501000\n")
    );
}

#[test]
fn gd_is_polled_after_bm() {
    let config = ScipConfig {
        scan: ScanCommand::Gd,
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    let out = rig.bring_up();
    assert_eq!(writes(&out).last().map(String::as_str), Some("BM\n"));
    assert_eq!(writes(&rig.feed(b"BM\n00P\n\n")), ["GD0044072501\n"]);
    let stamp = rig.device_ms() - 120;
    let gd = reply(
        "GD0044072501",
        "00",
        &scan_lines(stamp, &urg04lx_values(), 3),
    );
    let out = rig.feed(&gd);
    assert_eq!(out[0], DriverOutput::State(DeviceState::Streaming));
    assert_eq!(scans(&out).len(), 1);
    assert_eq!(writes(&out), ["GD0044072501\n"], "the next GD follows");
    // Laser off (status 10): BM, then GD again.
    assert_eq!(
        writes(&rig.feed(&reply("GD0044072501", "10", &[]))),
        ["BM\n"]
    );
    assert_eq!(rig.driver.stats().errors("device_error_laser_off"), 1);
    assert_eq!(writes(&rig.feed(b"BM\n02R\n\n")), ["GD0044072501\n"]);
    // A bad GD reply is dropped and the next GD sent.
    let mut bad = gd.clone();
    let at = bad.len() - 30;
    bad[at] ^= 0x01;
    let out = rig.feed(&bad);
    assert!(scans(&out).is_empty());
    assert_eq!(writes(&out), ["GD0044072501\n"]);
    // Silence past the stream timeout.
    let out = rig.advance_ms(500);
    assert!(reconnect_reason(&out)
        .unwrap()
        .starts_with("no reply to GD0044072501"));
}

#[test]
fn commands_counted_match_writes() {
    let mut rig = Rig::new(ScipConfig {
        intensity: true,
        ..ScipConfig::default()
    });
    let mut out = rig.bring_up();
    out.extend(rig.feed(&reply("ME0044072501000", "0E", &[])));
    out.extend(rig.feed(&reply(MD_FULL, "00", &[])));
    out.extend(rig.feed(&reply(MD_FULL, "0L", &[])));
    out.extend(rig.advance_ms(1_000));
    rig.driver.shutdown(&mut out);
    assert_eq!(writes(&out).len() as u64, rig.driver.stats().commands);
}
