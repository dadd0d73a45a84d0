//! Property tests of the PCD reader: random clouds round-trip through every
//! encoding bit for bit; mutated, truncated and random files and random headers
//! never panic.

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

fn encoding() -> impl Strategy<Value = PcdEncoding> {
    prop_oneof![
        Just(PcdEncoding::Ascii),
        Just(PcdEncoding::Binary),
        Just(PcdEncoding::BinaryCompressed),
    ]
}

/// Finite f32 of any magnitude, and small repeated values that LZF compresses.
fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        any::<f32>().prop_filter("finite", |v| v.is_finite()),
        (-4i8..4).prop_map(|v| v as f32 * 0.5),
    ]
}

fn cloud() -> impl Strategy<Value = (Vec<[f32; 3]>, Option<Vec<f32>>)> {
    (0usize..200, any::<bool>()).prop_flat_map(|(n, with_intensity)| {
        let points = proptest::collection::vec([coordinate(), coordinate(), coordinate()], n);
        let intensity = proptest::collection::vec(coordinate(), n);
        (
            points,
            intensity.prop_map(move |i| with_intensity.then_some(i)),
        )
    })
}

/// One line of a plausible header: keywords PCL knows and some it does not,
/// with values right, wrong or absurd.
fn header_line() -> impl Strategy<Value = String> {
    let keyword = prop_oneof![
        Just("VERSION"),
        Just("FIELDS"),
        Just("COLUMNS"),
        Just("SIZE"),
        Just("TYPE"),
        Just("COUNT"),
        Just("WIDTH"),
        Just("HEIGHT"),
        Just("VIEWPOINT"),
        Just("POINTS"),
        Just("DATA"),
        Just("#"),
        Just("BOGUS"),
    ];
    let value = prop_oneof![
        Just("x"),
        Just("y"),
        Just("z"),
        Just("intensity"),
        Just("_"),
        Just("0"),
        Just("1"),
        Just("2"),
        Just("4"),
        Just("8"),
        Just("F"),
        Just("U"),
        Just("I"),
        Just("ascii"),
        Just("binary"),
        Just("binary_compressed"),
        Just("0.7"),
        Just("-1"),
        Just("18446744073709551615"),
        Just("99999999999"),
    ];
    (keyword, proptest::collection::vec(value, 0..6))
        .prop_map(|(keyword, values)| format!("{keyword} {}", values.join(" ")))
}

proptest! {
    #![proptest_config(config(96))]

    #[test]
    fn random_clouds_round_trip_bit_for_bit((points, intensity) in cloud(), encoding in encoding()) {
        let bytes = write_pcd(&points, intensity.as_deref(), encoding).unwrap();
        let cloud = parse_pcd(&bytes).unwrap();
        prop_assert_eq!(cloud.points, points);
        prop_assert_eq!(cloud.intensity, intensity);
        prop_assert_eq!(cloud.skipped_invalid, 0);
    }

    #[test]
    fn mutated_and_truncated_files_never_panic(
        (points, intensity) in cloud(),
        encoding in encoding(),
        mutations in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..5),
        cut in any::<prop::sample::Index>(),
    ) {
        let valid = write_pcd(&points, intensity.as_deref(), encoding).unwrap();
        let mut bytes = valid.clone();
        for (at, byte) in mutations {
            let at = at.index(bytes.len());
            bytes[at] = byte;
        }
        let _ = parse_pcd(&bytes);
        let _ = parse_pcd(&bytes[..cut.index(bytes.len())]);
        // A cut binary file with points is always an error (ASCII cuts inside
        // the last number can leave a well-formed file, and so can cutting the
        // final newline of an empty cloud's header).
        let cut = cut.index(valid.len());
        if encoding != PcdEncoding::Ascii && !points.is_empty() {
            prop_assert!(parse_pcd(&valid[..cut]).is_err());
        }
    }

    #[test]
    fn random_headers_never_panic(
        lines in proptest::collection::vec(header_line(), 0..12),
        data in encoding(),
        body in proptest::collection::vec(any::<u8>(), 0..120),
    ) {
        let mut bytes = lines.join("\n").into_bytes();
        bytes.extend(format!("\nDATA {}\n", data.name()).as_bytes());
        bytes.extend(body);
        if let Ok(cloud) = parse_pcd(&bytes) {
            let intensity = cloud.intensity.as_ref().map_or(cloud.points.len(), Vec::len);
            prop_assert_eq!(intensity, cloud.points.len());
        }
    }

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        let _ = parse_pcd(&bytes);
        let mut with_header = b"FIELDS x y z\nPOINTS 3\nDATA binary_compressed\n".to_vec();
        with_header.extend(&bytes);
        let _ = parse_pcd(&with_header);
    }
}
