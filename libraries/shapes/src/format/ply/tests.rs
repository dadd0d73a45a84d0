//! PLY reading across encodings, scalar types and layouts, its errors, and its
//! robustness against truncated or random bytes.

use super::*;
use crate::format::scalar::ScalarType;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

const ALL_TYPES: [(&str, ScalarType); 8] = [
    ("char", ScalarType::I8),
    ("uint8", ScalarType::U8),
    ("short", ScalarType::I16),
    ("ushort", ScalarType::U16),
    ("int32", ScalarType::I32),
    ("uint", ScalarType::U32),
    ("float", ScalarType::F32),
    ("float64", ScalarType::F64),
];

#[derive(Clone, Copy, PartialEq)]
enum Body {
    Ascii,
    Little,
    Big,
}

impl Body {
    fn name(self) -> &'static str {
        match self {
            Body::Ascii => "ascii",
            Body::Little => "binary_little_endian",
            Body::Big => "binary_big_endian",
        }
    }
}

/// A property value or a list of values (with the list's count and item types).
enum Value {
    Scalar(ScalarType, f64),
    List(ScalarType, ScalarType, Vec<f64>),
}

fn record(values: &[Value], body: Body) -> Vec<u8> {
    if body == Body::Ascii {
        let mut tokens = Vec::new();
        for v in values {
            match v {
                Value::Scalar(_, x) => tokens.push(x.to_string()),
                Value::List(_, _, items) => {
                    tokens.push(items.len().to_string());
                    tokens.extend(items.iter().map(|x| x.to_string()));
                }
            }
        }
        return format!("{}\n", tokens.join(" ")).into_bytes();
    }
    let big = body == Body::Big;
    let mut out = Vec::new();
    for v in values {
        match v {
            Value::Scalar(ty, x) => out.extend(ty.encode(*x, big)),
            Value::List(count, item, items) => {
                out.extend(count.encode(items.len() as f64, big));
                items.iter().for_each(|x| out.extend(item.encode(*x, big)));
            }
        }
    }
    out
}

/// A file with a `camera` element (with a list) before the vertices, vertices with
/// shuffled properties of type `name`/`ty` (optionally with a list property of
/// their own), and faces after them.
fn sample_file(body: Body, name: &str, ty: ScalarType, vertex_list: bool) -> Vec<u8> {
    let list = if vertex_list {
        "property list uchar ushort neighbours\n"
    } else {
        ""
    };
    let header = format!(
        "ply\nformat {} 1.0\ncomment made by a test\nobj_info none\nelement camera 2\nproperty float focal\n\
         property list int double coeffs\nelement vertex 3\nproperty uchar red\nproperty {name} z\n\
         property {name} x\n{list}property double nx\nproperty {name} y\nproperty {name} intensity\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n",
        body.name()
    );
    let mut out = header.into_bytes();
    for k in 0..2 {
        let coeffs: Vec<f64> = (0..k * 3).map(|i| i as f64 * 0.5).collect();
        let camera = [
            Value::Scalar(ScalarType::F32, 35.0),
            Value::List(ScalarType::I32, ScalarType::F64, coeffs),
        ];
        out.extend(record(&camera, body));
    }
    for (i, [x, y, z]) in expected_points().iter().enumerate() {
        let mut vertex = vec![
            Value::Scalar(ScalarType::U8, 200.0),
            Value::Scalar(ty, *z as f64),
            Value::Scalar(ty, *x as f64),
        ];
        if vertex_list {
            vertex.push(Value::List(ScalarType::U8, ScalarType::U16, vec![1.0; i]));
        }
        vertex.extend([
            Value::Scalar(ScalarType::F64, 0.25),
            Value::Scalar(ty, *y as f64),
        ]);
        vertex.push(Value::Scalar(ty, 10.0 * (i + 1) as f64));
        out.extend(record(&vertex, body));
    }
    out.extend(record(
        &[Value::List(
            ScalarType::U8,
            ScalarType::I32,
            vec![0.0, 1.0, 2.0],
        )],
        body,
    ));
    out
}

/// Small non-negative integers, representable in every scalar type.
fn expected_points() -> Vec<[f32; 3]> {
    vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 127.0]]
}

#[test]
fn reads_every_type_encoding_and_layout() {
    for body in [Body::Ascii, Body::Little, Body::Big] {
        for (name, ty) in ALL_TYPES {
            for vertex_list in [false, true] {
                let bytes = sample_file(body, name, ty, vertex_list);
                let cloud = parse_ply(&bytes)
                    .unwrap_or_else(|e| panic!("{} {name} {vertex_list}: {e}", body.name()));
                assert_eq!(cloud.points, expected_points(), "{} {name}", body.name());
                assert_eq!(
                    cloud.intensity,
                    Some(vec![10.0, 20.0, 30.0]),
                    "{} {name}",
                    body.name()
                );
            }
        }
    }
}

#[test]
fn keeps_full_precision_of_each_type() {
    let header = |body: Body, ty: &str| {
        format!("ply\nformat {} 1.0\nelement vertex 1\nproperty {ty} x\nproperty {ty} y\nproperty {ty} z\nend_header\n", body.name())
    };
    for body in [Body::Little, Body::Big] {
        let mut bytes = header(body, "int").into_bytes();
        [-2_000_000_000.0, 5.0, -1.0]
            .iter()
            .for_each(|&v| bytes.extend(ScalarType::I32.encode(v, body == Body::Big)));
        assert_eq!(parse_ply(&bytes).unwrap().points, vec![[-2e9, 5.0, -1.0]]);
        let mut bytes = header(body, "double").into_bytes();
        [0.1, -1e300, 1e-300]
            .iter()
            .for_each(|&v| bytes.extend(ScalarType::F64.encode(v, body == Body::Big)));
        assert_eq!(
            parse_ply(&bytes).unwrap().points,
            vec![[0.1f32, f32::NEG_INFINITY, 0.0]]
        );
    }
}

#[test]
fn scalar_intensity_is_accepted_and_absent_intensity_is_none() {
    let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n\
                property float scalar_Intensity\nend_header\n1 2 3 0.5\n";
    assert_eq!(
        parse_ply(text.as_bytes()).unwrap().intensity,
        Some(vec![0.5])
    );
    let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n\
                end_header\n\n1 2 3\n";
    assert_eq!(
        parse_ply(text.as_bytes()).unwrap(),
        PlyCloud {
            points: vec![[1.0, 2.0, 3.0]],
            intensity: None,
            skipped_invalid: 0,
        }
    );
}

#[test]
fn written_clouds_read_back_bit_for_bit() {
    let mut rng = Pcg64::seed_from_u64(7);
    let points: Vec<[f32; 3]> = (0..500)
        .map(|_| {
            [
                rng.random(),
                rng.random::<f32>() * 1e6,
                -rng.random::<f32>() * 1e-6,
            ]
        })
        .collect();
    let intensity: Vec<f32> = (0..500).map(|_| rng.random::<f32>() * 65535.0).collect();
    for ascii in [true, false] {
        let cloud = parse_ply(&write_ply_points(&points, Some(&intensity), ascii)).unwrap();
        assert_eq!(cloud.points, points);
        assert_eq!(cloud.intensity.as_deref(), Some(intensity.as_slice()));
        let cloud = parse_ply(&write_ply_points(&points, None, ascii)).unwrap();
        assert_eq!((cloud.points.len(), cloud.intensity), (500, None));
    }
    // An intensity of the wrong length is left out rather than misaligned.
    let cloud = parse_ply(&write_ply_points(&points, Some(&intensity[..10]), false)).unwrap();
    assert_eq!(cloud.intensity, None);
}

#[test]
fn errors_name_the_problem_and_place() {
    let vertex = "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n";
    let ascii = |body: &str| format!("ply\nformat ascii 1.0\n{vertex}end_header\n{body}");
    assert_eq!(
        parse_ply(ascii("1 2 3\n4 five 6\n").as_bytes()),
        Err(FormatError::PlyBadAsciiNumber {
            line: 9,
            token: "five".into()
        })
    );
    assert!(matches!(
        parse_ply(ascii("1 2 3\n4 5\n").as_bytes()),
        Err(FormatError::PlyBadAsciiRecord { line: 9, .. })
    ));
    assert!(matches!(
        parse_ply(ascii("1 2 3 4\n").as_bytes()),
        Err(FormatError::PlyBadAsciiRecord { line: 8, .. })
    ));
    let text = ascii("1 2 3\n");
    assert_eq!(
        parse_ply(text.as_bytes()),
        Err(FormatError::PlyTruncatedBody {
            expected: 2,
            got: 1,
            offset: text.len()
        })
    );
    let mut binary =
        format!("ply\nformat binary_little_endian 1.0\n{vertex}end_header\n").into_bytes();
    let body_start = binary.len();
    binary.extend([0u8; 12 + 7]);
    assert_eq!(
        parse_ply(&binary),
        Err(FormatError::PlyTruncatedBody {
            expected: 2,
            got: 1,
            offset: body_start + 12
        })
    );
    let no_z = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n";
    assert_eq!(
        parse_ply(no_z.as_bytes()),
        Err(FormatError::PlyMissingCoordinate { axis: 'z' })
    );
    let no_vertex = "ply\nformat ascii 1.0\nelement point 1\nproperty float x\nend_header\n1\n";
    assert_eq!(
        parse_ply(no_vertex.as_bytes()),
        Err(FormatError::PlyNoVertexElement)
    );
    let mut negative_list = b"ply\nformat binary_little_endian 1.0\nelement meta 1\nproperty list char int ids\n\
                         element vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
        .to_vec();
    negative_list.push(0xff);
    assert!(matches!(
        parse_ply(&negative_list),
        Err(FormatError::PlyBadListLength { record: 0, length, .. }) if length == -1.0
    ));
}

#[test]
fn every_truncation_fails_cleanly() {
    for body in [Body::Ascii, Body::Little, Body::Big] {
        let bytes = sample_file(body, "short", ScalarType::I16, true);
        let vertices_end = bytes.len()
            - record(
                &[Value::List(ScalarType::U8, ScalarType::I32, vec![0.0; 3])],
                body,
            )
            .len();
        // An ASCII cut inside the last value of the last vertex leaves a shorter but
        // well-formed number: nothing can tell it was cut.
        let undetectable = match body {
            Body::Ascii => {
                bytes[..vertices_end]
                    .iter()
                    .rposition(|&b| b == b' ')
                    .unwrap_or(0)
                    + 2
            }
            _ => vertices_end,
        };
        for len in 0..undetectable {
            assert!(
                parse_ply(&bytes[..len]).is_err(),
                "{} cut at {len}",
                body.name()
            );
        }
        // The faces after the vertices are not needed.
        for len in vertices_end..=bytes.len() {
            assert_eq!(parse_ply(&bytes[..len]).unwrap().points, expected_points());
        }
    }
}

#[test]
fn random_and_corrupted_bytes_never_panic() {
    let mut rng = Pcg64::seed_from_u64(11);
    for _ in 0..2000 {
        let len = rng.random_range(0..300);
        let mut bytes: Vec<u8> = (0..len).map(|_| rng.random()).collect();
        if rng.random_bool(0.5) {
            bytes.splice(0..0, b"ply\nformat binary_big_endian 1.0\n".iter().copied());
        }
        let _ = parse_ply(&bytes);
    }
    for body in [Body::Ascii, Body::Little, Body::Big] {
        let valid = sample_file(body, "uint", ScalarType::U32, true);
        for _ in 0..3000 {
            let mut bytes = valid.clone();
            for _ in 0..rng.random_range(1..4) {
                let at = rng.random_range(0..bytes.len());
                bytes[at] = rng.random();
            }
            let _ = parse_ply(&bytes);
        }
    }
}

#[test]
fn huge_counts_neither_hang_nor_allocate() {
    let vertex = "element vertex 1000000000000000000\nproperty float x\nproperty float y\nproperty float z\n";
    for body in [Body::Ascii, Body::Little] {
        let text = format!(
            "ply\nformat {} 1.0\nelement empty 1000000000000000000\n{vertex}end_header\n",
            body.name()
        );
        let mut bytes = text.into_bytes();
        bytes.extend(b"1 2 3\n");
        assert!(matches!(
            parse_ply(&bytes),
            Err(FormatError::PlyTruncatedBody { got: 0, .. })
                | Err(FormatError::PlyBadAsciiRecord { .. })
        ));
    }
    let text = format!("ply\nformat ascii 1.0\n{vertex}end_header\n1 2 3\n");
    assert!(matches!(
        parse_ply(text.as_bytes()),
        Err(FormatError::PlyTruncatedBody { got: 1, .. })
    ));
}
