//! Outside bytes that must be refused with an error naming the field, never
//! a panic, and never an allocation sized by an unchecked count.

mod common;

use common::{golden, golden_names};
use shroud_ros2::cdr::{decode_payload, CdrDecode};
use shroud_ros2::*;

/// Decodes `bytes` as the type of golden case `name` (its file name's prefix).
fn decode_as(name: &str, bytes: &[u8]) -> Result<(), CdrError> {
    fn with<T: CdrDecode>(bytes: &[u8]) -> Result<(), CdrError> {
        decode_payload::<T>(bytes).map(drop)
    }
    let decode = match name.trim_end_matches("_be") {
        n if n.starts_with("point_cloud2") => |b: &[u8]| PointCloud2::decode_borrowed(b).map(drop),
        n if n.starts_with("joint_state") => with::<JointState>,
        n if n.starts_with("marker_array") => with::<MarkerArray>,
        "marker_every_field" => with::<Marker>,
        "float64" => with::<Float64>,
        "diagnostic_status" => with::<DiagnosticStatus>,
        "key_value" => with::<KeyValue>,
        "tf_message" => with::<TFMessage>,
        "time" => with::<Time>,
        "duration" => with::<Duration>,
        "header" => with::<Header>,
        "color_rgba" => with::<ColorRGBA>,
        "point_field" => with::<PointField>,
        "compressed_image" => with::<CompressedImage>,
        "point" => with::<Point>,
        "vector3" => with::<Vector3>,
        "quaternion" => with::<Quaternion>,
        "pose" => with::<Pose>,
        "transform" => with::<Transform>,
        "transform_stamped" => with::<TransformStamped>,
        "uv_coordinate" => with::<UVCoordinate>,
        "mesh_file" => with::<MeshFile>,
        other => panic!("no decoder for golden case {other}"),
    };
    decode(bytes)
}

#[test]
fn every_prefix_of_every_golden_payload_is_an_error() {
    for name in golden_names() {
        let bytes = golden(&name);
        decode_as(&name, &bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        for len in 0..bytes.len() {
            let error = decode_as(&name, &bytes[..len]).expect_err(&format!("{name}[..{len}]"));
            assert!(!error.to_string().is_empty());
        }
    }
}

/// The JointState golden with the u32 at `offset` replaced by `value`.
fn joint_state_with_u32(offset: usize, value: u32) -> Vec<u8> {
    let mut bytes = golden("joint_state_positions");
    bytes[offset..offset + 4].copy_from_slice(&value.to_le_bytes());
    bytes
}

// joint_state_positions: header (stamp 4..12, frame_id length 12..16, NUL 16),
// then padding to 20 and the name count at 20..24.
const NAME_COUNT_AT: usize = 20;
const FRAME_ID_LENGTH_AT: usize = 12;

#[test]
fn absurd_sequence_count_is_refused_before_allocating() {
    let bytes = joint_state_with_u32(NAME_COUNT_AT, u32::MAX);
    match JointState::decode(&bytes).unwrap_err() {
        CdrError::Count { field, count, .. } => {
            assert_eq!((field, count), ("JointState.name", u32::MAX));
        }
        other => panic!("{other}"),
    }
    let cloud = golden("point_cloud2_xyz");
    let mut huge_data = cloud.clone();
    let data_count_at = cloud.len() - 1 - 24 - 4;
    huge_data[data_count_at..data_count_at + 4].copy_from_slice(&u32::MAX.to_le_bytes());
    let error = PointCloud2::decode_borrowed(&huge_data).unwrap_err();
    assert!(
        error.to_string().starts_with("PointCloud2.data:"),
        "{error}"
    );
}

#[test]
fn absurd_string_length_is_truncation() {
    let bytes = joint_state_with_u32(FRAME_ID_LENGTH_AT, u32::MAX);
    let error = JointState::decode(&bytes).unwrap_err();
    assert!(
        matches!(
            error,
            CdrError::Truncated {
                field: "Header.frame_id",
                ..
            }
        ),
        "{error}"
    );
}

#[test]
fn strings_need_their_nul_and_utf8() {
    let mut no_nul = golden("header");
    let frame_id_nul = no_nul.len() - 1;
    no_nul[frame_id_nul] = b'x';
    assert_eq!(
        Header::decode(&no_nul).unwrap_err(),
        CdrError::MissingNul {
            field: "Header.frame_id",
            length: 10
        }
    );
    let zero_length = {
        let mut bytes = golden("header")[..16].to_vec();
        bytes[12..16].copy_from_slice(&0u32.to_le_bytes());
        bytes
    };
    assert!(matches!(
        Header::decode(&zero_length).unwrap_err(),
        CdrError::MissingNul { length: 0, .. }
    ));
    let mut not_utf8 = golden("header");
    not_utf8[16] = 0xFF;
    assert_eq!(
        Header::decode(&not_utf8).unwrap_err(),
        CdrError::NotUtf8 {
            field: "Header.frame_id"
        }
    );
}

#[test]
fn bools_are_zero_or_one() {
    let mut bytes = golden("point_cloud2_xyz");
    let last = bytes.len() - 1;
    bytes[last] = 2;
    let error = PointCloud2::decode_borrowed(&bytes).unwrap_err();
    assert_eq!(
        error,
        CdrError::Bool {
            field: "PointCloud2.is_dense",
            value: 2
        }
    );
    assert!(error.to_string().contains("PointCloud2.is_dense"));
}

#[test]
fn headers_other_than_classic_cdr_are_refused() {
    let mut bytes = golden("float64");
    for identifier in [[0x00, 0x02], [0x00, 0x03], [0x00, 0x07], [0x01, 0x01]] {
        bytes[..2].copy_from_slice(&identifier);
        assert_eq!(
            Float64::decode(&bytes).unwrap_err(),
            CdrError::Header { identifier }
        );
    }
    assert!(matches!(
        Float64::decode(&[0, 1]).unwrap_err(),
        CdrError::Truncated { .. }
    ));
}

#[test]
fn trailing_padding_up_to_three_zero_bytes_only() {
    let bytes = golden("point_cloud2_xyz");
    for padding in 1..=3 {
        let mut padded = bytes.clone();
        padded.resize(bytes.len() + padding, 0);
        assert!(
            PointCloud2::decode_borrowed(&padded).is_ok(),
            "{padding} zero bytes"
        );
    }
    let mut four = bytes.clone();
    four.resize(bytes.len() + 4, 0);
    assert_eq!(
        PointCloud2::decode_borrowed(&four).unwrap_err(),
        CdrError::TrailingBytes {
            count: 4,
            allowed: 3
        }
    );
    let mut junk = bytes;
    junk.push(7);
    assert!(matches!(
        PointCloud2::decode_borrowed(&junk).unwrap_err(),
        CdrError::TrailingBytes { count: 1, .. }
    ));
}
