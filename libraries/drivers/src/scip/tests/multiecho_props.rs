//! Property tests of multi-echo (`ND`/`NE`) streams: splitting the bytes
//! anywhere changes nothing; a corrupted byte never yields a scan whose ray
//! count differs from the clean data's number of echoes, and a lost scan is
//! always counted; arbitrary `&`-laden data never panics the decoder.

use proptest::prelude::*;

use super::support::*;
use crate::device::DeviceDriver;
use crate::scip::*;

/// 100 steps, 100..=199.
const STEPS: usize = 100;

fn echo(intensity: bool) -> &'static str {
    if intensity {
        "NE0100019901000"
    } else {
        "ND0100019901000"
    }
}

/// A driver streaming `ND` (or `NE`) over steps 100..=199.
fn rig(intensity: bool) -> Rig {
    let mut rig = Rig::new(ScipConfig {
        scan: ScanCommand::Nd,
        intensity,
        start_step: Some(100),
        end_step: Some(199),
        ..ScipConfig::default()
    });
    rig.bring_up();
    rig.feed(&reply(echo(intensity), "00", &[]));
    rig
}

/// Step `i` with `counts[i]` echoes: ranges 1000 + 10i + j (an error code
/// for the first echo of every 17th step), intensities 3i + j.
fn steps(counts: &[u8], intensity: bool) -> Vec<Vec<u32>> {
    counts
        .iter()
        .enumerate()
        .map(|(i, &n)| {
            let i = i as u32;
            (0..u32::from(n))
                .flat_map(|j| {
                    let range = if i.is_multiple_of(17) && j == 0 {
                        1
                    } else {
                        1000 + 10 * i + j
                    };
                    let mut values = vec![range];
                    if intensity {
                        values.push(3 * i + j);
                    }
                    values
                })
                .collect()
        })
        .collect()
}

/// A streamed scan whose timestamp is `age_ms` before now.
fn scan(rig: &Rig, counts: &[u8], intensity: bool, age_ms: u32) -> Vec<u8> {
    let stamp = rig.device_ms().wrapping_sub(age_ms) & 0xFF_FFFF;
    let per_echo = if intensity { 2 } else { 1 };
    let data = multiecho_lines(stamp, &steps(counts, intensity), per_echo);
    reply(echo(intensity), "99", &data)
}

fn pattern() -> Vec<u8> {
    (0..STEPS).map(|i| [3, 1, 2, 1][i % 4]).collect()
}

fn feed_all(rig: &mut Rig, chunks: &[&[u8]]) -> Vec<ScanBits> {
    chunks
        .iter()
        .flat_map(|c| scans(&rig.feed(c)))
        .map(|s| scan_bits(&s))
        .collect()
}

#[test]
fn nd_split_at_every_byte_position_yields_identical_scans() {
    let counts = pattern();
    let mut whole = rig(false);
    let mut stream = scan(&whole, &counts, false, 150);
    stream.extend(scan(&whole, &counts, false, 50));
    let text = String::from_utf8(stream.clone()).unwrap();
    assert!(
        text.lines()
            .any(|l| l.len() == 65 && l[..64].ends_with('&')),
        "some line ends with a bare '&'"
    );
    let expected = feed_all(&mut whole, &[&stream]);
    assert_eq!(expected.len(), 2);
    let rays: usize = counts.iter().map(|&n| usize::from(n)).sum();
    assert_eq!(expected[0].3.len(), rays);
    for at in 0..=stream.len() {
        let mut split = rig(false);
        let (a, b) = stream.split_at(at);
        assert_eq!(feed_all(&mut split, &[a, b]), expected, "split at {at}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn single_byte_corruption_never_yields_a_wrong_multiecho_scan(
        counts in prop::collection::vec(1u8..=3, STEPS),
        intensity in any::<bool>(),
        index in any::<prop::sample::Index>(),
        byte in any::<u8>(),
    ) {
        let mut rig = rig(intensity);
        let mut stream = scan(&rig, &counts, intensity, 150);
        stream.extend(scan(&rig, &counts, intensity, 50));
        let at = index.index(stream.len());
        prop_assume!(stream[at] != byte);
        stream[at] = byte;
        // A clean third scan closes any reply the corruption left open.
        stream.extend(scan(&rig, &counts, intensity, 10));
        let got = scans(&rig.feed(&stream));
        let rays: usize = counts.iter().map(|&n| usize::from(n)).sum();
        prop_assert!(got.len() <= 3);
        for scan in &got {
            prop_assert_eq!(scan.rays.len(), rays);
            prop_assert_eq!(scan.has_intensity(), intensity);
        }
        if got.len() < 3 {
            prop_assert!(rig.driver.stats().total_errors() > 0, "a lost scan is counted");
        }
    }

    #[test]
    fn arbitrary_multiecho_data_never_panics_and_decodes_consistently(
        data in prop::collection::vec(prop::sample::select(b"0@Aa&o".to_vec()), 0..300),
        intensity in any::<bool>(),
        steps in 1u16..40,
    ) {
        let kind = if intensity { ScanKind::Ne } else { ScanKind::Nd };
        let request = ScanRequest { kind, start: 0, end: steps - 1, cluster: 1, interval: 0, scans: 0 };
        let mut lines = vec![summed("0000").trim_end().as_bytes().to_vec()];
        lines.extend(
            data.chunks(64)
                .map(|c| summed(std::str::from_utf8(c).unwrap()).trim_end().as_bytes().to_vec()),
        );
        if let Ok(decoded) = decode_scan(&lines, &request) {
            let counts = decoded.echoes.expect("multi-echo data has echo counts");
            prop_assert_eq!(counts.len(), usize::from(steps));
            prop_assert!(counts.iter().all(|n| (1..=3).contains(n)));
            let total: usize = counts.iter().map(|&n| usize::from(n)).sum();
            prop_assert_eq!(decoded.ranges.len(), total);
            prop_assert_eq!(decoded.intensities.map(|i| i.len()), intensity.then_some(total));
        }
    }
}
