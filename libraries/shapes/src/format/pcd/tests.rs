//! PCD reading of fixtures not written by shroud (`libraries/shapes/tests/data/pcd/`: by its
//! `make_fixtures.py` in PCL's layouts, and by PCL 1.13 itself), header variants,
//! round trips, and every error with its place.

use super::*;
use crate::format::scalar::ScalarType;

/// A fixture of `libraries/shapes/tests/data/pcd/`.
macro_rules! fixture {
    ($name:literal) => {
        include_bytes!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/data/pcd/",
            $name
        ))
        .as_slice()
    };
}

/// Point k of the unorganised fixtures (see `make_fixtures.py`).
fn fixture_points(n: usize) -> (Vec<[f32; 3]>, Vec<f32>) {
    let points = (0..n)
        .map(|k| {
            let k = k as f32;
            [k / 2.0 - 1.0, 2.0 - k / 4.0, k * k / 8.0]
        })
        .collect();
    let intensity = (0..n).map(|k| 10.0 * k as f32 + 5.0).collect();
    (points, intensity)
}

fn assert_fixture(bytes: &[u8], n: usize) {
    let cloud = parse_pcd(bytes).unwrap();
    let (points, intensity) = fixture_points(n);
    assert_eq!(cloud.points, points);
    assert_eq!(cloud.intensity, Some(intensity));
    assert_eq!(cloud.skipped_invalid, 0);
}

#[test]
fn reads_pcl_style_files_of_every_encoding() {
    assert_fixture(fixture!("xyz_rgb_intensity_ascii.pcd"), 8);
    assert_fixture(fixture!("xyzi_padded_binary.pcd"), 6);
    assert_fixture(fixture!("intensity_first_binary.pcd"), 5);
    assert_fixture(fixture!("xyz_rgb_fpfh_intensity_compressed.pcd"), 7);
    // Written by PCL 1.13 itself: its LZF, and zero padding after the body.
    assert_fixture(fixture!("pcl113_fpfh_binary_compressed.pcd"), 7);
}

#[test]
fn invalid_points_of_organised_clouds_are_skipped_and_counted() {
    let cloud = parse_pcd(fixture!("organised_nan_binary.pcd")).unwrap();
    let expected: Vec<[f32; 3]> = (0..12)
        .filter(|k| ![1, 6, 11].contains(k))
        .map(|k| {
            let (c, r) = ((k % 4) as f32, (k / 4) as f32);
            [c, r, c + r]
        })
        .collect();
    assert_eq!(cloud.points, expected);
    assert_eq!((cloud.skipped_invalid, &cloud.intensity), (3, &None));
    assert_eq!(
        parse_pcd(fixture!("pcl113_organised_nan_binary.pcd")).unwrap(),
        cloud
    );
    let cloud = parse_pcd(fixture!("organised_nan_ascii.pcd")).unwrap();
    assert_eq!(cloud.points.len(), 5);
    assert_eq!(cloud.skipped_invalid, 1);
    assert_eq!(cloud.points[1], [2.0, 0.0, 2.0]);
}

#[test]
fn a_nan_point_keeps_intensity_aligned_and_inf_is_kept_for_validation() {
    let text = "FIELDS x y z intensity\nPOINTS 3\nDATA ascii\n1 2 3 4\n5 nan 7 8\ninf 1 1 9\n";
    let cloud = parse_pcd(text.as_bytes()).unwrap();
    assert_eq!(
        cloud.points,
        vec![[1.0, 2.0, 3.0], [f32::INFINITY, 1.0, 1.0]]
    );
    assert_eq!(cloud.intensity, Some(vec![4.0, 9.0]));
    assert_eq!(cloud.skipped_invalid, 1);
}

#[test]
fn written_clouds_read_back_bit_for_bit() {
    let points: Vec<[f32; 3]> = (0..300)
        .map(|i| {
            let t = i as f32;
            [t.sin() * 1e6, (t * 0.37).cos() * 1e-6, -t / 7.0]
        })
        .collect();
    let intensity: Vec<f32> = (0..300).map(|i| (i * i) as f32 / 3.0).collect();
    for encoding in PcdEncoding::ALL {
        let bytes = write_pcd(&points, Some(&intensity), encoding).unwrap();
        let cloud = parse_pcd(&bytes).unwrap();
        assert_eq!(cloud.points, points, "{encoding:?}");
        assert_eq!(cloud.intensity.as_deref(), Some(intensity.as_slice()));
        let cloud = parse_pcd(&write_pcd(&points, None, encoding).unwrap()).unwrap();
        assert_eq!((cloud.points.len(), cloud.intensity), (300, None));
        // An intensity of the wrong length is left out rather than misaligned.
        let bytes = write_pcd(&points, Some(&intensity[..3]), encoding).unwrap();
        assert_eq!(parse_pcd(&bytes).unwrap().intensity, None);
        let empty = parse_pcd(&write_pcd(&[], None, encoding).unwrap()).unwrap();
        assert_eq!(empty.points, Vec::<[f32; 3]>::new());
    }
}

#[test]
fn the_writer_matches_pcls_header() {
    let bytes = write_pcd(&[[1.0, 2.0, 3.5]], Some(&[0.25]), PcdEncoding::Ascii).unwrap();
    assert_eq!(
        String::from_utf8(bytes).unwrap(),
        "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\n\
         SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 1\nHEIGHT 1\n\
         VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1\nDATA ascii\n1 2 3.5 0.25\n"
    );
    let points = vec![[0.5f32, 0.5, 0.5]; 1000];
    let bytes = write_pcd(&points, None, PcdEncoding::BinaryCompressed).unwrap();
    let data_line = b"DATA binary_compressed\n";
    let body = bytes
        .windows(data_line.len())
        .position(|w| w == data_line)
        .unwrap()
        + data_line.len();
    let size = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    // 12000 bytes of one repeated pattern compress to a few hundred.
    assert_eq!(size(body + 4), 12_000);
    assert!(size(body) < 600, "{}", size(body));
    assert_eq!(bytes.len(), body + 8 + size(body) as usize);
    assert_eq!(parse_pcd(&bytes).unwrap().points, points);
}

#[test]
fn older_and_looser_headers_take_pcls_defaults() {
    // v0.5: COLUMNS, no SIZE/TYPE/COUNT (float32 each), no WIDTH/HEIGHT.
    let text =
        "# old\n\nVERSION .5\r\nCOLUMNS x y z\r\nPOINTS 2\r\nDATA ascii\r\n1 2 3\r\n\r\n4 5 6\r\n";
    let cloud = parse_pcd(text.as_bytes()).unwrap();
    assert_eq!(cloud.points, vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
    // POINTS may be left out when WIDTH and HEIGHT are given; keywords in any order.
    let text = "HEIGHT 1\nFIELDS z y x\n# between\nWIDTH 1\nDATA ascii\n3 2 1\n";
    assert_eq!(
        parse_pcd(text.as_bytes()).unwrap().points,
        vec![[1.0, 2.0, 3.0]]
    );
    // A binary body of 64-bit and 8-bit integers.
    let mut bytes =
        b"FIELDS X Y Z Intensity\nSIZE 8 8 1 1\nTYPE I U I U\nPOINTS 1\nDATA binary\n".to_vec();
    bytes.extend((-7i64).to_le_bytes());
    bytes.extend(9u64.to_le_bytes());
    bytes.extend([0xfe, 200]);
    let cloud = parse_pcd(&bytes).unwrap();
    assert_eq!(cloud.points, vec![[-7.0, 9.0, -2.0]]);
    assert_eq!(cloud.intensity, Some(vec![200.0]));
}

#[test]
fn skips_array_fields_in_ascii_bodies() {
    let text =
        "FIELDS normal x fpfh y z\nCOUNT 3 1 2 1 1\nPOINTS 1\nDATA ascii\n0 0 1 7 0.5 0.5 8 9\n";
    assert_eq!(
        parse_pcd(text.as_bytes()).unwrap().points,
        vec![[7.0, 8.0, 9.0]]
    );
}

fn err(text: &str) -> FormatError {
    parse_pcd(text.as_bytes()).unwrap_err()
}

#[test]
fn header_errors_name_the_line() {
    let malformed = |text: &str, line: usize, needle: &str| match err(text) {
        FormatError::PcdMalformedHeader { line: l, reason } => {
            assert_eq!(l, line, "{text}: {reason}");
            assert!(reason.contains(needle), "{text}: {reason}");
        }
        other => panic!("{text}: {other}"),
    };
    malformed(
        "VERSION 0.7\nFIELDS x y z\nCOLOUR red\n",
        3,
        "unknown keyword 'COLOUR'",
    );
    malformed(
        "FIELDS x y z\nFIELDS x y z\nDATA ascii\n",
        2,
        "a second 'FIELDS'",
    );
    malformed(
        "VERSION 2.0\nFIELDS x y z\nPOINTS 0\nDATA ascii\n",
        1,
        "VERSION",
    );
    malformed(
        "FIELDS x y z\nVIEWPOINT 0 0 0 1 0 0\nPOINTS 0\nDATA ascii\n",
        2,
        "7 numbers",
    );
    malformed(
        "FIELDS x y z\nWIDTH -4\nHEIGHT 1\nDATA ascii\n",
        2,
        "'-4' is not",
    );
    malformed("FIELDS x y z\nPOINTS 1 2\nDATA ascii\n", 2, "one value");
    malformed(
        "FIELDS x y x\nPOINTS 0\nDATA ascii\n",
        1,
        "a second field named 'x'",
    );
    malformed("FIELDS\nPOINTS 0\nDATA ascii\n", 1, "no field");
    malformed(
        "FIELDS x y z\nSIZE 4 0 4\nPOINTS 0\nDATA ascii\n",
        2,
        "SIZE of field 'y' is '0'",
    );
    malformed(
        "FIELDS x y z\nTYPE F D F\nPOINTS 0\nDATA ascii\n",
        2,
        "TYPE of field 'y'",
    );
    malformed(
        "FIELDS x y z\nCOUNT 1 1 q\nPOINTS 0\nDATA ascii\n",
        2,
        "COUNT of field 'z'",
    );
    malformed("FIELDS x y z\nPOINTS 0\nDATA ascii extra\n", 3, "DATA");
    assert_eq!(
        parse_pcd(b"FIELDS x y z\n\xff\nDATA ascii\n").unwrap_err(),
        FormatError::PcdMalformedHeader {
            line: 2,
            reason: "the header must be ASCII text".into()
        }
    );
    assert_eq!(err("FIELDS x y z\nPOINTS 3\n"), FormatError::PcdMissingData);
    for (text, keyword) in [
        ("POINTS 1\nDATA ascii\n", "FIELDS"),
        ("FIELDS x y z\nDATA ascii\n", "POINTS"),
        ("FIELDS x y z\nWIDTH 3\nPOINTS 3\nDATA ascii\n", "HEIGHT"),
        ("FIELDS x y z\nHEIGHT 3\nPOINTS 3\nDATA ascii\n", "WIDTH"),
    ] {
        assert_eq!(err(text), FormatError::PcdMissingKeyword { keyword });
    }
    assert_eq!(
        err("FIELDS x y z\nPOINTS 1\nDATA binary_lzma\n"),
        FormatError::PcdUnknownData {
            line: 3,
            found: "binary_lzma".into()
        }
    );
    assert_eq!(
        err("FIELDS x y z rgb\nSIZE 4 4 4\nPOINTS 1\nDATA ascii\n"),
        FormatError::PcdFieldCountMismatch {
            line: 2,
            keyword: "SIZE",
            got: 3,
            expected: 4
        }
    );
    assert_eq!(
        err("FIELDS x y z\nSIZE 4 4 2\nTYPE F F F\nPOINTS 1\nDATA ascii\n"),
        FormatError::PcdUnsupportedType {
            line: 3,
            field: "z".into(),
            kind: "F".into(),
            size: 2
        }
    );
    assert_eq!(
        err("FIELDS x y z\nWIDTH 2\nHEIGHT 3\nPOINTS 5\nDATA ascii\n"),
        FormatError::PcdPointsMismatch {
            points: 5,
            width: 2,
            height: 3
        }
    );
    assert_eq!(
        err("FIELDS x y intensity\nPOINTS 1\nDATA ascii\n1 2 3\n"),
        FormatError::PcdMissingCoordinate { axis: 'z' }
    );
    assert_eq!(
        err("FIELDS x y z\nCOUNT 1 2 1\nPOINTS 1\nDATA ascii\n1 2 3 4\n"),
        FormatError::PcdFieldNotScalar {
            field: "y".into(),
            count: 2
        }
    );
    assert!(matches!(
        err("FIELDS x y z\nWIDTH 99999999999\nHEIGHT 99999999999\nDATA binary\n"),
        FormatError::PcdAbsurdSize { .. }
    ));
    assert!(matches!(
        err("FIELDS x y z fpfh\nSIZE 4 4 4 8\nCOUNT 1 1 1 9999999999999999999\nPOINTS 1\nDATA binary\n"),
        FormatError::PcdAbsurdSize { what } if what.contains("field 'fpfh'")
    ));
    assert!(matches!(
        err("FIELDS x y z a b\nSIZE 4 4 4 8 8\nCOUNT 1 1 1 2305843009213693951 2305843009213693951\nPOINTS 1\nDATA binary\n"),
        FormatError::PcdAbsurdSize { .. }
    ));
}

#[test]
fn ascii_body_errors_name_line_point_and_field() {
    let head = "VERSION 0.7\nFIELDS x y z intensity\nPOINTS 2\nDATA ascii\n";
    let body = |b: &str| format!("{head}{b}");
    assert_eq!(
        err(&body("1 2 3 4\n5 6 seven 8\n")),
        FormatError::PcdBadAsciiNumber {
            line: 6,
            point: 1,
            field: "z".into(),
            token: "seven".into()
        }
    );
    assert!(matches!(
        err(&body("1 2 3\n")),
        FormatError::PcdBadAsciiRecord { line: 5, point: 0, ref reason } if reason.contains("4 values, this line has 3")
    ));
    let short = body("1 2 3 4\n");
    assert_eq!(
        err(&short),
        FormatError::PcdMissingPoints {
            expected: 2,
            got: 1,
            offset: short.len()
        }
    );
    assert!(matches!(
        err(&body("1 2 3 4\n5 6 7 8\n\n9 9 9 9\n")),
        FormatError::PcdBadAsciiRecord {
            line: 8,
            point: 2,
            ..
        }
    ));
    let mut not_text = body("1 2 3 4\n").into_bytes();
    not_text.extend(b"\xff 1 1 1\n");
    assert!(matches!(
        parse_pcd(&not_text),
        Err(FormatError::PcdBadAsciiRecord {
            line: 6,
            point: 1,
            ..
        })
    ));
}

/// A binary header of fields `x y z _ intensity` (16 + 4 bytes a point: the
/// padding is 4 bytes) for `points` points, and the body offset.
fn padded_binary(points: usize, data: &str) -> (Vec<u8>, usize) {
    let header = format!(
        "FIELDS x y z _ intensity\nSIZE 4 4 4 1 4\nTYPE F F F U F\nCOUNT 1 1 1 4 1\nPOINTS {points}\nDATA {data}\n"
    );
    let len = header.len();
    (header.into_bytes(), len)
}

#[test]
fn binary_truncation_names_point_field_and_offset() {
    let (mut bytes, body) = padded_binary(3, "binary");
    bytes.extend([0u8; 20 + 20 + 18]);
    // Cut 2 bytes into point 2's intensity (at 16 in its record), then 1 byte
    // into its 4 padding bytes (at 12).
    for (len, field, start, available) in [(58, "intensity", 16, 2), (53, "_", 12, 1)] {
        bytes.truncate(body + len);
        assert_eq!(
            parse_pcd(&bytes).unwrap_err(),
            FormatError::PcdTruncatedBody {
                point: 2,
                field: field.into(),
                needed: 4,
                offset: body + 40 + start,
                available
            }
        );
    }
    bytes.truncate(body);
    assert!(matches!(
        parse_pcd(&bytes).unwrap_err(),
        FormatError::PcdTruncatedBody { point: 0, ref field, offset, available: 0, .. } if field == "x" && offset == body
    ));
    // PCL pads the files it writes with zeros; other bytes after the last point are
    // points the header does not count.
    bytes.extend([0u8; 60 + 4036]);
    assert_eq!(parse_pcd(&bytes).unwrap().points.len(), 3);
    bytes[body + 60 + 4000] = 1;
    assert_eq!(
        parse_pcd(&bytes).unwrap_err(),
        FormatError::PcdTrailingBytes {
            count: 4036,
            points: 3,
            offset: body + 60
        }
    );
}

/// A binary_compressed file of 3 padded points whose body is `sizes` then `data`.
fn compressed(compressed: u32, uncompressed: u32, data: &[u8]) -> Vec<u8> {
    let (mut bytes, _) = padded_binary(3, "binary_compressed");
    bytes.extend(compressed.to_le_bytes());
    bytes.extend(uncompressed.to_le_bytes());
    bytes.extend(data);
    bytes
}

fn compressed_reason(bytes: &[u8]) -> (usize, String) {
    match parse_pcd(bytes).unwrap_err() {
        FormatError::PcdBadCompressedBody { offset, reason } => (offset, reason),
        other => panic!("{other}"),
    }
}

#[test]
fn compressed_sizes_are_checked_before_allocating() {
    let (_, body) = padded_binary(3, "binary_compressed");
    let literal = super::lzf::literal_runs(&[0u8; 60]);
    assert_eq!(
        parse_pcd(&compressed(literal.len() as u32, 60, &literal))
            .unwrap()
            .points,
        vec![[0.0; 3]; 3]
    );
    let (offset, reason) = compressed_reason(&compressed(62, 61, &literal));
    assert_eq!(offset, body + 4);
    assert!(
        reason.contains("POINTS 3 x 20 bytes per point is 60"),
        "{reason}"
    );
    let (offset, reason) = compressed_reason(&compressed(u32::MAX, 60, &literal));
    assert_eq!(offset, body);
    assert!(
        reason.contains("beyond the file (62 bytes remain)"),
        "{reason}"
    );
    let (offset, reason) = compressed_reason(&compressed(0, 60, &[]));
    assert_eq!(offset, body);
    assert!(reason.contains("cannot hold 60"), "{reason}");
    let (offset, reason) = compressed_reason(&compressed(62, 60, &[0x20; 62]));
    assert_eq!(offset, body + 8);
    assert!(reason.contains("corrupt"), "{reason}");
    let mut short = literal.clone();
    short[0] = 0; // the first run now holds 1 byte; the rest decodes to garbage
    assert!(matches!(
        parse_pcd(&compressed(short.len() as u32, 60, &short)),
        Err(FormatError::PcdBadCompressedBody { .. })
    ));
    let cut = compressed(2, 60, &[]);
    let (offset, reason) = compressed_reason(&cut[..cut.len() - 3]);
    assert_eq!(offset, body + 4);
    assert!(reason.contains("needs 4 bytes, only 1 remain"), "{reason}");
    let padded = [literal.as_slice(), &[0; 100]].concat();
    assert_eq!(
        parse_pcd(&compressed(literal.len() as u32, 60, &padded))
            .unwrap()
            .points
            .len(),
        3
    );
    assert_eq!(
        parse_pcd(&compressed(
            literal.len() as u32,
            60,
            &[literal.as_slice(), b"\n"].concat()
        ))
        .unwrap_err(),
        FormatError::PcdTrailingBytes {
            count: 1,
            points: 3,
            offset: body + 8 + literal.len()
        }
    );
    // A header announcing 2^31 bytes or more is refused before any allocation.
    let (header, body) = padded_binary(107_374_183, "binary_compressed");
    let mut huge = header;
    huge.extend((u32::MAX).to_le_bytes());
    huge.extend(2_147_483_660u32.to_le_bytes());
    let (offset, reason) = compressed_reason(&huge);
    assert_eq!(offset, body + 4);
    assert!(reason.contains("beyond the 2147483647 bytes"), "{reason}");
}

#[test]
fn the_types_of_the_fixtures_are_the_ones_asked_for() {
    // The intensity-first fixture reads intensity as U 2 and coordinates as F 8.
    let header = header::parse_header(fixture!("intensity_first_binary.pcd")).unwrap();
    let types: Vec<ScalarType> = header.fields.iter().map(|f| f.ty).collect();
    assert_eq!(
        types,
        [
            ScalarType::U16,
            ScalarType::F64,
            ScalarType::F64,
            ScalarType::F64,
            ScalarType::F32,
            ScalarType::U32
        ]
    );
    assert_eq!(header.record_size, 2 + 24 + 8);
    let header = header::parse_header(fixture!("organised_nan_binary.pcd")).unwrap();
    assert_eq!((header.width, header.height, header.points), (4, 3, 12));
}

#[test]
fn every_truncation_fails_cleanly() {
    for bytes in [
        fixture!("xyzi_padded_binary.pcd"),
        fixture!("intensity_first_binary.pcd"),
        fixture!("xyz_rgb_fpfh_intensity_compressed.pcd"),
        fixture!("organised_nan_binary.pcd"),
    ] {
        for len in 0..bytes.len() {
            assert!(parse_pcd(&bytes[..len]).is_err(), "cut at {len}");
        }
    }
    // An ASCII cut inside the last number leaves a shorter, well-formed number.
    let ascii = fixture!("xyz_rgb_intensity_ascii.pcd");
    let last_space = ascii.iter().rposition(|&b| b == b' ').unwrap();
    for len in 0..=last_space {
        assert!(parse_pcd(&ascii[..len]).is_err(), "cut at {len}");
    }
}

#[test]
fn sniffing_finds_pcd_headers() {
    assert!(has_pcd_header(b"# .PCD v0.7\nVERSION 0.7\n"));
    assert!(has_pcd_header(b"\n\nFIELDS x y z\n"));
    assert!(!has_pcd_header(b"# x y z\n1 2 3\n"));
    assert!(!has_pcd_header(b"ply\nformat ascii 1.0\n"));
    assert!(!has_pcd_header(b"VERSIONS\n"));
    assert!(!has_pcd_header(b""));
}
