//! Property tests of the XYZ/CSV/TSV reader: random clouds round-trip through
//! `write_xyz` bit for bit; a file cut at a line end reads as the points
//! before the cut; mutated and cut files never panic.

use super::xyz::{parse_xyz, write_xyz};
use proptest::prelude::*;

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

fn points() -> impl Strategy<Value = Vec<[f32; 3]>> {
    let coordinate = any::<f32>().prop_filter("finite", |v| v.is_finite());
    proptest::collection::vec([coordinate.clone(), coordinate.clone(), coordinate], 1..100)
}

proptest! {
    #![proptest_config(config(96))]

    #[test]
    fn random_clouds_round_trip_bit_for_bit(points in points()) {
        prop_assert_eq!(parse_xyz(&write_xyz(&points)).unwrap(), points);
    }

    #[test]
    fn a_cut_at_a_line_end_keeps_the_points_before_it(points in points(), keep in any::<prop::sample::Index>()) {
        let keep = keep.index(points.len()) + 1;
        let text = write_xyz(&points);
        let cut = text
            .iter()
            .enumerate()
            .filter(|(_, b)| **b == b'\n')
            .nth(keep - 1)
            .map_or(text.len(), |(at, _)| at + 1);
        prop_assert_eq!(parse_xyz(&text[..cut]).unwrap(), points[..keep].to_vec());
    }

    #[test]
    fn mutated_and_cut_files_never_panic(
        points in points(),
        mutations in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..5),
        cut in any::<prop::sample::Index>(),
    ) {
        let mut bytes = write_xyz(&points);
        for (at, byte) in mutations {
            let at = at.index(bytes.len());
            bytes[at] = byte;
        }
        if let Ok(read) = parse_xyz(&bytes) {
            prop_assert!(read.len() <= points.len() + 1);
        }
        let _ = parse_xyz(&bytes[..cut.index(bytes.len())]);
    }
}
