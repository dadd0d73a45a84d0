//! CAN sensor protocol tests: round trips (direct, through SLCAN, through a
//! candump log), every error kind, and property tests.

use super::*;
use crate::{ErrorKind, IngestError, Scan};
use proptest::prelude::*;

fn scan(sequence: u32, n: usize) -> Scan {
    let points = (0..n)
        .map(|i| [i as f32 * 0.001, -(i as f32) * 0.002, 1.5])
        .collect();
    Scan::new(
        sequence,
        1_700_000_000_000_000_000 + u64::from(sequence),
        points,
    )
}

fn run(decoder: &mut CanScanDecoder, frames: &[CanFrame]) -> (Vec<Scan>, Vec<IngestError>) {
    let mut results: Vec<_> = frames.iter().flat_map(|f| decoder.push(f)).collect();
    results.extend(decoder.finish());
    let mut scans = Vec::new();
    let mut errors = Vec::new();
    for r in results {
        match r {
            Ok(s) => scans.push(s),
            Err(e) => errors.push(e),
        }
    }
    (scans, errors)
}

fn decode(frames: &[CanFrame]) -> (Vec<Scan>, Vec<IngestError>) {
    run(&mut CanScanDecoder::default(), frames)
}

fn kinds(errors: &[IngestError]) -> Vec<ErrorKind> {
    errors.iter().map(IngestError::kind).collect()
}

#[test]
fn scans_round_trip_with_standard_and_extended_ids() {
    for config in [
        CanSensorConfig::default(),
        CanSensorConfig {
            base_id: 0x18FF_0000,
            extended: true,
        },
    ] {
        let frames: Vec<_> = [scan(1, 0), scan(2, 1), scan(65_537, 100)]
            .iter()
            .flat_map(|s| config.encode(s).unwrap())
            .collect();
        assert_eq!(frames.len(), 3 + 4 + 103);
        assert!(frames
            .iter()
            .all(|f| f.len == 8 && f.extended == config.extended));
        let mut decoder = CanScanDecoder::new(config);
        let (scans, errors) = run(&mut decoder, &frames);
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(scans.len(), 3);
        assert_eq!(scans[2].sequence, 1, "the sequence travels modulo 2^16");
        assert_eq!(scans[2].stamp_ns, scan(65_537, 0).stamp_ns);
        for (a, b) in scan(1, 100)
            .points
            .iter()
            .flatten()
            .zip(scans[2].points.iter().flatten())
        {
            assert!((a - b).abs() <= 5e-4);
        }
        assert_eq!(decoder.stats().scans, 3);
        assert_eq!(decoder.stats().points, 101);
    }
}

#[test]
fn the_documented_frame_layout() {
    let frames = CanSensorConfig::default()
        .encode(&Scan::new(0x0102, 5, vec![[0.001, -0.002, 32.767]]))
        .unwrap();
    assert_eq!(frames[0].id, 0x300);
    assert_eq!(frames[0].data, [0x02, 0x01, 1, 0, CAN_VERSION, 0, 0, 0]);
    assert_eq!(frames[1].id, 0x301);
    assert_eq!(frames[1].data, 5u64.to_le_bytes());
    assert_eq!(frames[2].id, 0x302);
    assert_eq!(frames[2].data, [1, 0, 0xFE, 0xFF, 0xFF, 0x7F, 0, 0]);
    assert_eq!(frames[3].id, 0x303);
    let crc = crc32fast::hash(&[frames[0].data, frames[1].data, frames[2].data].concat());
    assert_eq!(frames[3].data[4..], crc.to_le_bytes());
    assert_eq!(frames[3].data[..4], [0x02, 0x01, 1, 0]);
}

#[test]
fn the_encoder_refuses_what_it_cannot_send() {
    let config = CanSensorConfig::default();
    assert!(matches!(
        config.encode(&Scan::new(0, 0, vec![[0.0, 0.0, 33.0]])),
        Err(IngestError::OutOfRange { field: "z", .. })
    ));
    assert!(matches!(
        config.encode(&Scan::new(0, 0, vec![[f32::NAN, 0.0, 0.0]])),
        Err(IngestError::NonFinite { field: "x", .. })
    ));
    assert!(matches!(
        config.encode(&scan(0, 65_536)),
        Err(IngestError::Oversize { .. })
    ));
    let bad_id = CanSensorConfig {
        base_id: 0x7FE,
        extended: false,
    };
    assert!(matches!(
        bad_id.encode(&scan(0, 1)),
        Err(IngestError::Malformed { .. })
    ));
}

#[test]
fn foreign_frames_are_unknown_ids_and_do_not_disturb_a_scan() {
    let mut frames = CanSensorConfig::default().encode(&scan(1, 5)).unwrap();
    frames.insert(3, CanFrame::new(0x100, false, &[1]).unwrap());
    frames.insert(4, CanFrame::new(0x300, true, &[0; 8]).unwrap());
    frames.insert(5, CanFrame::remote(0x302, false, 8).unwrap());
    let (scans, errors) = decode(&frames);
    assert_eq!(scans.len(), 1);
    assert_eq!(kinds(&errors), vec![ErrorKind::UnknownId; 3]);
    assert_eq!(
        errors[0],
        IngestError::UnknownId {
            id: 0x100,
            extended: false
        }
    );
}

#[test]
fn lost_and_reordered_frames_drop_their_scan_once() {
    let config = CanSensorConfig::default();
    let a = config.encode(&scan(1, 5)).unwrap();
    let b = config.encode(&scan(2, 5)).unwrap();
    let c = config.encode(&scan(3, 5)).unwrap();
    // scan 1 loses POINT 2 (frame 4); scan 2 swaps POINT 0 and 1; scan 3 is fine.
    let mut stream: Vec<CanFrame> = Vec::new();
    stream.extend(
        a.iter()
            .enumerate()
            .filter(|&(i, _)| i != 4)
            .map(|(_, f)| *f),
    );
    let mut swapped = b.clone();
    swapped.swap(2, 3);
    stream.extend(swapped);
    stream.extend(c);
    let mut decoder = CanScanDecoder::default();
    let (scans, errors) = run(&mut decoder, &stream);
    assert_eq!(
        scans.iter().map(|s| s.sequence).collect::<Vec<_>>(),
        vec![3]
    );
    assert_eq!(
        errors,
        vec![
            IngestError::MissingFrame {
                sequence: 1,
                expected: 4,
                found: 5
            },
            IngestError::MissingFrame {
                sequence: 2,
                expected: 2,
                found: 3
            },
        ]
    );
    // The rest of each lost scan was discarded quietly, END included.
    assert_eq!(decoder.stats().discarded_frames, 3 + 6);
    // A repeated frame is out of order.
    let mut repeated = a.clone();
    repeated.insert(3, a[2]);
    let (scans, errors) = decode(&repeated);
    assert!(scans.is_empty());
    assert_eq!(
        errors,
        vec![IngestError::OutOfOrder {
            sequence: 1,
            expected: 3,
            found: 2
        }]
    );
    // A lost STAMP.
    let (_, errors) = decode(&[a[0], a[2]]);
    assert_eq!(
        errors[0],
        IngestError::MissingFrame {
            sequence: 1,
            expected: 1,
            found: 2
        }
    );
}

#[test]
fn lost_starts_and_ends_are_counted() {
    let config = CanSensorConfig::default();
    let a = config.encode(&scan(1, 3)).unwrap();
    let b = config.encode(&scan(2, 3)).unwrap();
    let c = config.encode(&scan(3, 3)).unwrap();
    // scan 1 loses its END; scan 2 loses its START; scan 3 is fine. Scan 2's
    // STAMP is out of order for scan 1; its END shows that scan 2 was lost too.
    let stream = [&a[..a.len() - 1], &b[1..], &c[..]].concat();
    let (scans, errors) = decode(&stream);
    assert_eq!(scans.len(), 1);
    assert_eq!(scans[0].sequence, 3);
    assert_eq!(
        errors,
        vec![
            IngestError::OutOfOrder {
                sequence: 1,
                expected: 5,
                found: 1
            },
            IngestError::MissingFrame {
                sequence: 2,
                expected: 0,
                found: 5
            },
        ]
    );
    // With no scan in progress, a lost START shows at the first orphan frame.
    let (scans, errors) = decode(&[&b[1..], &c[..]].concat());
    assert_eq!(scans.len(), 1);
    assert_eq!(
        errors,
        vec![IngestError::MissingFrame {
            sequence: 0,
            expected: 0,
            found: 1
        }]
    );
    // An END of another scan ends the current one; the stream end does too.
    let (_, errors) = decode(&[&a[..a.len() - 1], &b[b.len() - 1..], &c[..2]].concat());
    assert_eq!(
        kinds(&errors),
        vec![ErrorKind::IncompleteScan, ErrorKind::IncompleteScan]
    );
}

#[test]
fn checksum_length_version_and_index_faults_are_named() {
    let config = CanSensorConfig::default();
    let a = config.encode(&scan(1, 3)).unwrap();
    let good = config.encode(&scan(2, 1)).unwrap();
    let edit = |i: usize, f: &dyn Fn(&mut CanFrame)| {
        let mut frames = a.clone();
        f(&mut frames[i]);
        [frames, good.clone()].concat()
    };
    let cases: [(Vec<CanFrame>, ErrorKind); 6] = [
        (edit(3, &|f| f.data[0] ^= 1), ErrorKind::BadChecksum),
        (edit(1, &|f| f.data[7] ^= 1), ErrorKind::BadChecksum),
        (edit(3, &|f| f.len = 6), ErrorKind::Malformed),
        (edit(0, &|f| f.data[4] = 2), ErrorKind::Version),
        (edit(3, &|f| f.data[6] = 9), ErrorKind::Malformed),
        (edit(5, &|f| f.data[2] = 4), ErrorKind::Malformed),
    ];
    for (frames, kind) in cases {
        let (scans, errors) = decode(&frames);
        assert_eq!(scans.len(), 1, "{kind:?}");
        assert_eq!(scans[0].sequence, 2);
        assert_eq!(kinds(&errors), vec![kind]);
    }
}

#[test]
fn scans_survive_slcan_and_candump_transport() {
    let config = CanSensorConfig::default();
    let frames: Vec<_> = (0..3)
        .flat_map(|s| config.encode(&scan(s, 20)).unwrap())
        .collect();
    let mut bytes = b"\x07garbage\rV1013\r".to_vec();
    for f in &frames {
        slcan::write_frame(f, &mut bytes);
    }
    let mut slcan = SlcanDecoder::default();
    let received: Vec<CanFrame> = bytes
        .chunks(13)
        .flat_map(|c| slcan.push(c))
        .filter_map(|m| match m {
            Ok(SlcanMessage::Frame { frame, .. }) => Some(frame),
            _ => None,
        })
        .collect();
    assert_eq!(received, frames);
    assert_eq!(slcan.stats().total_errors(), 2);
    let log: String = frames
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let record = CandumpRecord {
                stamp_ns: 1_700_000_000_000_000_000 + i as u64 * 1000,
                interface: "can0".into(),
                frame: *f,
            };
            format_candump_line(&record) + "\n"
        })
        .collect();
    let mut parser = CandumpParser::default();
    let parsed: Vec<CanFrame> = log
        .lines()
        .filter_map(|l| parser.push_line(l))
        .map(|r| r.unwrap().frame)
        .collect();
    assert_eq!(parsed, frames);
    let (scans, errors) = decode(&parsed);
    assert!(errors.is_empty());
    assert_eq!(scans.len(), 3);
}

fn arb_frame() -> impl Strategy<Value = CanFrame> {
    (0x2FEu32..0x306, any::<bool>(), 0u8..=8, any::<[u8; 8]>()).prop_map(|(id, ext, len, data)| {
        CanFrame {
            id,
            extended: ext && id % 3 == 0,
            remote: len == 3,
            len,
            data,
        }
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_frames_never_panic(frames in prop::collection::vec(arb_frame(), 0..300)) {
        let mut decoder = CanScanDecoder::default();
        for f in &frames {
            // Random frames essentially never form a valid scan, but if one
            // does, it is a scan with at most the u16 point limit.
            for scan in decoder.push(f).into_iter().flatten() {
                prop_assert!(scan.points.len() < 65_536);
            }
        }
        decoder.finish();
        prop_assert_eq!(decoder.stats().input, frames.len() as u64);
    }

    #[test]
    fn scans_among_random_frames_are_recovered(
        counts in prop::collection::vec(0usize..40, 1..5),
        noise in prop::collection::vec(prop::collection::vec(arb_frame(), 0..4), 1..20),
    ) {
        let config = CanSensorConfig { base_id: 0x400, extended: false };
        let mut stream = Vec::new();
        let mut noise = noise.iter().cycle();
        for (seq, &n) in counts.iter().enumerate() {
            // Noise only between scans: foreign ids (0x2FE..0x306) never collide with 0x400.
            stream.extend(noise.next().unwrap().iter().copied());
            stream.extend(config.encode(&scan(seq as u32, n)).unwrap());
        }
        let (scans, errors) = run(&mut CanScanDecoder::new(config), &stream);
        prop_assert_eq!(scans.len(), counts.len());
        prop_assert!(errors.iter().all(|e| e.kind() == ErrorKind::UnknownId));
    }

    #[test]
    fn slcan_random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..2000)) {
        let mut decoder = SlcanDecoder::default();
        let _ = decoder.push(&bytes);
    }

    #[test]
    fn candump_random_lines_never_panic(line in "[ -~]{0,60}", tail in "[0-9A-Fa-f#R.]{0,30}") {
        let _ = parse_candump_line(&line, 1);
        let _ = parse_candump_line(&format!("(1.5) can0 {tail}"), 1);
    }
}
