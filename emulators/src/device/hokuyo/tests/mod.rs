//! Tests of the Hokuyo emulators: golden vectors from the SCIP 2.0 spec,
//! state machines, faults, and properties over arbitrary host input. The
//! reply decoder here is written independently of the emulator's codec.

use proptest::prelude::*;

use super::codec::{checksum, encode_into};
use super::framer::MAX_LINE;
use super::output::OUTPUT_CAPACITY;
use super::{HokuyoEmulator, HokuyoModel, HokuyoOptions, Link, Rejection};
use crate::device::{Faults, RayReturn, RaySource, SerialDeviceEmulator};

// ---------------------------------------------------------------- helpers

/// A flat wall `distance` metres in front (+x), infinitely wide.
struct Wall {
    distance: f64,
    reflectance: f64,
}

impl Wall {
    fn range_at(&self, angle: f64) -> f64 {
        self.distance / angle.cos()
    }
}

impl RaySource for Wall {
    fn cast(&self, angle: f64, _time: f64, max_range: f64) -> Option<RayReturn> {
        if angle.cos() <= 0.0 {
            return None;
        }
        let range = self.range_at(angle);
        (range <= max_range).then_some(RayReturn {
            range,
            reflectance: self.reflectance,
        })
    }
}

const WALL: Wall = Wall {
    distance: 1.0,
    reflectance: 0.5,
};

/// How long before step 0 the beam passes the rear centre (AFRT - ARES/2),
/// the moment a scan's timestamp marks: 128 of 1024 steps of a 100 ms
/// revolution (URG-04LX), 180 of 1440 steps of 25 ms (UTM-30LX).
const URG_REAR_US: i64 = 12_500;
const UTM_REAR_US: i64 = 3_125;

/// The 24-bit timestamp of a scan whose step 0 is at `step0_ms`.
fn at_rear(step0_ms: u32, rear_us: i64) -> u32 {
    ((i64::from(step0_ms) * 1000 - rear_us).div_euclid(1000) & 0xFF_FFFF) as u32
}

fn exact() -> HokuyoOptions {
    HokuyoOptions {
        range_noise_scale: 0.0,
        ..HokuyoOptions::default()
    }
}

fn sensor(model: HokuyoModel, options: HokuyoOptions) -> HokuyoEmulator {
    sensor_at(model, options, 1.0)
}

fn sensor_at(model: HokuyoModel, options: HokuyoOptions, distance: f64) -> HokuyoEmulator {
    let wall = Wall {
        distance,
        reflectance: 0.5,
    };
    HokuyoEmulator::new(model, Box::new(wall), options)
}

fn urg() -> HokuyoEmulator {
    sensor(HokuyoModel::Urg04lx, exact())
}

/// Sends `command` at `t` and returns what the sensor sent by `t`.
fn exchange(emu: &mut HokuyoEmulator, command: &[u8], t: f64) -> Vec<u8> {
    emu.receive(command, t);
    poll(emu, t)
}

fn poll(emu: &mut HokuyoEmulator, t: f64) -> Vec<u8> {
    let mut out = Vec::new();
    emu.poll(t, &mut out);
    out
}

/// Test-side SCIP sum.
fn sum(bytes: &[u8]) -> u8 {
    let total: u32 = bytes.iter().map(|&b| u32::from(b)).sum();
    (total % 64) as u8 + b'0'
}

/// Test-side SCIP decoding of a 2/3/4-character group.
fn decode(chars: &[u8]) -> u32 {
    chars
        .iter()
        .fold(0, |acc, &c| (acc << 6) | u32::from(c - b'0'))
}

/// Splits output into messages (lists of lines), each ended by an empty
/// line.
fn messages(bytes: &[u8]) -> Vec<Vec<Vec<u8>>> {
    let mut all = Vec::new();
    let mut current = Vec::new();
    let mut lines: Vec<&[u8]> = bytes.split(|&b| b == b'\n').collect();
    lines.pop(); // what follows the last LF
    for line in lines {
        if line.is_empty() {
            all.push(std::mem::take(&mut current));
        } else {
            current.push(line.to_vec());
        }
    }
    assert!(current.is_empty(), "unterminated message {current:?}");
    all
}

/// A decoded scan message.
#[derive(Debug)]
struct Scan {
    echo: Vec<u8>,
    status: Vec<u8>,
    timestamp: u32,
    values: Vec<u32>,
    bad_sums: usize,
}

/// Decodes a scan message whose values are `width` characters each.
fn decode_scan(message: &[Vec<u8>], width: usize) -> Scan {
    let [echo, status, time, data @ ..] = message else {
        panic!("short scan message {message:?}");
    };
    let check = |line: &Vec<u8>| {
        let (text, last) = line.split_at(line.len() - 1);
        (text.to_vec(), sum(text) == last[0])
    };
    let (status_text, status_ok) = check(status);
    assert!(status_ok, "status sum");
    let (time_text, time_ok) = check(time);
    assert!(time_ok && time_text.len() == 4, "timestamp line {time:?}");
    let mut joined = Vec::new();
    let mut bad_sums = 0;
    for line in data {
        let (text, ok) = check(line);
        assert!(text.len() <= 64);
        bad_sums += usize::from(!ok);
        joined.extend(text);
    }
    assert_eq!(joined.len() % width, 0, "payload length");
    Scan {
        echo: echo.clone(),
        status: status_text,
        timestamp: decode(&time_text),
        values: joined.chunks(width).map(decode).collect(),
        bad_sums,
    }
}

/// Test-side geometry: the angle of `step` (REP-103, CCW from +x).
fn angle(step: u32, afrt: u32, ares: u32) -> f64 {
    (f64::from(step) - f64::from(afrt)) * 2.0 * std::f64::consts::PI / f64::from(ares)
}

fn wall_mm(step: u32, afrt: u32, ares: u32) -> u32 {
    (WALL.range_at(angle(step, afrt, ares)) * 1000.0).round() as u32
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

// ---------------------------------------------------------- golden vectors

#[test]
fn encodes_the_spec_examples() {
    // Spec §6, pp. 6-8.
    let cases: [(u32, u32, &[u8]); 3] = [
        (5432, 3, b"1Dh"),
        (16_000_000, 4, b"m2@0"),
        (1234, 2, b"CB"),
    ];
    for (value, width, expected) in cases {
        let mut out = Vec::new();
        encode_into(value, width, &mut out);
        assert_eq!(out, expected);
        assert_eq!(decode(expected), value);
    }
}

#[test]
fn sums_the_spec_examples() {
    assert_eq!(checksum(b"00"), b'P');
    assert_eq!(checksum(b"99"), b'b');
    assert_eq!(sum(b"00"), b'P');
    assert_eq!(sum(b"99"), b'b');
}

#[test]
fn qt_replies_as_the_spec() {
    let mut emu = urg();
    assert_eq!(exchange(&mut emu, b"QT\n", 0.5), b"QT\n00P\n\n");
}

#[test]
fn pp_matches_the_urg_04lx_example() {
    let mut emu = urg();
    let reply = text(&exchange(&mut emu, b"PP\n", 0.5));
    assert!(reply.starts_with("PP\n00P\n"));
    assert!(reply.ends_with("\n\n"));
    // Spec p. 21 (ARES sum per the URG wiki "scip_status_en").
    for line in [
        "DMIN:20;4\n",
        "DMAX:5600;_\n",
        "ARES:1024;\\\n",
        "AMIN:44;7\n",
        "AMAX:725;o\n",
        "AFRT:384;6\n",
        "SCAN:600;e\n",
    ] {
        assert!(reply.contains(line), "{line:?} missing from {reply:?}");
    }
}

#[test]
fn pp_matches_a_utm_30lx_log() {
    let mut emu = sensor(HokuyoModel::Utm30lx, exact());
    let reply = text(&exchange(&mut emu, b"PP\n", 0.5));
    for line in [
        "DMIN:23;7\n",
        "DMAX:60000;J\n",
        "ARES:1440;^\n",
        "AMIN:0;?\n",
        "AMAX:1080;Z\n",
        "AFRT:540;0\n",
        "SCAN:2400;U\n",
    ] {
        assert!(reply.contains(line), "{line:?} missing from {reply:?}");
    }
}

#[test]
fn vv_and_ii_lines_match_the_urg_wiki_example() {
    let mut emu = urg();
    let vv = text(&exchange(&mut emu, b"VV\n", 0.5));
    for line in [
        "VV\n00P\n",
        "VEND:Hokuyo Automatic Co.,Ltd.;[\n",
        "PROD:SOKUIKI Sensor URG-04LX;[\n",
        "FIRM:3.1.00(18/Jan./2007);`\n",
        "PROT:SCIP 2.0;N\n",
        "SERI:H0614967;V\n",
    ] {
        assert!(vv.contains(line), "{line:?} missing from {vv:?}");
    }
    let ii = text(&exchange(&mut emu, b"II\n", 0.6));
    for line in [
        "MODL:URG-04LX(Hokuyo Automatic Co.,Ltd.);N\n",
        "LASR:OFF;7\n",
        "SCSP:Initial(600[rpm])<-Default setting by user;A\n",
        "MESM:IDLE;:\n",
        "SBPS:19200[bps]<-Default setting by user;A\n",
        "STAT:Sensor works well.;8\n",
    ] {
        assert!(ii.contains(line), "{line:?} missing from {ii:?}");
    }
}

// --------------------------------------------------------------- streaming

#[test]
fn md_streams_the_ranges_of_a_flat_wall() {
    let mut emu = urg();
    let (start, end) = (384 - 170, 384 + 170);
    let command = format!("MD{start:04}{end:04}01000\n");
    let out = exchange(&mut emu, command.as_bytes(), 0.0);
    assert_eq!(
        out,
        format!("MD{start:04}{end:04}01000\n00P\n\n").as_bytes()
    );
    let all = messages(&poll(&mut emu, 0.35));
    assert_eq!(all.len(), 3, "scans at 0.07, 0.17, 0.27 s");
    let expected: Vec<u32> = (start..=end).map(|s| wall_mm(s, 384, 1024)).collect();
    for (k, message) in all.iter().enumerate() {
        let scan = decode_scan(message, 3);
        assert_eq!(scan.echo, format!("MD{start:04}{end:04}01000").as_bytes());
        assert_eq!(scan.status, b"99");
        assert_eq!(scan.timestamp, at_rear(100 * k as u32, URG_REAR_US));
        assert_eq!(scan.bad_sums, 0);
        assert_eq!(scan.values, expected);
    }
}

#[test]
fn clusters_report_their_smallest_range() {
    let mut emu = urg();
    exchange(&mut emu, b"MD0044072503000\n", 0.0);
    let scan = decode_scan(&messages(&poll(&mut emu, 0.08))[0], 3);
    // Test-side truth: the wall's range, or nothing behind / beyond DMAX.
    let seen = |step: u32| {
        let a = angle(step, 384, 1024);
        let mm = (WALL.range_at(a) * 1000.0).round();
        (a.cos() > 0.0 && mm <= 5600.0).then_some(mm as u32)
    };
    let steps: Vec<u32> = (44..=725).collect();
    let expected: Vec<u32> = steps
        .chunks(3)
        .map(|c| c.iter().filter_map(|&s| seen(s)).min().unwrap_or(1))
        .collect();
    assert_eq!(scan.values.len(), 682_usize.div_ceil(3));
    assert_eq!(scan.values, expected);
}

#[test]
fn a_finite_stream_counts_down_then_stops_the_laser() {
    let mut emu = urg();
    exchange(&mut emu, b"MD0384038401103;ab\n", 0.0);
    let all = messages(&poll(&mut emu, 2.0));
    let echoes: Vec<String> = all.iter().map(|m| text(&m[0])).collect();
    assert_eq!(
        echoes,
        [
            "MD0384038401102;ab",
            "MD0384038401101;ab",
            "MD0384038401100;ab"
        ]
    );
    // Interval 1: every other revolution.
    let stamps: Vec<u32> = all.iter().map(|m| decode_scan(m, 3).timestamp).collect();
    assert_eq!(stamps, [0, 200, 400].map(|ms| at_rear(ms, URG_REAR_US)));
    assert_eq!(
        exchange(&mut emu, b"GD0384038401\n", 2.1),
        b"GD0384038401\n10Q\n\n"
    );
}

#[test]
fn ms_sends_two_characters_and_zero_beyond_4095() {
    let mut near = sensor_at(HokuyoModel::Urg04lx, exact(), 1.0);
    exchange(&mut near, b"MS0384038400001\n", 0.0);
    let scan = decode_scan(&messages(&poll(&mut near, 0.1))[0], 2);
    assert_eq!(scan.values, [1000]);
    let mut far = sensor_at(HokuyoModel::Urg04lx, exact(), 5.0);
    exchange(&mut far, b"MS0384038400001\n", 0.0);
    let scan = decode_scan(&messages(&poll(&mut far, 0.1))[0], 2);
    assert_eq!(scan.values, [0]);
}

#[test]
fn me_interleaves_range_and_intensity_at_40_hz() {
    let mut emu = sensor(HokuyoModel::Utm30lx, exact());
    exchange(&mut emu, b"ME0000108001000\n", 0.0);
    let all = messages(&poll(&mut emu, 1.0));
    assert_eq!(all.len(), 40);
    for (k, message) in all.iter().enumerate() {
        let scan = decode_scan(message, 3);
        assert_eq!(scan.timestamp, at_rear(25 * k as u32, UTM_REAR_US));
        assert_eq!(scan.values.len(), 2 * 1081);
        let front = 2 * 540;
        assert_eq!(scan.values[front], 1000);
        assert_eq!(scan.values[front + 1], 5000);
        let step: u32 = 540 + 100;
        assert_eq!(scan.values[2 * step as usize], wall_mm(step, 540, 1440));
        // Steps behind the sensor see nothing: UTM error code 1.
        assert_eq!(scan.values[0], 1);
    }
}

#[test]
fn me_is_undefined_on_the_urg_04lx() {
    let mut emu = urg();
    assert_eq!(
        exchange(&mut emu, b"ME0044072501000\n", 0.0),
        b"ME0044072501000\n0Ee\n\n"
    );
}

#[test]
fn streaming_continues_while_nobody_reads() {
    let mut emu = urg();
    exchange(&mut emu, b"MD0044072501000\n", 0.0);
    let all = messages(&poll(&mut emu, 10.0));
    assert_eq!(all.len(), 100);
    assert!(emu.sensor.laser_on);
}

#[test]
fn a_long_silence_keeps_output_bounded() {
    let mut emu = sensor(HokuyoModel::Utm30lx, exact());
    exchange(&mut emu, b"ME0000108001000\n", 0.0);
    let out = poll(&mut emu, 1.0e7);
    assert!(out.len() <= OUTPUT_CAPACITY);
    assert!(emu.stats().scans_skipped_output_full > 0);
    // Still streaming afterwards.
    assert!(!messages(&poll(&mut emu, 1.0e7 + 0.1)).is_empty());
}

#[test]
fn timestamps_wrap_at_24_bits() {
    let options = HokuyoOptions {
        clock_start_ms: (1 << 24) - 50,
        ..exact()
    };
    let mut emu = sensor(HokuyoModel::Urg04lx, options);
    exchange(&mut emu, b"MD0384038401000\n", 0.0);
    let stamps: Vec<u32> = messages(&poll(&mut emu, 0.25))
        .iter()
        .map(|m| decode_scan(m, 3).timestamp)
        .collect();
    assert_eq!(
        stamps,
        [(1 << 24) - 50, 50].map(|ms| at_rear(ms, URG_REAR_US))
    );
}

// ------------------------------------------------------- single scans, BM

#[test]
fn gd_needs_the_laser() {
    let mut emu = urg();
    assert_eq!(
        exchange(&mut emu, b"GD0384038401\n", 0.5),
        b"GD0384038401\n10Q\n\n"
    );
    assert_eq!(exchange(&mut emu, b"BM\n", 0.6), b"BM\n00P\n\n");
    assert_eq!(exchange(&mut emu, b"BM\n", 0.6), b"BM\n02R\n\n");
    let scan = decode_scan(
        &messages(&exchange(&mut emu, b"GD0383038501\n", 0.65))[0],
        3,
    );
    assert_eq!(scan.status, b"00");
    assert_eq!(
        scan.values,
        [wall_mm(383, 384, 1024), 1000, wall_mm(385, 384, 1024)]
    );
    // The latest complete revolution started at 0.5 s.
    assert_eq!(scan.timestamp, at_rear(500, URG_REAR_US));
    assert_eq!(exchange(&mut emu, b"QT\n", 0.7), b"QT\n00P\n\n");
    assert_eq!(
        exchange(&mut emu, b"GS0384038401\n", 0.8),
        b"GS0384038401\n10Q\n\n"
    );
}

// ------------------------------------------------------ command checking

#[test]
fn malformed_commands_get_the_spec_statuses() {
    let cases: [(&[u8], &[u8]); 17] = [
        (b"XX", b"0E"),
        (b"Q", b"0E"),
        (b"MD004407250100", b"0C"),
        (b"MD00440725010000", b"0D"),
        (b"QTX", b"0D"),
        (b"MDx044072501000", b"01"),
        (b"MD0044x72501000", b"02"),
        (b"MD004407250x000", b"03"),
        (b"MD0044080001000", b"04"),
        (b"MD0010072501000", b"04"),
        (b"MD0400030001000", b"05"),
        (b"MD00440725010x00", b"0D"),
        (b"MD004407250100x", b"07"),
        (b"MD0044072501x00", b"06"),
        (b"TM3", b"01"),
        (b"QT;abcdefghijklmnopq", b"0G"),
        (b"QT;a-b", b"0H"),
    ];
    for (command, status) in cases {
        let mut emu = urg();
        let mut line = command.to_vec();
        line.push(b'\n');
        let mut expected = command.to_vec();
        expected.push(b'\n');
        expected.extend_from_slice(status);
        expected.push(sum(status));
        expected.extend_from_slice(b"\n\n");
        assert_eq!(text(&exchange(&mut emu, &line, 0.5)), text(&expected));
    }
}

#[test]
fn rejections_are_counted_by_kind() {
    let mut emu = urg();
    exchange(&mut emu, b"XX\nQT;a-b\nMD0044080001000\n", 0.5);
    let stats = emu.stats();
    assert_eq!(stats.rejected(Rejection::UnknownCommand), 1);
    assert_eq!(stats.rejected(Rejection::TagInvalid), 1);
    assert_eq!(stats.rejected(Rejection::BadParameter), 1);
    let names: Vec<&str> = stats.rejections().map(|(name, _)| name).collect();
    assert!(names.contains(&"unknown_command"));
}

#[test]
fn terminators_and_tags() {
    let mut emu = urg();
    assert_eq!(exchange(&mut emu, b"QT;abc\r\n", 0.5), b"QT;abc\n00P\n\n");
    assert_eq!(exchange(&mut emu, b"QT\r", 0.5), b"QT\n00P\n\n");
    assert_eq!(
        exchange(&mut emu, b"QT\r\nQT\n", 0.5),
        b"QT\n00P\n\nQT\n00P\n\n"
    );
}

#[test]
fn overlong_lines_are_refused_and_bounded() {
    let mut emu = urg();
    let mut line = vec![b'Q'; 1000];
    line.push(b'\n');
    let out = exchange(&mut emu, &line, 0.5);
    let mut expected = vec![b'Q'; MAX_LINE];
    expected.extend_from_slice(b"\n0Bb\n\n");
    assert_eq!(out, expected);
    assert_eq!(emu.stats().rejected(Rejection::LineTooLong), 1);
}

// ------------------------------------------------------- modes and states

#[test]
fn starts_in_scip_1_1_until_switched() {
    let options = HokuyoOptions {
        starts_in_scip1: true,
        ..exact()
    };
    let mut emu = sensor(HokuyoModel::Urg04lx, options);
    assert_eq!(exchange(&mut emu, b"QT\n", 0.1), b"QT\nE\n\n");
    assert_eq!(exchange(&mut emu, b"SCIP2.0\n", 0.2), b"SCIP2.0\n0\n\n");
    assert_eq!(exchange(&mut emu, b"QT\n", 0.3), b"QT\n00P\n\n");
    assert_eq!(emu.stats().rejected(Rejection::Scip11Mode), 1);
}

#[test]
fn time_adjust_mode() {
    let mut emu = urg();
    assert_eq!(exchange(&mut emu, b"TM1\n", 0.1), b"TM1\n04T\n\n");
    assert_eq!(exchange(&mut emu, b"TM2\n", 0.1), b"TM2\n03S\n\n");
    assert_eq!(exchange(&mut emu, b"TM0\n", 0.1), b"TM0\n00P\n\n");
    assert_eq!(exchange(&mut emu, b"TM0\n", 0.1), b"TM0\n02R\n\n");
    // urg_c recognises TM mode by "0Ee" to QT.
    assert_eq!(exchange(&mut emu, b"QT\n", 0.2), b"QT\n0Ee\n\n");
    let reply = exchange(&mut emu, b"TM1\n", 1.234);
    let all = messages(&reply);
    assert_eq!(all[0][..2], [b"TM1".to_vec(), b"00P".to_vec()]);
    let time = &all[0][2];
    assert_eq!(time.len(), 5);
    assert_eq!(sum(&time[..4]), time[4]);
    assert_eq!(decode(&time[..4]), 1234);
    assert_eq!(exchange(&mut emu, b"TM2\n", 1.3), b"TM2\n00P\n\n");
    assert_eq!(exchange(&mut emu, b"QT\n", 1.3), b"QT\n00P\n\n");
}

#[test]
fn rs_stops_and_resets_the_clock() {
    let mut emu = urg();
    exchange(&mut emu, b"MD0384038401000\n", 0.0);
    poll(&mut emu, 4.99);
    assert_eq!(exchange(&mut emu, b"RS\n", 5.0), b"RS\n00P\n\n");
    assert!(poll(&mut emu, 6.0).is_empty(), "stream stopped");
    exchange(&mut emu, b"TM0\n", 6.0);
    let all = messages(&exchange(&mut emu, b"TM1\n", 6.5));
    assert_eq!(decode(&all[0][2][..4]), 1500);
}

#[test]
fn rs232_output_is_paced_and_ss_switches_after_its_reply() {
    let options = HokuyoOptions {
        link: Link::Rs232 { baud: 19_200 },
        ..exact()
    };
    let mut emu = sensor(HokuyoModel::Urg04lx, options);
    assert_eq!(emu.uart_baud(), Some(19_200));
    emu.receive(b"SS115200\n", 1.0);
    let reply = b"SS115200\n00P\n\n";
    // 15 bytes at 1920 bytes/s take 7.8 ms.
    let early = poll(&mut emu, 1.004);
    assert!(!early.is_empty() && early.len() < reply.len());
    assert_eq!(emu.uart_baud(), Some(19_200));
    let rest = poll(&mut emu, 1.01);
    assert_eq!([early, rest].concat(), reply);
    assert_eq!(emu.uart_baud(), Some(115_200));
    assert_eq!(
        exchange(&mut emu, b"SS115200\n", 2.0).len(),
        0,
        "still on the wire"
    );
    assert_eq!(poll(&mut emu, 2.1), b"SS115200\n03S\n\n");
    assert_eq!(exchange(&mut emu, b"SS038400\n", 3.0), b"");
    assert_eq!(poll(&mut emu, 3.1), b"SS038400\n02R\n\n");
    exchange(&mut emu, b"SS11520x\n", 4.0);
    assert_eq!(poll(&mut emu, 4.1), b"SS11520x\n01Q\n\n");
    // RS goes back to the power-on rate once its reply is out.
    exchange(&mut emu, b"RS\n", 5.0);
    assert_eq!(poll(&mut emu, 5.1), b"RS\n00P\n\n");
    assert_eq!(emu.uart_baud(), Some(19_200));
}

#[test]
fn a_slow_line_skips_scans_it_cannot_carry() {
    let options = HokuyoOptions {
        link: Link::Rs232 { baud: 19_200 },
        ..exact()
    };
    let mut emu = sensor(HokuyoModel::Urg04lx, options);
    exchange(&mut emu, b"MD0044072501000\n", 0.0);
    let mut out = poll(&mut emu, 5.0);
    // Keep complete messages only; the line is mid-scan.
    let end = out
        .windows(2)
        .rposition(|w| w == b"\n\n")
        .map_or(0, |at| at + 2);
    out.truncate(end);
    let all = messages(&out);
    // A full scan is about 2.1 kB, over a second at 19200 bit/s.
    assert!(all.len() >= 4 && all.len() <= 6, "{} messages", all.len());
    assert!(emu.stats().scans_skipped_link_busy > 30);
}

#[test]
fn ss_over_usb_and_on_the_utm_30lx() {
    let mut usb = urg();
    assert_eq!(exchange(&mut usb, b"SS115200\n", 0.5), b"SS115200\n00P\n\n");
    assert_eq!(usb.uart_baud(), None);
    assert!(text(&exchange(&mut usb, b"II\n", 0.6)).contains("SBPS:115200[bps];"));
    let mut utm = sensor(HokuyoModel::Utm30lx, exact());
    assert_eq!(exchange(&mut utm, b"SS115200\n", 0.5), b"SS115200\n04T\n\n");
}

#[test]
fn abnormal_state_until_two_rbs_within_a_second() {
    let options = HokuyoOptions {
        abnormal_after_scans: Some(2),
        reboot_seconds: 2.0,
        ..exact()
    };
    let mut emu = sensor(HokuyoModel::Urg04lx, options);
    exchange(&mut emu, b"MD0384038401000\n", 0.0);
    let all = messages(&poll(&mut emu, 1.0));
    assert_eq!(all.len(), 3);
    assert_eq!(decode_scan(&all[1], 3).status, b"99");
    assert_eq!(all[2], [b"MD0384038401000".to_vec(), b"0Ll".to_vec()]);
    assert_eq!(exchange(&mut emu, b"QT\n", 1.1), b"QT\n0Ll\n\n");
    assert_eq!(exchange(&mut emu, b"RS\n", 1.1), b"RS\n0Ll\n\n");
    assert!(text(&exchange(&mut emu, b"II\n", 1.1)).contains("STAT:Sensor is in abnormal state."));
    assert_eq!(exchange(&mut emu, b"RB\n", 1.2), b"RB\n01Q\n\n");
    assert_eq!(
        exchange(&mut emu, b"RB\n", 2.5),
        b"RB\n01Q\n\n",
        "more than 1 s apart"
    );
    assert_eq!(exchange(&mut emu, b"RB\n", 3.0), b"RB\n00P\n\n");
    assert_eq!(exchange(&mut emu, b"QT\n", 4.0), b"", "rebooting");
    assert!(emu.stats().rejected(Rejection::Rebooting) > 0);
    assert_eq!(exchange(&mut emu, b"QT\n", 5.1), b"QT\n00P\n\n");
    // The clock restarted at the end of the reboot (about 5.0 s).
    exchange(&mut emu, b"TM0\n", 5.2);
    let time = decode(&messages(&exchange(&mut emu, b"TM1\n", 5.2))[0][2][..4]);
    assert!((199..=201).contains(&time), "{time}");
}

#[test]
fn a_reboot_returns_to_scip_1_1() {
    let options = HokuyoOptions {
        starts_in_scip1: true,
        ..exact()
    };
    let mut emu = sensor(HokuyoModel::Urg04lx, options);
    exchange(&mut emu, b"SCIP2.0\n", 0.1);
    exchange(&mut emu, b"RB\nRB\n", 0.2);
    assert_eq!(exchange(&mut emu, b"QT\n", 2.0), b"QT\nE\n\n");
}

// ------------------------------------------------------------------ faults

fn scans_one_by_one(options: HokuyoOptions, count: usize) -> Vec<Vec<u8>> {
    let mut emu = sensor(HokuyoModel::Urg04lx, options);
    exchange(&mut emu, b"MD0044072501000\n", 0.0);
    // Scan k is ready at 0.1 k + 0.071 s.
    (0..count)
        .map(|k| poll(&mut emu, 0.1 * k as f64 + 0.09))
        .collect()
}

#[test]
fn corrupt_every_spoils_one_line_of_every_nth_scan() {
    let options = HokuyoOptions {
        faults: Faults {
            corrupt_every: 3,
            ..Faults::default()
        },
        ..exact()
    };
    let bad: Vec<usize> = scans_one_by_one(options, 9)
        .iter()
        .map(|bytes| decode_scan(&messages(bytes)[0], 3).bad_sums)
        .collect();
    assert_eq!(bad, [0, 0, 1, 0, 0, 1, 0, 0, 1]);
}

#[test]
fn garbage_every_prefixes_every_nth_scan() {
    let clean = scans_one_by_one(exact(), 6);
    let options = HokuyoOptions {
        faults: Faults {
            garbage_every: 2,
            seed: 7,
            ..Faults::default()
        },
        ..exact()
    };
    let dirty = scans_one_by_one(options, 6);
    for (k, (clean, dirty)) in clean.iter().zip(&dirty).enumerate() {
        if (k + 1) % 2 == 0 {
            assert!(
                dirty.len() > clean.len() && dirty.ends_with(clean),
                "scan {k}"
            );
        } else {
            assert_eq!(dirty, clean, "scan {k}");
        }
    }
}

// ------------------------------------------------------------------ noise

#[test]
fn dropouts_report_an_error_code() {
    let options = HokuyoOptions {
        dropout_probability: 1.0,
        ..exact()
    };
    let mut emu = sensor(HokuyoModel::Urg04lx, options);
    exchange(&mut emu, b"MD0300040001000\n", 0.0);
    let scan = decode_scan(&messages(&poll(&mut emu, 0.08))[0], 3);
    assert!(scan.values.iter().all(|&v| v == 6));
}

#[test]
fn noise_follows_the_datasheet_accuracy() {
    let mut emu = sensor(HokuyoModel::Urg04lx, HokuyoOptions::default());
    exchange(&mut emu, b"MD0384038401000\n", 0.0);
    let values: Vec<u32> = messages(&poll(&mut emu, 50.0))
        .iter()
        .flat_map(|m| decode_scan(m, 3).values)
        .collect();
    assert_eq!(values.len(), 500);
    // ±10 mm at 1 m is 2 sigma: all within 4 sigma, and not all equal.
    assert!(values.iter().all(|&v| (980..=1020).contains(&v)));
    assert!(values.iter().any(|&v| v != values[0]));
    let mean = values.iter().map(|&v| f64::from(v)).sum::<f64>() / 500.0;
    assert!((mean - 1000.0).abs() < 1.5, "{mean}");
}

// ------------------------------------------------------------- properties

/// Host input: valid commands mixed with arbitrary bytes.
fn host_bytes() -> impl Strategy<Value = Vec<u8>> {
    let commands: Vec<&'static [u8]> = vec![
        b"MD0044072501000\n",
        b"ME0000108003100\n",
        b"MS0000108000005\n",
        b"GD0044072501\n",
        b"ND0000108001000\n",
        b"NE0000108002003\n",
        b"HD0000108001\n",
        b"HE0500060003\n",
        b"BM\n",
        b"QT\n",
        b"RS\n",
        b"RB\n",
        b"TM0\n",
        b"TM1\n",
        b"TM2\n",
        b"SS115200\n",
        b"SCIP2.0\n",
        b"II\n",
    ];
    prop_oneof![
        prop::sample::select(commands).prop_map(<[u8]>::to_vec),
        prop::collection::vec(any::<u8>(), 0..200),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn arbitrary_host_bytes_never_panic_and_stay_bounded(
        utm in any::<bool>(),
        rs232 in any::<bool>(),
        scip1 in any::<bool>(),
        multi_echo_fraction in prop::num::f64::ANY,
        steps in prop::collection::vec((host_bytes(), 0.0f64..0.06), 1..40),
    ) {
        let model = if utm { HokuyoModel::Utm30lx } else { HokuyoModel::Urg04lx };
        let options = HokuyoOptions {
            link: if rs232 { Link::Rs232 { baud: 115_200 } } else { Link::Usb },
            starts_in_scip1: scip1,
            abnormal_after_scans: Some(5),
            dropout_probability: 0.1,
            multi_echo_fraction,
            faults: Faults { corrupt_every: 2, garbage_every: 3, seed: 1 },
            ..HokuyoOptions::default()
        };
        let mut emu = HokuyoEmulator::new(model, Box::new(WALL), options);
        let mut t = 0.0;
        for (bytes, dt) in steps {
            t += dt;
            emu.receive(&bytes, t);
            let mut out = Vec::new();
            emu.poll(t, &mut out);
            prop_assert!(out.len() <= OUTPUT_CAPACITY);
            prop_assert!(emu.output.pending() <= OUTPUT_CAPACITY);
            prop_assert!(emu.framer.held() <= MAX_LINE);
        }
    }

    #[test]
    fn time_may_jump_or_be_nonsense(times in prop::collection::vec(prop::num::f64::ANY, 1..20)) {
        let mut emu = HokuyoEmulator::new(HokuyoModel::Urg04lx, Box::new(WALL), exact());
        emu.receive(b"MD0044072501000\n", 0.0);
        for t in times {
            let mut out = Vec::new();
            emu.poll(t, &mut out);
            prop_assert!(out.len() <= OUTPUT_CAPACITY);
        }
    }
}

#[test]
fn model_names_round_trip() {
    for model in [HokuyoModel::Urg04lx, HokuyoModel::Utm30lx] {
        assert_eq!(HokuyoModel::from_name(model.name()), Some(model));
        let emu = HokuyoEmulator::new(model, Box::new(WALL), exact());
        assert_eq!(emu.model(), model.name());
    }
    assert_eq!(
        HokuyoModel::from_name("URG-04LX"),
        Some(HokuyoModel::Urg04lx)
    );
    assert_eq!(HokuyoModel::from_name("ust-10lx"), None);
}

mod multi_echo;
