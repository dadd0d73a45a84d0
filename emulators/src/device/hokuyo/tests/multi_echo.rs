//! Tests of the UTM-30LX multi-echo commands HD/ND/HE/NE, read with a
//! test-side decoder written from urg_c's `receive_length_data()`
//! description: lines joined after their sums, a `&` starts a further echo
//! of the previous step.

use super::*;

/// One echo: range (mm) and intensity (0 for HD/ND).
type Echo = (u32, u32);

/// A decoded multi-echo scan message.
#[derive(Debug)]
struct MultiEchoScan {
    echo: Vec<u8>,
    status: Vec<u8>,
    timestamp: u32,
    /// Per output value, its echoes nearest first.
    steps: Vec<Vec<Echo>>,
    /// The data lines without their sums.
    lines: Vec<Vec<u8>>,
    bad_sums: usize,
}

/// Decodes a multi-echo scan message; `with_intensity` for HE/NE.
fn decode_multi_echo(message: &[Vec<u8>], with_intensity: bool) -> MultiEchoScan {
    let [echo, status, time, data @ ..] = message else {
        panic!("short scan message {message:?}");
    };
    let strip = |line: &Vec<u8>| {
        let (text, last) = line.split_at(line.len() - 1);
        (text.to_vec(), sum(text) == last[0])
    };
    let (status_text, status_ok) = strip(status);
    let (time_text, time_ok) = strip(time);
    assert!(status_ok && time_ok && time_text.len() == 4);
    let mut lines = Vec::new();
    let mut bad_sums = 0;
    for line in data {
        let (text, ok) = strip(line);
        assert!(!text.is_empty() && text.len() <= 64, "line {line:?}");
        bad_sums += usize::from(!ok);
        lines.push(text);
    }
    let joined = lines.concat();
    MultiEchoScan {
        echo: echo.clone(),
        status: status_text,
        timestamp: decode(&time_text),
        steps: split_echoes(&joined, with_intensity),
        lines,
        bad_sums,
    }
}

fn split_echoes(joined: &[u8], with_intensity: bool) -> Vec<Vec<Echo>> {
    let mut steps: Vec<Vec<Echo>> = Vec::new();
    let mut rest = joined;
    while !rest.is_empty() {
        let further = rest[0] == b'&';
        if further {
            rest = &rest[1..];
        }
        let range = decode(&rest[..3]);
        let intensity = if with_intensity {
            decode(&rest[3..6])
        } else {
            0
        };
        rest = &rest[if with_intensity { 6 } else { 3 }..];
        if further {
            steps
                .last_mut()
                .expect("& before any step")
                .push((range, intensity));
        } else {
            steps.push(vec![(range, intensity)]);
        }
    }
    steps
}

fn utm(options: HokuyoOptions) -> HokuyoEmulator {
    sensor(HokuyoModel::Utm30lx, options)
}

/// Exact ranges, every echo followed by another.
fn always_three() -> HokuyoOptions {
    HokuyoOptions {
        multi_echo_fraction: 1.0,
        ..exact()
    }
}

/// The first stream scan of `command` on a fresh UTM-30LX.
fn first_scan(options: HokuyoOptions, command: &[u8], with_intensity: bool) -> MultiEchoScan {
    let mut emu = utm(options);
    exchange(&mut emu, command, 0.0);
    decode_multi_echo(&messages(&poll(&mut emu, 0.024))[0], with_intensity)
}

fn ranges(step: &[Echo]) -> Vec<u32> {
    step.iter().map(|&(range, _)| range).collect()
}

const UTM_DMAX: u32 = 60_000;

// ----------------------------------------------------------- data format

#[test]
fn without_further_echoes_nd_sends_md_data() {
    let options = HokuyoOptions {
        multi_echo_fraction: 0.0,
        ..HokuyoOptions::default()
    };
    let mut md = utm(options.clone());
    let mut nd = utm(options);
    exchange(&mut md, b"MD0000108001000\n", 0.0);
    exchange(&mut nd, b"ND0000108001000\n", 0.0);
    let md_all = messages(&poll(&mut md, 0.2));
    let nd_all = messages(&poll(&mut nd, 0.2));
    assert_eq!(nd_all.len(), 8);
    for (m, n) in md_all.iter().zip(&nd_all) {
        assert_eq!(n[0], b"ND0000108001000");
        assert_eq!(m[1..], n[1..], "status, timestamp and data as MD");
    }
}

#[test]
fn first_echoes_are_what_md_reads() {
    // Same seed and noise: the further echoes draw from their own stream.
    let options = HokuyoOptions {
        multi_echo_fraction: 0.3,
        seed: 11,
        ..HokuyoOptions::default()
    };
    let mut md = utm(options.clone());
    let mut nd = utm(options);
    exchange(&mut md, b"MD0000108002000\n", 0.0);
    exchange(&mut nd, b"ND0000108002000\n", 0.0);
    let md_scans = messages(&poll(&mut md, 0.1));
    let nd_scans = messages(&poll(&mut nd, 0.1));
    assert_eq!(nd_scans.len(), 4);
    let mut further = 0;
    for (m, n) in md_scans.iter().zip(&nd_scans) {
        let md_values = decode_scan(m, 3).values;
        let nd_scan = decode_multi_echo(n, false);
        let firsts: Vec<u32> = nd_scan.steps.iter().map(|s| s[0].0).collect();
        assert_eq!(firsts, md_values);
        further += nd_scan.steps.iter().map(|s| s.len() - 1).sum::<usize>();
    }
    assert!(further > 0, "a fraction of 0.3 shows further echoes");
}

#[test]
fn further_echoes_lie_0_3_to_2_m_behind_within_dmax() {
    let scan = first_scan(always_three(), b"ND0000108001000\n", false);
    assert_eq!(scan.status, b"99");
    assert_eq!(scan.timestamp, at_rear(0, UTM_REAR_US));
    assert_eq!(scan.steps.len(), 1081);
    assert_eq!(ranges(&scan.steps[540])[0], 1000);
    for (step, echoes) in scan.steps.iter().enumerate() {
        let r = ranges(echoes);
        assert!(r.len() <= 3, "step {step}: {r:?}");
        if r[0] < 23 {
            assert_eq!(r.len(), 1, "step {step}: an error code has no further echo");
            continue;
        }
        if r[0] <= UTM_DMAX - 2 * 2000 {
            assert_eq!(r.len(), 3, "step {step}: {r:?}");
        }
        for pair in r.windows(2) {
            let gap = pair[1] - pair[0];
            assert!((300..=2000).contains(&gap), "step {step}: {r:?}");
        }
        assert!(r.iter().all(|&mm| mm <= UTM_DMAX));
    }
}

#[test]
fn no_further_echo_beyond_dmax() {
    // The front step reads 59.9 m: nothing fits 0.3 m behind it.
    let mut emu = sensor_at(HokuyoModel::Utm30lx, always_three(), 59.9);
    exchange(&mut emu, b"BM\n", 0.0);
    let all = messages(&exchange(&mut emu, b"HD0540054000\n", 0.1));
    let scan = decode_multi_echo(&all[0], false);
    assert_eq!(scan.status, b"00");
    assert_eq!(scan.steps, [vec![(59_900, 0)]]);
}

#[test]
fn an_echo_mark_may_end_a_data_line() {
    let scan = first_scan(always_three(), b"ND0000108001000\n", false);
    let ends_with_mark = scan
        .lines
        .iter()
        .position(|line| line.last() == Some(&b'&'))
        .expect("a 64-character cut falls just after some '&'");
    // Its value starts the next line, and the decoder joins them.
    let next = &scan.lines[ends_with_mark + 1];
    assert_ne!(next[0], b'&');
    assert!(scan.lines[..scan.lines.len() - 1]
        .iter()
        .all(|line| line.len() == 64));
    assert_eq!(scan.steps.len(), 1081);
}

#[test]
fn a_value_may_straddle_a_line_after_its_mark() {
    // "&" + 3 characters split as "&v" / "vv" or "&vv" / "v".
    let scan = first_scan(always_three(), b"ND0000108001000\n", false);
    let joined = scan.lines.concat();
    let cut_inside = (1..scan.lines.len()).any(|k| {
        let at = 64 * k;
        (at >= 2 && joined[at - 2] == b'&') || (at >= 3 && joined[at - 3] == b'&')
    });
    assert!(cut_inside);
}

#[test]
fn ne_sends_an_intensity_with_every_echo() {
    // The wall reflects 0.5: the first echo reads 5000 (ME's scale).
    let scan = first_scan(always_three(), b"NE0540054000001\n", true);
    assert_eq!(scan.echo, b"NE0540054000000");
    let [step] = scan.steps.as_slice() else {
        panic!("{:?}", scan.steps);
    };
    assert_eq!(step.len(), 3);
    assert_eq!(step[0], (1000, 5000));
    for pair in step.windows(2) {
        let (before, after) = (f64::from(pair[0].1), f64::from(pair[1].1));
        assert!(after >= (0.2 * before).floor() && after <= (0.8 * before).ceil());
        assert!(pair[1].0 > pair[0].0);
    }
    // 6 characters per echo and one '&' per further echo.
    assert_eq!(scan.lines.concat().len(), 3 * 6 + 2);
}

#[test]
fn he_and_hd_answer_one_scan_with_the_laser_on() {
    let mut emu = utm(always_three());
    assert_eq!(
        exchange(&mut emu, b"HD0540054000\n", 0.1),
        b"HD0540054000\n10Q\n\n"
    );
    exchange(&mut emu, b"BM\n", 0.1);
    let all = messages(&exchange(&mut emu, b"HE0539054100\n", 0.2));
    let scan = decode_multi_echo(&all[0], true);
    assert_eq!(
        (scan.echo.as_slice(), scan.status.as_slice()),
        (&b"HE0539054100"[..], &b"00"[..])
    );
    assert_eq!(scan.steps.len(), 3);
    assert_eq!(scan.steps[1][0], (1000, 5000));
    assert!(scan.steps.iter().all(|s| s.len() == 3));
}

#[test]
fn clusters_carry_the_echoes_of_their_nearest_step() {
    let scan = first_scan(always_three(), b"ND0530055005000\n", false);
    // 21 steps in clusters of 5: 5 values, the middle one the front step.
    assert_eq!(scan.steps.len(), 5);
    assert_eq!(scan.steps[2][0].0, 1000);
    assert!(scan.steps.iter().all(|s| s.len() == 3));
}

// ------------------------------------------------------ commands, states

#[test]
fn multi_echo_is_undefined_on_the_urg_04lx() {
    let mut emu = urg();
    for command in [
        "HD0044072501",
        "ND0044072501000",
        "HE0044072501",
        "NE0044072501000",
    ] {
        let reply = exchange(&mut emu, format!("{command}\n").as_bytes(), 0.5);
        assert_eq!(text(&reply), format!("{command}\n0Ee\n\n"));
    }
    assert_eq!(emu.stats().rejected(Rejection::UnknownCommand), 4);
    assert!(!emu.sensor.laser_on);
}

#[test]
fn hs_and_ns_are_not_scan_commands() {
    // HS is the sensitivity command (spec §8.9), not emulated; no NS exists.
    let mut emu = utm(exact());
    for command in ["HS0000108001", "NS0000108001000"] {
        let reply = exchange(&mut emu, format!("{command}\n").as_bytes(), 0.5);
        assert_eq!(text(&reply), format!("{command}\n0Ee\n\n"));
    }
}

#[test]
fn multi_echo_parameters_are_checked_as_md_and_gd() {
    let cases: [(&[u8], &[u8]); 16] = [
        (b"ND000010800100", b"0C"),
        (b"ND00001080010000", b"0D"),
        (b"NDx000108001000", b"01"),
        (b"ND0000x08001000", b"02"),
        (b"ND000010800x000", b"03"),
        (b"ND0000108101000", b"04"),
        (b"ND0500040001000", b"05"),
        (b"ND0000108001x00", b"06"),
        (b"ND00001080010x0", b"07"),
        (b"NE0000108001x00", b"06"),
        (b"ND0000108001000;a-b", b"0H"),
        (b"HD000010800", b"0C"),
        (b"HD0000108101", b"04"),
        (b"HE0500040001", b"05"),
        (b"HD000010800x", b"03"),
        (b"HE00001080010", b"0D"),
    ];
    for (command, status) in cases {
        let mut emu = utm(exact());
        let mut line = command.to_vec();
        line.push(b'\n');
        let mut expected = command.to_vec();
        expected.push(b'\n');
        expected.extend_from_slice(status);
        expected.push(sum(status));
        expected.extend_from_slice(b"\n\n");
        assert_eq!(text(&exchange(&mut emu, &line, 0.5)), text(&expected));
        assert!(
            poll(&mut emu, 1.0).is_empty(),
            "{} streams nothing",
            text(command)
        );
    }
}

#[test]
fn nd_counts_down_then_stops_the_laser() {
    let mut emu = utm(always_three());
    assert_eq!(
        exchange(&mut emu, b"ND0540054001103;ab\n", 0.0),
        b"ND0540054001103;ab\n00P\n\n"
    );
    let all = messages(&poll(&mut emu, 1.0));
    let scans: Vec<MultiEchoScan> = all.iter().map(|m| decode_multi_echo(m, false)).collect();
    let echoes: Vec<String> = scans.iter().map(|s| text(&s.echo)).collect();
    assert_eq!(
        echoes,
        [
            "ND0540054001102;ab",
            "ND0540054001101;ab",
            "ND0540054001100;ab"
        ]
    );
    // Interval 1 at 40 Hz: every other 25 ms revolution.
    let stamps: Vec<u32> = scans.iter().map(|s| s.timestamp).collect();
    assert_eq!(stamps, [0, 50, 100].map(|ms| at_rear(ms, UTM_REAR_US)));
    assert!(scans
        .iter()
        .all(|s| s.status == b"99" && s.steps.len() == 1));
    assert_eq!(
        exchange(&mut emu, b"HD0540054000\n", 1.1),
        b"HD0540054000\n10Q\n\n"
    );
}

#[test]
fn qt_stops_an_nd_stream() {
    let mut emu = utm(exact());
    exchange(&mut emu, b"NE0000108001000\n", 0.0);
    assert_eq!(messages(&poll(&mut emu, 0.1)).len(), 4);
    assert_eq!(exchange(&mut emu, b"QT\n", 0.1), b"QT\n00P\n\n");
    assert!(poll(&mut emu, 1.0).is_empty());
}

// ------------------------------------------------------------------ faults

/// The first `count` scans of an ND stream, each polled on its own.
fn nd_scans_one_by_one(options: HokuyoOptions, count: usize) -> Vec<Vec<u8>> {
    let mut emu = utm(options);
    exchange(&mut emu, b"ND0000108001000\n", 0.0);
    // Scan k is ready at 25 k + 18.8 ms.
    (0..count)
        .map(|k| poll(&mut emu, 0.025 * k as f64 + 0.022))
        .collect()
}

#[test]
fn corrupt_every_spoils_multi_echo_scans_too() {
    let options = HokuyoOptions {
        faults: Faults {
            corrupt_every: 2,
            ..Faults::default()
        },
        ..always_three()
    };
    let bad: Vec<usize> = nd_scans_one_by_one(options, 6)
        .iter()
        .map(|bytes| decode_multi_echo(&messages(bytes)[0], false).bad_sums)
        .collect();
    assert_eq!(bad, [0, 1, 0, 1, 0, 1]);
}

#[test]
fn garbage_every_prefixes_multi_echo_scans_too() {
    let clean = nd_scans_one_by_one(always_three(), 4);
    let options = HokuyoOptions {
        faults: Faults {
            garbage_every: 2,
            seed: 3,
            ..Faults::default()
        },
        ..always_three()
    };
    let dirty = nd_scans_one_by_one(options, 4);
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

// ------------------------------------------------------------- properties

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn multi_echo_scans_always_decode(
        seed in any::<u64>(),
        fraction in prop::num::f64::ANY,
        distance in 0.01f64..80.0,
        start in 0u32..=1080,
        len in 0u32..=1080,
        cluster in 0u32..=99,
        intensity in any::<bool>(),
    ) {
        let end = (start + len).min(1080);
        let options = HokuyoOptions {
            seed,
            multi_echo_fraction: fraction,
            dropout_probability: 0.05,
            ..HokuyoOptions::default()
        };
        let mut emu = sensor_at(HokuyoModel::Utm30lx, options, distance);
        let symbol = if intensity { "NE" } else { "ND" };
        let command = format!("{symbol}{start:04}{end:04}{cluster:02}000\n");
        exchange(&mut emu, command.as_bytes(), 0.0);
        let all = messages(&poll(&mut emu, 0.06));
        prop_assert_eq!(all.len(), 2);
        let values = (end - start + 1).div_ceil(cluster.max(1)) as usize;
        for message in &all {
            let scan = decode_multi_echo(message, intensity);
            prop_assert_eq!(scan.bad_sums, 0);
            prop_assert_eq!(scan.steps.len(), values);
            for step in &scan.steps {
                let r = ranges(step);
                prop_assert!(!r.is_empty() && r.len() <= 3);
                prop_assert!(r.windows(2).all(|p| p[0] >= 23 && p[1] > p[0]));
                prop_assert!(r.iter().all(|&mm| mm <= UTM_DMAX));
            }
        }
    }
}
