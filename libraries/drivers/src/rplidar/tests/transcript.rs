//! Scripted connects: the driver's outputs request by request against
//! answers a device would give, and its recovery paths.

use super::sim::*;
use crate::device::{DeviceDriver, DeviceState, DriverOutput};
use crate::rplidar::protocol::answer;
use crate::rplidar::{MotorControl, RplidarConfig, RplidarDriver, ScanMode};

fn driver() -> Harness {
    Harness::new(RplidarDriver::new(RplidarConfig::default()))
}

fn conf_request(key: u8, mode: Option<u8>) -> Vec<u8> {
    let mut r = vec![0xA5, 0x84, if mode.is_some() { 6 } else { 4 }, key, 0, 0, 0];
    if let Some(m) = mode {
        r.extend([m, 0]);
    }
    let sum = r.iter().fold(0, |a, b| a ^ b);
    r.push(sum);
    r
}

fn identity(out: &[DriverOutput]) -> Vec<(String, String)> {
    out.iter()
        .find_map(|o| match o {
            DriverOutput::Identity(pairs) => Some(pairs.clone()),
            _ => None,
        })
        .expect("an Identity output")
}

fn value<'a>(pairs: &'a [(String, String)], key: &str) -> &'a str {
    &pairs.iter().find(|(k, _)| k == key).unwrap().1
}

/// A1M8, firmware 1.29: answers GET_LIDAR_CONF (3 modes, typical Boost = an
/// ultra-capsule mode this driver does not decode), no accessory board.
#[test]
fn a1_connect_transcript_falls_back_to_listed_express_and_dtr() {
    let mut h = driver();
    assert_eq!(
        h.connect(),
        [
            DriverOutput::State(DeviceState::Connecting),
            DriverOutput::Write(vec![0xA5, 0x25]),
        ]
    );
    assert_eq!(h.wait(50), [], "still settling after STOP");
    assert_eq!(
        h.feed(&[0x3D, 0x41, 0x2D]),
        [],
        "leftover stream bytes are ignored"
    );
    assert_eq!(
        h.wait(50),
        [
            DriverOutput::FlushInput,
            DriverOutput::State(DeviceState::Configuring),
            DriverOutput::Write(vec![0xA5, 0x52]),
        ]
    );
    let health = [0xA5, 0x5A, 0x03, 0x00, 0x00, 0x00, 0x06, 0x00, 0x00, 0x00];
    assert_eq!(
        h.feed(&health),
        [
            DriverOutput::Health {
                ok: true,
                detail: "ok, error code 0x0000".into()
            },
            DriverOutput::Write(vec![0xA5, 0x50]),
        ]
    );
    let info = reply(answer::DEVINFO, &info_payload(0x18, 1, 29, 7));
    assert_eq!(info[..7], [0xA5, 0x5A, 0x14, 0x00, 0x00, 0x00, 0x04]);
    assert_eq!(h.feed(&info), [DriverOutput::Write(vec![0xA5, 0x59])]);
    let rate = reply(answer::SAMPLE_RATE, &[0xFC, 0x01, 0xFE, 0x00]); // 508 / 254 µs
    assert_eq!(
        h.feed(&rate),
        [DriverOutput::Write(conf_request(0x70, None))]
    );
    let count = conf_reply(0x70, &3u16.to_le_bytes());
    assert_eq!(
        h.feed(&count),
        [DriverOutput::Write(conf_request(0x7F, Some(0)))]
    );
    let modes: [(&str, u8, u32); 3] = [
        ("Standard", 0x81, 508 << 8),
        ("Express", 0x82, 254 << 8),
        ("Boost", 0x84, 127 << 8),
    ];
    for (id, (name, ty, us)) in modes.iter().enumerate() {
        let m = Some(id as u8);
        let answers = [
            (
                conf_reply(0x7F, format!("{name}\0").as_bytes()),
                conf_request(0x75, m),
            ),
            (conf_reply(0x75, &[*ty]), conf_request(0x71, m)),
            (conf_reply(0x71, &us.to_le_bytes()), conf_request(0x74, m)),
        ];
        for (answer_bytes, next) in answers {
            assert_eq!(h.feed(&answer_bytes), [DriverOutput::Write(next)]);
        }
        let next = if id < 2 {
            conf_request(0x7F, Some(id as u8 + 1))
        } else {
            conf_request(0x7C, None)
        };
        let distance = conf_reply(0x74, &(12u32 << 8).to_le_bytes());
        assert_eq!(h.feed(&distance), [DriverOutput::Write(next)]);
    }
    let board_query = vec![0xA5, 0xFF, 0x04, 0, 0, 0, 0, 0x5E];
    assert_eq!(
        h.feed(&conf_reply(0x7C, &2u16.to_le_bytes())),
        [DriverOutput::Write(board_query)]
    );
    // The A1 does not answer GET_ACC_BOARD_FLAG: after the reply timeout the
    // driver goes on with DTR motor control.
    assert_eq!(h.wait(999), []);
    let out = h.wait(1);
    let pairs = identity(&out);
    assert_eq!(value(&pairs, "model"), "A1M8");
    assert_eq!(value(&pairs, "firmware"), "1.29");
    assert_eq!(value(&pairs, "serial"), "000102030405060708090A0B0C0D0E0F");
    assert_eq!(value(&pairs, "typical_scan_mode"), "Boost");
    assert_eq!(value(&pairs, "motor_control"), "dtr");
    assert!(value(&pairs, "scan_mode").starts_with("Express (express samples, EXPRESS_SCAN mode 1"));
    // A5 ^ 82 ^ 05 ^ 01 = 0x23.
    assert_eq!(
        out[1..],
        [
            DriverOutput::SetDtr(false),
            DriverOutput::Write(vec![0xA5, 0x82, 0x05, 0x01, 0, 0, 0, 0, 0x23]),
        ]
    );
    let express_descriptor = [0xA5, 0x5A, 0x54, 0x00, 0x00, 0x40, 0x82];
    assert_eq!(
        h.feed(&express_descriptor),
        [DriverOutput::State(DeviceState::Streaming)]
    );
    let got = scans(&h.feed(&express_stream(3, 11)));
    assert!(got.len() >= 3);
    assert_eq!(got[0].sequence, 0);
    assert_eq!(got[1].sequence, 1);
    assert!(got
        .iter()
        .all(|s| s.rays.len() == 24 * 32 && !s.has_intensity()));

    let mut out = Vec::new();
    h.driver.shutdown(&mut out);
    assert_eq!(
        out,
        [
            DriverOutput::Write(vec![0xA5, 0x25]),
            DriverOutput::SetDtr(true),
            DriverOutput::State(DeviceState::Disconnected),
        ]
    );
    let stats = h.driver.stats();
    assert_eq!(stats.handshakes, 1);
    assert_eq!(stats.notes("optional_timeout"), 1);
    assert_eq!(stats.errors("timeout"), 0);
    // STOP, HEALTH, INFO, SAMPLERATE, 2 + 3·4 conf, board flag, scan, STOP.
    assert_eq!(stats.commands, 1 + 3 + 14 + 1 + 1 + 1);
}

fn a2() -> FakeLidar {
    FakeLidar {
        info: info_payload(0x28, 1, 20, 5),
        health: [0, 0, 0],
        sample_rate: Some([0xFC, 0x01, 0xFE, 0x00]),
        modes: Vec::new(),
        typical: 0,
        board_flag: Some(1),
        stream: express_stream(3, 12),
    }
}

/// A2M8, firmware 1.20 (before GET_LIDAR_CONF), accessory board with PWM.
#[test]
fn a2_with_board_flag_runs_the_motor_by_pwm_and_legacy_express() {
    let mut h = driver();
    let out = a2().run(&mut h, 20);
    let w = writes(&out);
    assert_eq!(
        w,
        [
            vec![0xA5, 0x25],
            vec![0xA5, 0x52],
            vec![0xA5, 0x50],
            vec![0xA5, 0x59],
            vec![0xA5, 0xFF, 0x04, 0, 0, 0, 0, 0x5E],
            vec![0xA5, 0xF0, 0x02, 0x94, 0x02, 0xC1],
            vec![0xA5, 0x82, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x22],
        ]
    );
    assert_eq!(value(&identity(&out), "motor_control"), "pwm 660");
    assert!(scans(&out).len() >= 3);
    assert_eq!(h.driver.stats().total_errors(), 0, "{}", h.driver.stats());
    assert_eq!(h.driver.stats().notes("partial_revolution"), 1);
    let mut out = Vec::new();
    h.driver.shutdown(&mut out);
    assert_eq!(
        writes(&out),
        [vec![0xA5, 0x25], vec![0xA5, 0xF0, 0x02, 0x00, 0x00, 0x57]]
    );
}

/// S1: GET_LIDAR_CONF by model, typical mode DenseBoost (0x85), built-in
/// motor control (RPM, no board query).
#[test]
fn s1_auto_picks_the_typical_dense_mode_and_rpm() {
    let s1 = FakeLidar {
        info: info_payload(0x61, 1, 2, 18),
        health: [0, 0, 0],
        sample_rate: Some([0x6C, 0x00, 0x6C, 0x00]),
        modes: vec![("Standard", 0x81, 250 << 8), ("DenseBoost", 0x85, 108 << 8)],
        typical: 1,
        board_flag: None,
        stream: dense_stream(3, 13),
    };
    let mut h = Harness::new(RplidarDriver::new(RplidarConfig {
        baud: 256_000,
        ..RplidarConfig::default()
    }));
    let out = s1.run(&mut h, 40);
    let w = writes(&out);
    assert!(!w.iter().any(|r| r.get(1) == Some(&0xFF)), "no board query");
    // RPM 600 = 0x0258: A5 ^ A8 ^ 02 ^ 58 ^ 02 = 0x55.
    assert!(w.contains(&vec![0xA5, 0xA8, 0x02, 0x58, 0x02, 0x55]));
    assert_eq!(
        w.last().unwrap(),
        &[0xA5, 0x82, 0x05, 0x01, 0, 0, 0, 0, 0x23]
    );
    let pairs = identity(&out);
    assert_eq!(value(&pairs, "model"), "S1M1");
    assert!(value(&pairs, "scan_mode").starts_with("DenseBoost (dense samples"));
    assert_eq!(
        value(&pairs, "scan_mode_1"),
        "DenseBoost, answer 0x85, 108.0 us/sample, 12.0 m"
    );
    let got = scans(&out);
    assert!(got.len() >= 2 && got.iter().all(|s| s.rays.len() == 18 * 40));
}

#[test]
fn configured_modes_and_motor_override_auto() {
    let mut device = a2();
    device.stream = standard_stream(3, 200, 14);
    let mut h = Harness::new(RplidarDriver::new(RplidarConfig {
        scan_mode: ScanMode::Standard,
        motor: MotorControl::Pwm(500),
        ..RplidarConfig::default()
    }));
    let out = device.run(&mut h, 20);
    let w = writes(&out);
    assert!(
        !w.iter().any(|r| r.get(1) == Some(&0xFF)),
        "no board query with PWM configured"
    );
    assert_eq!(w[w.len() - 2], request_motor(0xF0, 500));
    assert_eq!(w.last().unwrap(), &[0xA5, 0x20]);
    let got = scans(&out);
    assert_eq!(got.len(), 3);
    assert!(got.iter().all(|s| s.rays.len() == 200 && s.has_intensity()));

    // Dense on a device without a dense mode: Auto's choice, counted.
    let mut h = Harness::new(RplidarDriver::new(RplidarConfig {
        scan_mode: ScanMode::Dense,
        ..RplidarConfig::default()
    }));
    let out = a2().run(&mut h, 20);
    assert_eq!(h.driver.stats().errors("unsupported_scan_mode"), 1);
    assert!(scans(&out).len() >= 3, "legacy express instead");
}

fn request_motor(op: u8, v: u16) -> Vec<u8> {
    crate::rplidar::request::motor(op, v)
}

fn to_health(h: &mut Harness) {
    h.connect();
    h.wait(100);
}

#[test]
fn health_error_resets_drains_the_banner_and_reconnects() {
    let mut h = driver();
    to_health(&mut h);
    let out = h.feed(&reply(answer::DEVHEALTH, &[2, 0x34, 0x12]));
    let reason = "device health error 0x1234; reset it".to_string();
    assert_eq!(
        out,
        [
            DriverOutput::Health {
                ok: false,
                detail: "error, error code 0x1234".into()
            },
            DriverOutput::State(DeviceState::Recovering(reason.clone())),
            DriverOutput::Write(vec![0xA5, 0x40]),
        ]
    );
    assert_eq!(h.wait(300), []);
    assert_eq!(h.feed(b"RP LIDAR System.\r\nFirmware Ver 1.29 - rc9"), []);
    assert_eq!(h.wait(650), [], "1 s minimum");
    assert_eq!(h.feed(b"\r\nHardware Rev 7\r\n"), []);
    assert_eq!(h.wait(60), [], "banner not quiet yet");
    assert_eq!(
        h.wait(50),
        [
            DriverOutput::FlushInput,
            DriverOutput::State(DeviceState::Disconnected),
            DriverOutput::Reconnect(reason),
        ]
    );
    let stats = h.driver.stats();
    assert_eq!((stats.errors("health_error"), stats.reconnects), (1, 1));
    assert_eq!(stats.errors("stray_bytes"), 0, "the banner is not stray");
}

#[test]
fn health_warning_is_counted_and_the_handshake_goes_on() {
    let mut h = driver();
    to_health(&mut h);
    let out = h.feed(&reply(answer::DEVHEALTH, &[1, 5, 0]));
    assert_eq!(
        out[0],
        DriverOutput::Health {
            ok: false,
            detail: "warning, error code 0x0005".into()
        }
    );
    assert_eq!(out[1], DriverOutput::Write(vec![0xA5, 0x50]));
    assert_eq!(h.driver.stats().errors("health_warning"), 1);
}

#[test]
fn unanswered_request_is_retried_once_then_reconnects() {
    let mut h = driver();
    to_health(&mut h);
    assert_eq!(h.wait(1000), [DriverOutput::Write(vec![0xA5, 0x52])]);
    assert_eq!(
        h.wait(1000),
        [
            DriverOutput::State(DeviceState::Disconnected),
            DriverOutput::Reconnect("no answer to GET_HEALTH (asked twice)".into()),
        ]
    );
    assert_eq!(h.driver.stats().errors("timeout"), 2);
    assert_eq!(h.driver.stats().reconnects, 1);
    // Reconnect: everything is probed again.
    let out = a2().run(&mut h, 20);
    assert!(out.iter().any(|o| matches!(o, DriverOutput::Identity(_))));
    assert!(scans(&out).len() >= 3);
    assert_eq!(h.driver.stats().handshakes, 1);
}

#[test]
fn a_stalled_stream_reconnects() {
    let mut device = a2();
    device.stream = Vec::new();
    let mut h = driver();
    device.run(&mut h, 20);
    assert_eq!(h.driver.state(), &DeviceState::Streaming);
    assert_eq!(h.wait(2999), []);
    assert_eq!(
        h.wait(1),
        [
            DriverOutput::State(DeviceState::Disconnected),
            DriverOutput::Reconnect("no complete revolution for 3.0 s".into()),
        ]
    );
    assert_eq!(h.driver.stats().errors("stream_timeout"), 1);
}

#[test]
fn a_late_optional_answer_and_a_wrong_descriptor_are_counted() {
    let mut device = a2();
    device.board_flag = None;
    let mut h = driver();
    device.run(&mut h, 20);
    assert_eq!(h.driver.state(), &DeviceState::Streaming);
    // Start again, this time the board flag answer comes after its timeout,
    // and the scan start is first answered with the wrong stream type.
    let mut h = driver();
    to_health(&mut h);
    h.feed(&reply(answer::DEVHEALTH, &[0, 0, 0]));
    h.feed(&reply(answer::DEVINFO, &info_payload(0x28, 1, 20, 5)));
    h.feed(&reply(answer::SAMPLE_RATE, &[0xFC, 0x01, 0xFE, 0x00]));
    let out = h.wait(1000);
    assert!(writes(&out).contains(&vec![0xA5, 0x82, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00, 0x22]));
    h.feed(&reply(answer::ACC_BOARD_FLAG, &[1, 0, 0, 0]));
    h.feed(&descriptor(5, true, answer::MEASUREMENT));
    assert_eq!(h.driver.stats().errors("unexpected_response"), 2);
    let out = h.feed(&descriptor(84, true, answer::CAPSULED));
    assert_eq!(out, [DriverOutput::State(DeviceState::Streaming)]);
    assert_eq!(value(&identity_of(&mut h), "motor_control"), "dtr");
}

fn identity_of(h: &mut Harness) -> Vec<(String, String)> {
    // Reconnect to read the Identity again (it is re-probed every time).
    let mut device = a2();
    device.board_flag = None;
    identity(&device.run(h, 20))
}

#[test]
fn conf_queries_stop_when_the_mode_count_is_unanswered() {
    let mut h = driver();
    to_health(&mut h);
    h.feed(&reply(answer::DEVHEALTH, &[0, 0, 0]));
    h.feed(&reply(answer::DEVINFO, &info_payload(0x18, 1, 29, 7)));
    let out = h.feed(&reply(answer::SAMPLE_RATE, &[0xFC, 0x01, 0xFE, 0x00]));
    assert_eq!(writes(&out), [conf_request(0x70, None)]);
    // No answer: no more GET_LIDAR_CONF, straight to the board flag.
    let out = h.wait(1000);
    assert_eq!(writes(&out), [vec![0xA5, 0xFF, 0x04, 0, 0, 0, 0, 0x5E]]);
    let out = h.wait(1000);
    let pairs = identity(&out);
    assert!(value(&pairs, "scan_mode")
        .starts_with("Express (express samples, EXPRESS_SCAN mode 0, 254.0"));
    assert_eq!(h.driver.stats().notes("optional_timeout"), 2);
}

#[test]
fn malformed_answers_are_counted_and_the_request_still_times_out() {
    let mut h = driver();
    to_health(&mut h);
    assert_eq!(h.feed(&[0xA5, 0x5A, 0x03, 0, 0, 0x80, 0x06]), []);
    assert_eq!(h.feed(&reply(answer::DEVHEALTH, &[0, 0])), []);
    assert_eq!(
        h.feed(&reply(answer::DEVINFO, &info_payload(0x18, 1, 29, 7))),
        []
    );
    let stats = h.driver.stats();
    assert_eq!(stats.errors("bad_descriptor"), 1);
    assert_eq!(stats.errors("bad_reply"), 1);
    assert_eq!(stats.errors("unexpected_response"), 1);
    assert_eq!(h.wait(1000), [DriverOutput::Write(vec![0xA5, 0x52])]);
    let out = h.feed(&reply(answer::DEVHEALTH, &[0, 0, 0]));
    assert_eq!(out.last(), Some(&DriverOutput::Write(vec![0xA5, 0x50])));
}
