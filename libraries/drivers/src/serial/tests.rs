//! Serial protocol tests: round trips, every corruption kind, resynchronisation,
//! and property tests over random garbage and chunking.

use super::*;
use crate::{DecoderStats, ErrorKind, IngestError, Scan};
use proptest::prelude::*;

fn scan(sequence: u32, n: usize) -> Scan {
    let points = (0..n)
        .map(|i| {
            let t = i as f32 * 0.37;
            [t.sin() * 3.0, t.cos() * 2.0, 0.001 * i as f32]
        })
        .collect();
    Scan::new(
        sequence,
        1_700_000_000_000_000_000 + u64::from(sequence),
        points,
    )
}

fn decode_all(bytes: &[u8]) -> (Vec<Scan>, Vec<IngestError>, DecoderStats) {
    let mut decoder = SerialScanDecoder::default();
    let mut results = decoder.push(bytes);
    results.extend(decoder.finish());
    let (mut scans, mut errors) = (Vec::new(), Vec::new());
    for r in results {
        match r {
            Ok(s) => scans.push(s),
            Err(e) => errors.push(e),
        }
    }
    (scans, errors, *decoder.stats())
}

/// Rewrites both checksums of a frame after a test edited it.
fn reseal(frame: &mut [u8]) {
    let crc = crc16(&frame[..22]);
    frame[22..24].copy_from_slice(&crc.to_le_bytes());
    let body = frame.len() - 4;
    let crc = crc32fast::hash(&frame[..body]);
    frame[body..].copy_from_slice(&crc.to_le_bytes());
}

fn kinds(errors: &[IngestError]) -> Vec<ErrorKind> {
    errors.iter().map(IngestError::kind).collect()
}

#[test]
fn scans_round_trip_in_every_encoding_and_chunking() {
    let mut with_intensity = scan(7, 1000);
    with_intensity.intensity = Some((0..1000).map(|i| (i * 60) as f32).collect());
    for encoding in [
        PointEncoding::F32Metres,
        PointEncoding::I32Millimetres,
        PointEncoding::I16Millimetres,
    ] {
        for original in [
            scan(1, 0),
            scan(2, 1),
            scan(3, 256),
            scan(4, 257),
            with_intensity.clone(),
        ] {
            let encoder = SerialEncoder::new(encoding, 256);
            let bytes = encoder.encode(&original).unwrap();
            let frames = encoder.frames(&original).unwrap();
            assert_eq!(frames.len(), original.points.len().div_ceil(256).max(1));
            for chunk in [1, 7, 4096] {
                let mut decoder = SerialScanDecoder::default();
                let results: Vec<_> = bytes.chunks(chunk).flat_map(|c| decoder.push(c)).collect();
                assert_eq!(results.len(), 1, "{encoding:?} chunk {chunk}");
                let back = results.into_iter().next().unwrap().unwrap();
                assert_eq!(back.sequence, original.sequence);
                assert_eq!(back.stamp_ns, original.stamp_ns);
                assert_eq!(back.intensity, original.intensity);
                assert_eq!(back.points.len(), original.points.len());
                let tol = if encoding == PointEncoding::F32Metres {
                    0.0
                } else {
                    5e-4
                };
                for (a, b) in original
                    .points
                    .iter()
                    .flatten()
                    .zip(back.points.iter().flatten())
                {
                    assert!((a - b).abs() <= tol);
                }
                assert_eq!(decoder.stats().total_errors(), 0);
                assert_eq!(decoder.stats().scans, 1);
                assert_eq!(decoder.stats().input, bytes.len() as u64);
            }
        }
    }
}

#[test]
fn the_encoder_refuses_what_it_cannot_send() {
    let mut bad = scan(1, 3);
    bad.points[1][2] = f32::NAN;
    let e = SerialEncoder::default().encode(&bad);
    assert!(matches!(
        e,
        Err(IngestError::NonFinite {
            field: "z",
            index: 1
        })
    ));
    let far = Scan::new(1, 0, vec![[40.0, 0.0, 0.0]]);
    let e = SerialEncoder::new(PointEncoding::I16Millimetres, 10).encode(&far);
    assert!(matches!(e, Err(IngestError::OutOfRange { .. })));
    let mut mismatched = scan(1, 3);
    mismatched.intensity = Some(vec![1.0]);
    assert!(matches!(
        SerialEncoder::default().encode(&mismatched),
        Err(IngestError::Malformed { .. })
    ));
    for ppf in [0, 1025] {
        assert!(matches!(
            SerialEncoder::new(PointEncoding::F32Metres, ppf).encode(&scan(1, 3)),
            Err(IngestError::Oversize { .. })
        ));
    }
    let e = SerialEncoder::new(PointEncoding::I16Millimetres, 1).encode(&scan(1, 70_000));
    assert!(matches!(
        e,
        Err(IngestError::Oversize {
            what: "frames in a scan",
            ..
        })
    ));
}

#[test]
fn garbage_before_and_between_frames_is_skipped_and_counted_once() {
    let a = SerialEncoder::default().encode(&scan(1, 10)).unwrap();
    let b = SerialEncoder::default().encode(&scan(2, 10)).unwrap();
    let bytes = [&b"hello\x00\xA5"[..], &a, b"\xA5\xA5junk\x5A", &b].concat();
    let (scans, errors, stats) = decode_all(&bytes);
    assert_eq!(scans, vec![scan(1, 10), scan(2, 10)]);
    assert_eq!(kinds(&errors), vec![ErrorKind::Garbage, ErrorKind::Garbage]);
    assert_eq!(errors[0], IngestError::Garbage { bytes: 7 });
    assert_eq!(stats.skipped_bytes, 7 + 7);
}

#[test]
fn a_bad_header_crc_is_named_and_the_next_scan_survives() {
    let mut a = SerialEncoder::default().encode(&scan(1, 10)).unwrap();
    a[5] ^= 0x40;
    let b = SerialEncoder::default().encode(&scan(2, 10)).unwrap();
    let (scans, errors, stats) = decode_all(&[a, b].concat());
    assert_eq!(scans, vec![scan(2, 10)]);
    assert_eq!(kinds(&errors), vec![ErrorKind::BadHeaderCrc]);
    assert_eq!(stats.errors(ErrorKind::BadHeaderCrc), 1);
}

#[test]
fn a_corrupted_payload_drops_its_scan_with_one_bad_crc() {
    let encoder = SerialEncoder::new(PointEncoding::I16Millimetres, 4);
    let mut a = encoder.frames(&scan(1, 12)).unwrap();
    a[1][30] ^= 0x01;
    let b = encoder.encode(&scan(2, 5)).unwrap();
    let (scans, errors, stats) = decode_all(&[a.concat(), b].concat());
    assert_eq!(scans.len(), 1);
    assert_eq!(scans[0].sequence, 2);
    assert_eq!(kinds(&errors), vec![ErrorKind::BadCrc]);
    // The third frame of scan 1 is valid but its scan is lost.
    assert_eq!(stats.discarded_frames, 1);
    assert_eq!(stats.frames, 2 + 2);
}

#[test]
fn a_frame_cut_short_by_the_next_is_truncated() {
    let encoder = SerialEncoder::new(PointEncoding::F32Metres, 8);
    let a = encoder.encode(&scan(1, 8)).unwrap();
    let b = encoder.encode(&scan(2, 8)).unwrap();
    let bytes = [&a[..a.len() - 20], &b].concat();
    let (scans, errors, _) = decode_all(&bytes);
    assert_eq!(scans, vec![scan(2, 8)]);
    assert_eq!(
        errors,
        vec![IngestError::Truncated {
            got: a.len() - 20,
            expected: a.len()
        }]
    );
    // At the end of the stream, a partial frame is truncated too.
    let (scans, errors, stats) = decode_all(&a[..a.len() - 1]);
    assert!(scans.is_empty());
    assert_eq!(kinds(&errors), vec![ErrorKind::Truncated]);
    assert_eq!(stats.skipped_bytes, a.len() as u64 - 1);
}

#[test]
fn oversize_version_and_flag_faults_are_named() {
    let one = SerialEncoder::default().encode(&scan(1, 1)).unwrap();
    let good = SerialEncoder::default().encode(&scan(2, 3)).unwrap();
    for (offset, value, kind) in [
        (20usize, 0x0401u16, ErrorKind::Oversize),
        (2, 0x0102, ErrorKind::Version),
        (2, 0x4001, ErrorKind::Malformed),
    ] {
        let mut bad = one.clone();
        bad[offset..offset + 2].copy_from_slice(&value.to_le_bytes());
        reseal(&mut bad);
        let (scans, errors, stats) = decode_all(&[bad, good.clone()].concat());
        assert_eq!(scans, vec![scan(2, 3)], "{kind:?}");
        assert_eq!(kinds(&errors), vec![kind]);
        assert_eq!(stats.errors(kind), 1);
    }
}

#[test]
fn non_finite_points_drop_their_scan() {
    let encoder = SerialEncoder::new(PointEncoding::F32Metres, 2);
    let mut frames = encoder.frames(&scan(1, 6)).unwrap();
    frames[0][24 + 4..24 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    reseal(&mut frames[0]);
    let good = encoder.encode(&scan(2, 2)).unwrap();
    let (scans, errors, stats) = decode_all(&[frames.concat(), good].concat());
    assert_eq!(scans, vec![scan(2, 2)]);
    assert_eq!(
        errors,
        vec![IngestError::NonFinite {
            field: "y",
            index: 0
        }]
    );
    assert_eq!(stats.discarded_frames, 2);
}

#[test]
fn lost_reordered_and_unfinished_scans_are_counted() {
    let encoder = SerialEncoder::new(PointEncoding::I32Millimetres, 1);
    let f = |seq| encoder.frames(&scan(seq, 3)).unwrap();
    let (a, b, c, d, e) = (f(1), f(2), f(3), f(4), f(5));
    let stream = [
        // scan 1 misses its middle frame
        a[0].clone(),
        a[2].clone(),
        // scan 2 has two frames swapped
        b[0].clone(),
        b[2].clone(),
        b[1].clone(),
        // scan 3 never sends its last frame before scan 4 starts
        c[0].clone(),
        c[1].clone(),
        d[0].clone(),
        d[1].clone(),
        d[2].clone(),
        // scan 5 arrives without its first frame; then a stream end mid-scan
        e[1].clone(),
        e[2].clone(),
        a[0].clone(),
    ]
    .concat();
    let (scans, errors, stats) = decode_all(&stream);
    assert_eq!(
        scans.iter().map(|s| s.sequence).collect::<Vec<_>>(),
        vec![4]
    );
    assert_eq!(
        kinds(&errors),
        vec![
            ErrorKind::MissingFrame,
            ErrorKind::MissingFrame,
            ErrorKind::IncompleteScan,
            ErrorKind::MissingFrame,
            ErrorKind::IncompleteScan,
        ]
    );
    assert_eq!(
        errors[1],
        IngestError::MissingFrame {
            sequence: 2,
            expected: 1,
            found: 2
        }
    );
    assert_eq!(stats.discarded_frames, 1 + 2 + 2);
    // A repeated frame is out of order.
    let (_, errors, _) = decode_all(&[a[0].clone(), a[1].clone(), a[1].clone()].concat());
    assert_eq!(
        errors[0],
        IngestError::OutOfOrder {
            sequence: 1,
            expected: 2,
            found: 1
        }
    );
}

#[test]
fn frames_disagreeing_with_their_scan_are_malformed() {
    let encoder = SerialEncoder::new(PointEncoding::F32Metres, 1);
    let mut frames = encoder.frames(&scan(1, 2)).unwrap();
    frames[1][8] ^= 1; // another stamp
    reseal(&mut frames[1]);
    let (scans, errors, _) = decode_all(&frames.concat());
    assert!(scans.is_empty());
    assert_eq!(kinds(&errors), vec![ErrorKind::Malformed]);
}

#[test]
fn scans_beyond_the_limit_are_oversize() {
    let bytes = SerialEncoder::new(PointEncoding::F32Metres, 10)
        .encode(&scan(1, 25))
        .unwrap();
    let mut decoder = SerialScanDecoder::new(DecoderConfig {
        max_scan_points: 20,
    });
    let results = decoder.push(&bytes);
    assert_eq!(results.len(), 1);
    assert!(matches!(
        results[0],
        Err(IngestError::Oversize {
            what: "points in a scan",
            found: 25,
            limit: 20
        })
    ));
}

#[test]
fn the_decoder_starts_afresh_after_finish() {
    let bytes = SerialEncoder::default().encode(&scan(1, 300)).unwrap();
    let mut decoder = SerialScanDecoder::default();
    assert!(decoder.push(&bytes[..100]).is_empty());
    let ended = decoder.finish();
    assert_eq!(ended.len(), 1);
    assert!(matches!(ended[0], Err(IngestError::Truncated { .. })));
    let results = decoder.push(&bytes);
    assert_eq!(results, vec![Ok(scan(1, 300))]);
}

fn arb_scan() -> impl Strategy<Value = Scan> {
    (
        any::<u32>(),
        any::<u64>(),
        prop::collection::vec(prop::array::uniform3(-30.0f32..30.0), 0..300),
        any::<bool>(),
    )
        .prop_map(|(sequence, stamp_ns, points, with_intensity)| {
            let intensity =
                with_intensity.then(|| (0..points.len()).map(|i| (i % 999) as f32).collect());
            Scan {
                sequence,
                stamp_ns,
                points,
                intensity,
                channels: Vec::new(),
            }
        })
}

fn arb_encoder() -> impl Strategy<Value = SerialEncoder> {
    (0u8..3, 1usize..200)
        .prop_map(|(bits, ppf)| SerialEncoder::new(PointEncoding::from_bits(bits).unwrap(), ppf))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_garbage_never_panics(
        garbage in prop::collection::vec(any::<u8>(), 0..4000),
        chunk in 1usize..600,
    ) {
        let mut decoder = SerialScanDecoder::default();
        for c in garbage.chunks(chunk) {
            for r in decoder.push(c) {
                prop_assert!(r.is_err());
            }
        }
        decoder.finish();
        prop_assert_eq!(decoder.stats().skipped_bytes, garbage.len() as u64);
    }

    #[test]
    fn garbage_with_sync_words_never_panics(
        pieces in prop::collection::vec((any::<bool>(), prop::collection::vec(any::<u8>(), 0..40)), 0..60),
    ) {
        // Garbage dense in sync words and plausible headers.
        let mut bytes = Vec::new();
        for (sync, rest) in pieces {
            if sync { bytes.extend_from_slice(&[0xA5, 0x5A, 1]); }
            bytes.extend_from_slice(&rest);
        }
        let mut decoder = SerialScanDecoder::default();
        let _ = decoder.push(&bytes);
        let _ = decoder.finish();
    }

    #[test]
    fn valid_frames_in_garbage_are_all_recovered(
        scans in prop::collection::vec((arb_scan(), arb_encoder()), 1..6),
        garbage in prop::collection::vec(prop::collection::vec(any::<u8>(), 0..80), 1..40),
        chunk in 1usize..3000,
    ) {
        let mut stream = Vec::new();
        let mut expected = Vec::new();
        let mut garbage_len = 0;
        let mut g = garbage.iter().cycle();
        for (scan, encoder) in &scans {
            // What a clean channel delivers (quantised by the encoding).
            let clean = decode_all(&encoder.encode(scan).unwrap()).0;
            prop_assert_eq!(clean.len(), 1);
            expected.push(clean[0].clone());
            for frame in encoder.frames(scan).unwrap() {
                let junk = g.next().unwrap();
                garbage_len += junk.len();
                stream.extend_from_slice(junk);
                stream.extend_from_slice(&frame);
            }
        }
        let mut decoder = SerialScanDecoder::default();
        let mut got = Vec::new();
        for c in stream.chunks(chunk) {
            got.extend(decoder.push(c).into_iter().filter_map(Result::ok));
        }
        got.extend(decoder.finish().into_iter().filter_map(Result::ok));
        prop_assert_eq!(got, expected);
        prop_assert_eq!(decoder.stats().skipped_bytes, garbage_len as u64);
        prop_assert_eq!(decoder.stats().errors(ErrorKind::MissingFrame), 0);
    }

    #[test]
    fn a_flipped_byte_never_yields_a_wrong_scan(
        scan in arb_scan(),
        encoder in arb_encoder(),
        at in any::<prop::sample::Index>(),
        flip in 1u8..=255,
    ) {
        let clean = decode_all(&encoder.encode(&scan).unwrap()).0;
        let mut bytes = encoder.encode(&scan).unwrap();
        let i = at.index(bytes.len());
        bytes[i] ^= flip;
        let (scans, errors, _) = decode_all(&bytes);
        prop_assert!(scans.is_empty(), "{:?} survived, clean {:?}", scans, clean);
        prop_assert!(!errors.is_empty());
    }
}
