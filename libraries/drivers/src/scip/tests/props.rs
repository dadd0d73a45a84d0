//! Property tests: arbitrary input never panics and never yields a scan;
//! chunking does not change what is decoded; a corrupted byte never yields a
//! scan with the wrong number of rays, and a lost scan is always counted.

use proptest::prelude::*;

use super::support::*;
use crate::device::DeviceDriver;
use crate::scip::*;

/// Two streamed URG-04LX scans, back to back.
fn two_scans(rig: &Rig) -> Vec<u8> {
    let mut bytes = rig.md_scan(150);
    bytes.extend(rig.md_scan(50));
    bytes
}

fn feed_all(rig: &mut Rig, chunks: &[&[u8]]) -> Vec<ScanBits> {
    chunks
        .iter()
        .flat_map(|c| scans(&rig.feed(c)))
        .map(|s| scan_bits(&s))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_bytes_while_streaming_yield_no_scan(bytes in prop::collection::vec(any::<u8>(), 0..4096)) {
        let mut rig = Rig::streaming();
        prop_assert!(scans(&rig.feed(&bytes)).is_empty());
        prop_assert_eq!(rig.driver.stats().scans, 0);
    }

    #[test]
    fn random_bytes_and_time_in_any_phase_never_panic(
        steps in prop::collection::vec((prop::collection::vec(any::<u8>(), 0..512), 0u64..1500), 0..24),
        rs232 in any::<bool>(),
    ) {
        let link = if rs232 { Link::rs232() } else { Link::Usb };
        let mut rig = Rig::new(ScipConfig { link, ..ScipConfig::default() });
        rig.connect();
        for (bytes, ms) in &steps {
            prop_assert!(scans(&rig.feed(bytes)).is_empty());
            let out = rig.advance_ms(*ms);
            prop_assert!(scans(&out).is_empty());
            if reconnect_reason(&out).is_some() {
                rig.connect();
            }
        }
    }

    #[test]
    fn arbitrary_chunking_yields_identical_scans(cuts in prop::collection::vec(any::<prop::sample::Index>(), 0..12)) {
        let mut whole = Rig::streaming();
        let stream = two_scans(&whole);
        let expected = feed_all(&mut whole, &[&stream]);
        let mut at: Vec<usize> = cuts.iter().map(|c| c.index(stream.len() + 1)).collect();
        at.sort_unstable();
        let mut chunks = Vec::new();
        let mut last = 0;
        for cut in at.into_iter().chain([stream.len()]) {
            chunks.push(&stream[last..cut]);
            last = cut;
        }
        let mut split = Rig::streaming();
        prop_assert_eq!(feed_all(&mut split, &chunks), expected);
    }

    #[test]
    fn single_byte_corruption_never_yields_a_wrong_scan(
        index in any::<prop::sample::Index>(),
        byte in any::<u8>(),
    ) {
        let mut rig = Rig::streaming();
        let mut stream = two_scans(&rig);
        let at = index.index(stream.len());
        prop_assume!(stream[at] != byte);
        stream[at] = byte;
        // A clean third scan closes any reply the corruption left open.
        stream.extend(rig.md_scan(10));
        let got = scans(&rig.feed(&stream));
        prop_assert!(got.len() <= 3);
        for scan in &got {
            prop_assert_eq!(scan.rays.len(), 682);
        }
        if got.len() < 3 {
            prop_assert!(rig.driver.stats().total_errors() > 0, "a lost scan is counted");
        }
    }
}

#[test]
fn split_at_every_byte_position_yields_identical_scans() {
    let mut whole = Rig::streaming();
    let stream = two_scans(&whole);
    let expected = feed_all(&mut whole, &[&stream]);
    assert_eq!(expected.len(), 2);
    for at in 0..=stream.len() {
        let mut split = Rig::streaming();
        let (a, b) = stream.split_at(at);
        assert_eq!(feed_all(&mut split, &[a, b]), expected, "split at {at}");
    }
}

#[test]
fn byte_at_a_time_yields_identical_scans() {
    let mut whole = Rig::streaming();
    let stream = two_scans(&whole);
    let expected = feed_all(&mut whole, &[&stream]);
    let mut single = Rig::streaming();
    let chunks: Vec<&[u8]> = stream.chunks(1).collect();
    assert_eq!(feed_all(&mut single, &chunks), expected);
    assert_eq!(single.driver.stats().bytes, whole.driver.stats().bytes);
}
