//! Property tests of the PLY cloud reader: random clouds round-trip through
//! ASCII and binary bit for bit; a cut binary file is an error; mutated,
//! truncated and random files never panic.

use super::*;
use proptest::prelude::*;

/// `cases` cases; failures are not persisted to files (the source tree is
/// shared).
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

fn coordinate() -> impl Strategy<Value = f32> {
    any::<f32>().prop_filter("finite", |v| v.is_finite())
}

fn cloud() -> impl Strategy<Value = (Vec<[f32; 3]>, Option<Vec<f32>>)> {
    (0usize..150, any::<bool>()).prop_flat_map(|(n, with_intensity)| {
        let points = proptest::collection::vec([coordinate(), coordinate(), coordinate()], n);
        let intensity = proptest::collection::vec(coordinate(), n);
        (
            points,
            intensity.prop_map(move |i| with_intensity.then_some(i)),
        )
    })
}

proptest! {
    #![proptest_config(config(96))]

    #[test]
    fn random_clouds_round_trip_bit_for_bit((points, intensity) in cloud(), ascii in any::<bool>()) {
        let bytes = write_ply_points(&points, intensity.as_deref(), ascii);
        let cloud = parse_ply(&bytes).unwrap();
        prop_assert_eq!(cloud.points, points);
        prop_assert_eq!(cloud.intensity, intensity);
    }

    #[test]
    fn mutated_and_truncated_files_never_panic(
        (points, intensity) in cloud(),
        ascii in any::<bool>(),
        mutations in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..5),
        cut in any::<prop::sample::Index>(),
    ) {
        let valid = write_ply_points(&points, intensity.as_deref(), ascii);
        let mut bytes = valid.clone();
        for (at, byte) in mutations {
            let at = at.index(bytes.len());
            bytes[at] = byte;
        }
        let _ = parse_ply(&bytes);
        let _ = parse_ply(&bytes[..cut.index(bytes.len())]);
        // A cut binary file with points always lacks a vertex (an ASCII cut
        // inside the last number can leave a well-formed file).
        if !ascii && !points.is_empty() {
            prop_assert!(parse_ply(&valid[..cut.index(valid.len())]).is_err());
        }
    }

    #[test]
    fn random_bodies_never_panic(
        big_endian in any::<bool>(),
        body in proptest::collection::vec(any::<u8>(), 0..400),
    ) {
        let encoding = if big_endian { "binary_big_endian" } else { "binary_little_endian" };
        let mut bytes = format!(
            "ply\nformat {encoding} 1.0\nelement vertex 5\nproperty double x\nproperty float y\n\
             property short z\nproperty list uchar int extra\nend_header\n"
        )
        .into_bytes();
        bytes.extend(&body);
        let _ = parse_ply(&bytes);
        let _ = parse_ply(&body);
    }
}
