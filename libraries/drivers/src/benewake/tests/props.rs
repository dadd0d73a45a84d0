//! Property tests: arbitrary input never panics and never grows the buffer;
//! chunking never changes what a valid stream decodes to; mutated streams
//! never yield a reading from a frame whose sum failed. Plus a seeded soak
//! of frames, noise and corruption with exact expected counts.

use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use super::support::{frame, Bench};
use crate::benewake::{
    encode_frame, BenewakeConfig, BenewakeModel, DataFrame, Decoded, Decoder, Packet,
    COMMAND_HEADER, FRAME_HEADER, FRAME_LEN, MAX_COMMAND_FRAME_LEN,
};
use crate::device::{DeviceDriver, DriverOutput};

/// One item of a valid stream.
#[derive(Debug, Clone)]
enum Item {
    Frame(u16, u16, u16),
    Reply(u8, Vec<u8>),
}

fn item() -> impl Strategy<Value = Item> {
    prop_oneof![
        4 => (any::<u16>(), any::<u16>(), any::<u16>()).prop_map(|(d, s, t)| Item::Frame(d, s, t)),
        1 => (any::<u8>(), prop::collection::vec(any::<u8>(), 0..=12))
            .prop_map(|(id, payload)| Item::Reply(id, payload)),
    ]
}

fn stream_of(items: &[Item]) -> Vec<u8> {
    items
        .iter()
        .flat_map(|item| match item {
            Item::Frame(d, s, t) => frame(*d, *s, *t).to_vec(),
            Item::Reply(id, payload) => encode_frame(*id, payload),
        })
        .collect()
}

fn decode_chunks(chunks: &[&[u8]]) -> Vec<Decoded> {
    let mut decoder = Decoder::new();
    let mut out = Vec::new();
    for chunk in chunks {
        decoder.feed(chunk, &mut out);
        assert!(decoder.buffered() <= MAX_COMMAND_FRAME_LEN);
    }
    out
}

/// Every checksum-valid 9-byte window starting with 59 59 in `bytes`.
fn valid_windows(bytes: &[u8]) -> Vec<DataFrame> {
    bytes
        .windows(FRAME_LEN)
        .filter_map(|w| <&[u8; FRAME_LEN]>::try_from(w).ok())
        .filter_map(|w| DataFrame::parse(w).ok())
        .collect()
}

/// Applies `(kind, position, value)` edits: overwrite, insert, delete.
fn mutate(mut bytes: Vec<u8>, edits: &[(u8, usize, u8)]) -> Vec<u8> {
    for &(kind, pos, value) in edits {
        if bytes.is_empty() {
            bytes.push(value);
            continue;
        }
        let pos = pos % bytes.len();
        match kind % 3 {
            0 => bytes[pos] = value,
            1 => bytes.insert(pos, value),
            _ => {
                bytes.remove(pos);
            }
        }
    }
    bytes
}

fn drive(config: BenewakeConfig, chunks: &[Vec<u8>]) -> (Bench, Vec<DriverOutput>) {
    let mut bench = Bench::new(config);
    let mut all = bench.handshake();
    for chunk in chunks {
        bench.now = bench.now.plus_ns(1_000_000);
        all.extend(bench.feed(chunk));
    }
    (bench, all)
}

proptest! {
    #[test]
    fn random_bytes_never_panic(
        chunks in prop::collection::vec(prop::collection::vec(any::<u8>(), 0..64), 0..32),
        model in prop::sample::select(BenewakeModel::ALL.to_vec()),
    ) {
        let refs: Vec<&[u8]> = chunks.iter().map(Vec::as_slice).collect();
        decode_chunks(&refs);
        let config = BenewakeConfig { model, ..BenewakeConfig::default() };
        // Through the driver while connecting and while streaming.
        let mut connecting = Bench::new(config.clone());
        connecting.connect();
        for chunk in &chunks {
            connecting.wait_ms(7);
            connecting.feed(chunk);
        }
        let (bench, _) = drive(config, &chunks);
        prop_assert!(bench.driver.stats().scans <= bench.driver.stats().bytes / 9);
    }

    #[test]
    fn a_valid_stream_decodes_the_same_split_anywhere(
        items in prop::collection::vec(item(), 1..24),
    ) {
        let bytes = stream_of(&items);
        let whole = decode_chunks(&[&bytes]);
        prop_assert_eq!(whole.len(), items.len());
        prop_assert!(whole.iter().all(Result::is_ok));
        for split in 0..=bytes.len() {
            let (a, b) = bytes.split_at(split);
            prop_assert_eq!(&decode_chunks(&[a, b]), &whole);
        }
        let singles: Vec<&[u8]> = bytes.chunks(1).collect();
        prop_assert_eq!(&decode_chunks(&singles), &whole);
    }

    #[test]
    fn the_driver_delivers_the_same_readings_however_chunked(
        frames in prop::collection::vec((any::<u16>(), any::<u16>()), 1..40),
        cuts in prop::collection::vec(1usize..20, 1..40),
    ) {
        let bytes: Vec<u8> = frames.iter().flat_map(|&(d, s)| frame(d, s, 2248)).collect();
        let mut chunks = Vec::new();
        let mut rest = bytes.as_slice();
        for cut in cuts.iter().cycle() {
            if rest.is_empty() { break; }
            let (head, tail) = rest.split_at((*cut).min(rest.len()));
            chunks.push(head.to_vec());
            rest = tail;
        }
        let ranges = |chunks: &[Vec<u8>]| -> Vec<(u32, String, Option<f32>)> {
            let (_, out) = drive(BenewakeConfig::default(), chunks);
            out.iter().filter_map(|o| match o {
                DriverOutput::Scan(s) => Some((s.sequence, format!("{:?}", s.rays[0].range), s.rays[0].intensity)),
                _ => None,
            }).collect()
        };
        let expected = ranges(std::slice::from_ref(&bytes));
        prop_assert_eq!(expected.len(), frames.len());
        prop_assert_eq!(ranges(&chunks), expected);
    }

    #[test]
    fn mutations_never_deliver_a_frame_whose_sum_failed(
        items in prop::collection::vec(item(), 1..24),
        edits in prop::collection::vec((any::<u8>(), any::<usize>(), any::<u8>()), 1..12),
    ) {
        let mutated = mutate(stream_of(&items), &edits);
        let mut available = valid_windows(&mutated);
        for decoded in decode_chunks(&[&mutated]) {
            if let Ok(Packet::Data(frame)) = decoded {
                let at = available.iter().position(|w| *w == frame);
                prop_assert!(at.is_some(), "delivered {:?} from no valid window", frame);
                if let Some(at) = at { available.swap_remove(at); }
            }
        }
        // The same bytes through a streaming driver: one ray per scan, each
        // with the strength of a checksum-valid window, never more scans
        // than such windows.
        let windows = valid_windows(&mutated);
        let (bench, out) = drive(BenewakeConfig::default(), std::slice::from_ref(&mutated));
        prop_assert!(bench.driver.stats().scans <= windows.len() as u64);
        for o in &out {
            if let DriverOutput::Scan(scan) = o {
                prop_assert_eq!(scan.rays.len(), 1);
                let strength = scan.rays[0].intensity;
                prop_assert!(windows.iter().any(|w| Some(f32::from(w.strength)) == strength));
            }
        }
    }
}

/// A random byte that is neither header byte.
fn clean_byte(rng: &mut Pcg64) -> u8 {
    loop {
        let byte: u8 = rng.random();
        if byte != FRAME_HEADER && byte != COMMAND_HEADER {
            return byte;
        }
    }
}

/// A frame free of 0x59 and 0x5A outside its header, so the soak's expected
/// counts are exact.
fn clean_frame(rng: &mut Pcg64) -> [u8; FRAME_LEN] {
    loop {
        let bytes = frame(rng.random(), rng.random(), rng.random());
        if bytes[2..]
            .iter()
            .all(|b| *b != FRAME_HEADER && *b != COMMAND_HEADER)
        {
            return bytes;
        }
    }
}

/// `garbage` counts for a run of `skipped` bytes: one at its start (unless it
/// follows a bad checksum, which already counted it) and one more every 64.
fn garbage_for_run(skipped: u64, after_bad_checksum: bool) -> u64 {
    match (skipped, after_bad_checksum) {
        (0, _) => 0,
        (n, true) => (n - 1) / 64,
        (n, false) => (n - 1) / 64 + 1,
    }
}

#[test]
fn seeded_soak_counts_exactly() {
    let mut rng = Pcg64::seed_from_u64(0xBE7E_4A4E);
    let mut bytes = Vec::new();
    let (mut good, mut corrupted, mut garbage) = (0u64, 0u64, 0u64);
    for _ in 0..5000 {
        let mut f = clean_frame(&mut rng);
        let corrupt = rng.random_ratio(1, 20);
        if corrupt {
            // Another clean byte in the sum position: the sum fails, and the
            // 8 bytes after the slide are skipped as part of that error.
            f[8] = loop {
                let b = clean_byte(&mut rng);
                if b != f[8] {
                    break b;
                }
            };
            corrupted += 1;
        } else {
            good += 1;
        }
        bytes.extend(f);
        let burst = if rng.random_ratio(1, 25) {
            rng.random_range(1..200u64)
        } else {
            0
        };
        bytes.extend((0..burst).map(|_| clean_byte(&mut rng)));
        let skipped = burst + if corrupt { 8 } else { 0 };
        garbage += garbage_for_run(skipped, corrupt);
    }
    let mut decoder = Decoder::new();
    let mut out = Vec::new();
    let mut rest = bytes.as_slice();
    while !rest.is_empty() {
        let (chunk, tail) = rest.split_at(rng.random_range(1..100usize).min(rest.len()));
        decoder.feed(chunk, &mut out);
        rest = tail;
    }
    let count = |kind: &str| {
        out.iter()
            .filter(|d| d.map_err(|e| e.kind()) == Err(kind))
            .count() as u64
    };
    assert_eq!(out.iter().filter(|d| d.is_ok()).count() as u64, good);
    assert_eq!(count("bad_checksum"), corrupted);
    assert_eq!(count("garbage"), garbage);
    assert_eq!(count("partial_frame"), 0);
    assert!(corrupted > 100 && garbage > 100, "the soak exercises both");
}
