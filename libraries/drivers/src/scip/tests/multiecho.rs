//! Multi-echo commands (`ND`/`NE` streamed, `HD`/`HE` polled): replies
//! written by hand from the rule (urg_c `receive_length_data()`: every echo
//! after a step's first is `&` and its value group, anywhere in the joined
//! data lines), the malformed cases, and the fallback to single-echo commands.

use super::support::*;
use crate::device::{DeviceDriver, DeviceState, DriverOutput};
use crate::scip::*;

const STEP_NS: f64 = 100e6 / 1024.0;

/// The line sum, computed here independently of the driver's `line_sum`:
/// the low 6 bits of the byte sum, plus `0x30` (spec §7).
fn sum_char(body: &str) -> char {
    let total: u32 = body.bytes().map(u32::from).sum();
    char::from((total & 0x3F) as u8 + 0x30)
}

/// A line with its sum and LF.
fn hand_line(body: &str) -> String {
    format!("{body}{}\n", sum_char(body))
}

/// A 4-character timestamp, encoded here independently (spec §6).
fn hand_stamp(ms: u32) -> String {
    (0..4)
        .rev()
        .map(|g| char::from(0x30 + ((ms >> (6 * g)) & 0x3F) as u8))
        .collect()
}

/// A reply with `status` (already summed) and hand-written data lines.
fn hand_reply(echo: &str, status: &str, stamp_ms: u32, data: &[&str]) -> Vec<u8> {
    let mut text = format!("{echo}\n{status}\n{}", hand_line(&hand_stamp(stamp_ms)));
    for body in data {
        text.push_str(&hand_line(body));
    }
    text.push('\n');
    text.into_bytes()
}

fn angle(step: u16) -> f32 {
    ((f64::from(step) - 384.0) * std::f64::consts::TAU / 1024.0) as f32
}

fn offset_ns(steps_from_first: u16) -> u32 {
    (f64::from(steps_from_first) * STEP_NS).round() as u32
}

/// The metres a ray carries for `mm` on the URG-04LX (DMIN 20, DMAX 5600).
fn metres(mm: u32) -> f32 {
    if (20..=5600).contains(&mm) {
        mm as f32 / 1000.0
    } else {
        f32::NAN
    }
}

fn same_range(got: f32, want: f32) -> bool {
    got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan())
}

/// A driver for `config` that has started `echo` (the acknowledgement fed).
fn rig_running(config: ScipConfig, echo: &str) -> (Rig, Vec<DriverOutput>) {
    let mut rig = Rig::new(config);
    let mut out = rig.bring_up();
    out.extend(rig.feed(&reply(echo, "00", &[])));
    (rig, out)
}

fn nd_config(start: u16, end: u16) -> ScipConfig {
    ScipConfig {
        scan: ScanCommand::Nd,
        start_step: Some(start),
        end_step: Some(end),
        ..ScipConfig::default()
    }
}

const ND_ECHO: &str = "ND0100013301000";

/// Steps 100..=133 with `ND`, written from the rule: `0@0` = 16 * 64 = 1024
/// mm, each next letter 64 mm more; `001` = 1, an error code; `1Dh` = 5432.
/// Line 1 ends with `&0`, the first two characters of step 17's second echo
/// (`&0S0`), whose value ends on line 2. Line 2 ends with a bare `&`: step
/// 32's second echo (`0X0`) is all on line 3. Step 19 has 3 echoes.
const ND_LINE1: &str = "0@00A0&0B00C0001&0D00E00F00G00H00I00J00K00L00M00N00O00P00Q00R0&0";
const ND_LINE2: &str = "S00T00U0&0V0&0W01Dh0Z00a00a00a00a0&0b00a00a00a00a00a0&0c00a00d0&";
const ND_LINE3: &str = "0X00Y0";

/// Every echo of the reply above in wire order: (step - 100, mm).
const ND_ECHOES: [(u16, u32); 42] = [
    (0, 1024),
    (1, 1088),
    (1, 1152),
    (2, 1216),
    (3, 1),
    (3, 1280),
    (4, 1344),
    (5, 1408),
    (6, 1472),
    (7, 1536),
    (8, 1600),
    (9, 1664),
    (10, 1728),
    (11, 1792),
    (12, 1856),
    (13, 1920),
    (14, 1984),
    (15, 2048),
    (16, 2112),
    (17, 2176),
    (17, 2240),
    (18, 2304),
    (19, 2368),
    (19, 2432),
    (19, 2496),
    (20, 5432),
    (21, 2688),
    (22, 3136),
    (23, 3136),
    (24, 3136),
    (25, 3136),
    (25, 3200),
    (26, 3136),
    (27, 3136),
    (28, 3136),
    (29, 3136),
    (30, 3136),
    (30, 3264),
    (31, 3136),
    (32, 3328),
    (32, 2560),
    (33, 2624),
];

#[test]
fn nd_reply_with_echoes_straddling_lines() {
    assert_eq!(ND_LINE1.len(), 64);
    assert_eq!(ND_LINE2.len(), 64);
    assert_eq!(&ND_LINE1[62..], "&0", "an echo and its value straddle");
    assert!(ND_LINE2.ends_with('&'), "a bare marker ends a line");
    let (mut rig, out) = rig_running(nd_config(100, 133), ND_ECHO);
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("ND0100013301000\n")
    );
    let pairs = identity(&out).expect("identity at stream start");
    assert_eq!(
        identity_value(&pairs, "scan_command").as_deref(),
        Some("ND")
    );
    assert_eq!(identity_value(&pairs, "multiecho").as_deref(), Some("yes"));

    let stamp = rig.device_ms() - 100;
    let data = [ND_LINE1, ND_LINE2, ND_LINE3];
    let out = rig.feed(&hand_reply(ND_ECHO, "99b", stamp, &data));
    let [scan] = scans(&out).try_into().expect("one scan");
    assert_eq!(scan.rays.len(), ND_ECHOES.len());
    for (i, (ray, &(step, mm))) in scan.rays.iter().zip(&ND_ECHOES).enumerate() {
        assert_eq!(ray.angle, angle(100 + step), "ray {i}");
        assert_eq!(ray.offset_ns, offset_ns(step), "ray {i}");
        assert!(same_range(ray.range, metres(mm)), "ray {i}: {}", ray.range);
        assert_eq!(ray.intensity, None);
    }
    assert!(
        scan.rays[4].range.is_nan(),
        "the error code is a NaN ray, kept"
    );
    assert_eq!(
        rig.driver.stats().total_errors(),
        0,
        "{}",
        rig.driver.stats()
    );
}

#[test]
fn nd_data_decodes_to_echo_counts() {
    let request = ScanRequest {
        kind: ScanKind::Nd,
        start: 100,
        end: 133,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    let lines: Vec<Vec<u8>> = [hand_stamp(7).as_str(), ND_LINE1, ND_LINE2, ND_LINE3]
        .iter()
        .map(|body| hand_line(body).trim_end().as_bytes().to_vec())
        .collect();
    let data = decode_scan(&lines, &request).unwrap();
    assert_eq!(data.timestamp_ms, 7);
    let mut counts = vec![1u8; 34];
    for (step, n) in [(1, 2), (3, 2), (17, 2), (19, 3), (25, 2), (30, 2), (32, 2)] {
        counts[step] = n;
    }
    assert_eq!(data.echoes, Some(counts));
    let ranges: Vec<u32> = ND_ECHOES.iter().map(|&(_, mm)| mm).collect();
    assert_eq!(data.ranges, ranges);
    assert_eq!(data.intensities, None);
}

#[test]
fn ne_echoes_carry_their_own_intensity() {
    let config = ScipConfig {
        intensity: true,
        ..nd_config(200, 202)
    };
    let (mut rig, out) = rig_running(config, "NE0200020201000");
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("NE0200020201000\n")
    );
    let pairs = identity(&out).unwrap();
    assert_eq!(identity_value(&pairs, "intensity").as_deref(), Some("yes"));
    assert_eq!(identity_value(&pairs, "multiecho").as_deref(), Some("yes"));
    // Step 200: 1024 mm / 49, then & 1088 mm / 50. Step 201: error code 1,
    // intensity 0. Step 202: three echoes, 1152/51, 1216/52, 1280/53.
    let line = "0@000a&0A000b001000".to_owned() + "0B000c&0C000d&0D000e";
    assert_eq!(line.len(), 39);
    let stamp = rig.device_ms() - 100;
    let out = rig.feed(&hand_reply("NE0200020201000", "99b", stamp, &[&line]));
    let [scan] = scans(&out).try_into().expect("one scan");
    let want = [
        (0, 1024, 49),
        (0, 1088, 50),
        (1, 1, 0),
        (2, 1152, 51),
        (2, 1216, 52),
        (2, 1280, 53),
    ];
    assert_eq!(scan.rays.len(), want.len());
    assert!(scan.has_intensity());
    for (ray, &(step, mm, intensity)) in scan.rays.iter().zip(&want) {
        assert_eq!(ray.angle, angle(200 + step));
        assert_eq!(ray.offset_ns, offset_ns(step));
        assert!(same_range(ray.range, metres(mm)));
        assert_eq!(ray.intensity, Some(intensity as f32));
    }
}

#[test]
fn hd_is_polled_after_bm_and_he_with_intensity() {
    let config = ScipConfig {
        scan: ScanCommand::Hd,
        start_step: Some(384),
        end_step: Some(387),
        cluster: 2,
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    assert_eq!(
        writes(&rig.bring_up()).last().map(String::as_str),
        Some("BM\n")
    );
    assert_eq!(writes(&rig.feed(b"BM\n00P\n\n")), ["HD0384038702\n"]);
    // Cluster 2: two values, steps 384 and 386; the second has 2 echoes.
    let stamp = rig.device_ms() - 100;
    let out = rig.feed(&hand_reply("HD0384038702", "00P", stamp, &["0@00A0&0B0"]));
    assert_eq!(out[0], DriverOutput::State(DeviceState::Streaming));
    let [scan] = scans(&out).try_into().expect("one scan");
    let got: Vec<(f32, u32, f32)> = scan
        .rays
        .iter()
        .map(|r| (r.angle, r.offset_ns, r.range))
        .collect();
    assert_eq!(
        got,
        [
            (angle(384), 0, 1.024),
            (angle(386), offset_ns(2), 1.088),
            (angle(386), offset_ns(2), 1.152)
        ]
    );
    assert_eq!(writes(&out), ["HD0384038702\n"], "the next HD follows");

    let config = ScipConfig {
        scan: ScanCommand::Hd,
        intensity: true,
        start_step: Some(384),
        end_step: Some(384),
        ..ScipConfig::default()
    };
    let mut rig = Rig::new(config);
    rig.bring_up();
    assert_eq!(writes(&rig.feed(b"BM\n00P\n\n")), ["HE0384038401\n"]);
}

/// `ND` data for 2 steps (0..=1), decoded.
fn decode_nd(data: &str) -> Result<ScanData, ScanDataError> {
    let request = ScanRequest {
        kind: ScanKind::Nd,
        start: 0,
        end: 1,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    let lines: Vec<Vec<u8>> = [hand_stamp(1).as_str(), data]
        .iter()
        .map(|body| hand_line(body).trim_end().as_bytes().to_vec())
        .collect();
    decode_scan(&lines, &request)
}

#[test]
fn malformed_multiecho_data_is_rejected_and_named() {
    let kind = |data: &str| decode_nd(data).map(|d| d.echoes).map_err(|e| e.kind());
    assert_eq!(
        kind("0@0&0A0&0B00C0"),
        Ok(Some(vec![3, 1])),
        "3 echoes is the most"
    );
    assert_eq!(
        kind("0@00C0&0A0&0B0"),
        Ok(Some(vec![1, 3])),
        "last step too"
    );
    let cases = [
        (
            "&0@00A0",
            ScanDataError::EchoBeforeFirstValue,
            "malformed_multiecho",
        ),
        (
            "0@0&0A0&0B0&0C00D0",
            ScanDataError::TooManyEchoes,
            "malformed_multiecho",
        ),
        (
            "0@00A0&",
            ScanDataError::DanglingEchoMark,
            "malformed_multiecho",
        ),
        (
            "0@00A0&0B",
            ScanDataError::DanglingEchoMark,
            "malformed_multiecho",
        ),
        (
            "0@0&&0A00B0",
            ScanDataError::DanglingEchoMark,
            "malformed_multiecho",
        ),
        (
            "0@0",
            ScanDataError::MissingSteps {
                expected: 2,
                got: 1,
            },
            "incomplete_scan",
        ),
        (
            "0@00A",
            ScanDataError::MissingSteps {
                expected: 2,
                got: 1,
            },
            "incomplete_scan",
        ),
        (
            "0@00A0&0B00C0",
            ScanDataError::ExtraData { expected: 2 },
            "malformed_reply",
        ),
        ("0@00A0&0p0", ScanDataError::BadCharacter, "malformed_reply"),
    ];
    for (data, error, name) in cases {
        let got = decode_nd(data).unwrap_err();
        assert_eq!(got, error, "{data}");
        assert_eq!(got.kind(), name, "{data}");
    }
    // `&` in a single-echo command's data is not a code character.
    let md = ScanRequest {
        kind: ScanKind::Md,
        start: 0,
        end: 1,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    let lines: Vec<Vec<u8>> = [hand_stamp(1).as_str(), "0@0&0A"]
        .iter()
        .map(|body| hand_line(body).trim_end().as_bytes().to_vec())
        .collect();
    assert_eq!(decode_scan(&lines, &md), Err(ScanDataError::BadCharacter));
}

#[test]
fn malformed_multiecho_scans_are_dropped_whole_and_counted() {
    let (mut rig, _) = rig_running(nd_config(44, 45), "ND0044004501000");
    let echo = "ND0044004501000";
    let stamp = rig.device_ms() - 100;
    for data in ["&0@00A0", "0@0&0A0&0B0&0C00D0", "0@00A0&"] {
        let out = rig.feed(&hand_reply(echo, "99b", stamp, &[data]));
        assert!(scans(&out).is_empty(), "{data}");
    }
    assert_eq!(rig.driver.stats().errors("malformed_multiecho"), 3);
    let out = rig.feed(&hand_reply(echo, "99b", stamp, &["0@0&0A00B0"]));
    assert_eq!(scans(&out)[0].rays.len(), 3, "the stream goes on");
    assert_eq!(rig.driver.stats().scans, 1);
}

#[test]
fn refused_nd_falls_back_to_md_and_is_asked_again_next_connect() {
    let mut rig = Rig::new(ScipConfig {
        scan: ScanCommand::Nd,
        ..ScipConfig::default()
    });
    let out = rig.bring_up();
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("ND0044072501000\n")
    );
    // The URG-04LX does not know ND: "0E" (undefined command).
    let out = rig.feed(b"ND0044072501000\n0Ee\n\n");
    assert_eq!(writes(&out), ["MD0044072501000\n"]);
    assert_eq!(rig.driver.stats().errors("multiecho_unsupported"), 1);
    assert_eq!(rig.driver.stats().errors("device_error_unsupported"), 1);
    let pairs = identity(&rig.feed(b"MD0044072501000\n00P\n\n")).unwrap();
    assert_eq!(
        identity_value(&pairs, "scan_command").as_deref(),
        Some("MD")
    );
    let note = identity_value(&pairs, "multiecho").unwrap();
    assert_eq!(
        note,
        "unsupported (ND rejected with status 0E (undefined command))"
    );
    assert_eq!(identity_value(&pairs, "intensity").as_deref(), Some("no"));
    let out = rig.feed(&rig.md_scan(120));
    assert_eq!(scans(&out)[0].rays.len(), 682);
    // Next connect: ND again.
    let out = rig.bring_up();
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("ND0044072501000\n")
    );
}

#[test]
fn refused_ne_falls_back_to_me_then_md() {
    let mut rig = Rig::new(ScipConfig {
        scan: ScanCommand::Nd,
        intensity: true,
        ..ScipConfig::default()
    });
    let out = rig.bring_up();
    assert_eq!(
        writes(&out).last().map(String::as_str),
        Some("NE0044072501000\n")
    );
    let out = rig.feed(b"NE0044072501000\n0Ee\n\n");
    assert_eq!(writes(&out), ["ME0044072501000\n"]);
    let out = rig.feed(b"ME0044072501000\n0Ee\n\n");
    assert_eq!(writes(&out), ["MD0044072501000\n"]);
    let stats = rig.driver.stats();
    assert_eq!(stats.errors("multiecho_unsupported"), 1);
    assert_eq!(stats.errors("intensity_unsupported"), 1);
    let pairs = identity(&rig.feed(b"MD0044072501000\n00P\n\n")).unwrap();
    assert!(identity_value(&pairs, "multiecho")
        .unwrap()
        .starts_with("unsupported (NE rejected"));
    assert!(identity_value(&pairs, "intensity")
        .unwrap()
        .starts_with("unsupported (ME rejected"));
    // A sensor that refuses MD too: nothing left to drop.
    let mut rig = Rig::new(ScipConfig {
        scan: ScanCommand::Nd,
        ..ScipConfig::default()
    });
    rig.bring_up();
    rig.feed(b"ND0044072501000\n0Ee\n\n");
    let out = rig.feed(b"MD0044072501000\n0Ee\n\n");
    assert_eq!(
        reconnect_reason(&out).as_deref(),
        Some("MD rejected with status 0E (undefined command)")
    );
}

#[test]
fn refused_hd_falls_back_to_gd() {
    let mut rig = Rig::new(ScipConfig {
        scan: ScanCommand::Hd,
        ..ScipConfig::default()
    });
    rig.bring_up();
    assert_eq!(writes(&rig.feed(b"BM\n00P\n\n")), ["HD0044072501\n"]);
    let out = rig.feed(b"HD0044072501\n0Ee\n\n");
    assert_eq!(writes(&out), ["GD0044072501\n"]);
    assert_eq!(rig.driver.stats().errors("multiecho_unsupported"), 1);
    let stamp = rig.device_ms() - 120;
    let gd = reply(
        "GD0044072501",
        "00",
        &scan_lines(stamp, &urg04lx_values(), 3),
    );
    let out = rig.feed(&gd);
    let pairs = identity(&out).unwrap();
    assert!(identity_value(&pairs, "multiecho")
        .unwrap()
        .starts_with("unsupported (HD rejected"));
    assert_eq!(scans(&out)[0].rays.len(), 682);
}

#[test]
fn multiecho_scan_kinds_and_limits() {
    use ScanKind::*;
    assert_eq!(
        [Nd, Ne, Hd, He].map(ScanKind::symbol),
        ["ND", "NE", "HD", "HE"]
    );
    assert_eq!(
        [Nd, Ne, Hd, He].map(ScanKind::is_streamed),
        [true, true, false, false]
    );
    assert_eq!(
        [Nd, Ne, Hd, He].map(ScanKind::without_multiecho),
        [Md, Me, Gd, Ge]
    );
    assert_eq!(
        [Nd, Ne, Hd, He].map(ScanKind::without_intensity),
        [Nd, Nd, Hd, Hd]
    );
    assert!(!Md.is_multiecho() && !Ge.is_multiecho());
    assert_eq!(Ne.max_step_chars(), 3 * 6 + 2);
    assert_eq!(Md.max_step_chars(), 3);
    // The largest possible NE reply fits the reply bound.
    let lines = (10_000 * Ne.max_step_chars()).div_ceil(64) + 2;
    assert!(lines <= MAX_REPLY_LINES, "{lines}");
    let nd = ScanRequest {
        kind: Nd,
        start: 44,
        end: 725,
        cluster: 1,
        interval: 0,
        scans: 0,
    };
    assert!(nd.matches_echo(b"ND0044072501099", None));
    assert!(!nd.matches_echo(b"MD0044072501000", None));
}
