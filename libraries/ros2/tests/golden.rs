//! Every message type against payloads rosbags 0.11.9 wrote
//! (tests/golden/generate.py): decode(golden) == the value built here, and
//! encode(value) == golden, byte for byte; big-endian encapsulations decode
//! to the same values; type hashes and gids equal rosbags' and xxhash's.

mod common;

use common::{golden, golden_names, golden_pairs};
use shroud_ros2::*;
use std::borrow::Cow;
use std::fmt::Debug;

/// decode(golden) == value, encode(value) == golden and, where rosbags wrote
/// it, decode(big-endian golden) == value.
fn check<M: RosMessage + PartialEq + Debug>(name: &str, value: M) {
    let bytes = golden(name);
    assert_eq!(M::decode(&bytes).expect(name), value, "{name}: decode");
    assert_eq!(value.encode(), bytes, "{name}: encode");
    if golden_names().contains(&format!("{name}_be")) {
        let big_endian = golden(&format!("{name}_be"));
        assert_eq!(&big_endian[..4], &[0, 0, 0, 0], "{name}_be: CDR_BE header");
        assert_eq!(
            M::decode(&big_endian).expect(name),
            value,
            "{name}_be: decode"
        );
    }
}

fn time(sec: i32, nanosec: u32) -> Time {
    Time { sec, nanosec }
}

fn header(frame_id: &str, sec: i32, nanosec: u32) -> Header {
    Header {
        stamp: time(sec, nanosec),
        frame_id: frame_id.into(),
    }
}

fn xyz(datatype: u8, size: u32) -> Vec<PointField> {
    ["x", "y", "z"]
        .iter()
        .zip(0..)
        .map(|(name, i)| PointField::scalar(name, i * size, datatype))
        .collect()
}

fn cloud(
    fields: Vec<PointField>,
    point_step: u32,
    data: Vec<u8>,
    width: u32,
) -> PointCloud2<'static> {
    PointCloud2 {
        header: header("map", 1, 2),
        height: 1,
        width,
        fields,
        is_bigendian: false,
        point_step,
        row_step: point_step * width,
        data: Cow::Owned(data),
        is_dense: true,
    }
}

fn f32_le(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

fn point(x: f64, y: f64, z: f64) -> Point {
    Point { x, y, z }
}

fn vector3(x: f64, y: f64, z: f64) -> Vector3 {
    Vector3 { x, y, z }
}

fn color(r: f32, g: f32, b: f32, a: f32) -> ColorRGBA {
    ColorRGBA { r, g, b, a }
}

fn pose() -> Pose {
    Pose {
        position: point(1.0, 2.0, 3.0),
        orientation: Quaternion::IDENTITY,
    }
}

fn quarter_turn_about_z() -> Quaternion {
    Quaternion {
        x: 0.0,
        y: 0.0,
        z: std::f64::consts::FRAC_1_SQRT_2,
        w: std::f64::consts::FRAC_1_SQRT_2,
    }
}

fn joint_state(velocity: Vec<f64>, effort: Vec<f64>) -> JointState {
    JointState {
        header: header("", 10, 4),
        name: vec!["shoulder".into(), "elbow".into()],
        position: vec![0.5, -1.25],
        velocity,
        effort,
    }
}

fn compressed_image(format: &str, data: Vec<u8>) -> CompressedImage {
    CompressedImage {
        header: header("", 0, 0),
        format: format.into(),
        data,
    }
}

fn triangle_list_marker() -> Marker {
    Marker {
        header: header("map", 5, 6),
        ns: "shroud".into(),
        id: 7,
        type_: Marker::TRIANGLE_LIST,
        action: Marker::ADD,
        pose: pose(),
        scale: vector3(1.0, 1.0, 1.0),
        color: color(1.0, 0.5, 0.25, 1.0),
        points: vec![
            point(0.0, 0.0, 0.0),
            point(1.0, 0.0, 0.0),
            point(0.0, 1.0, 0.0),
        ],
        colors: vec![
            color(1.0, 0.0, 0.0, 1.0),
            color(0.0, 1.0, 0.0, 1.0),
            color(0.0, 0.0, 1.0, 1.0),
        ],
        texture: compressed_image("", vec![]),
        ..Marker::default()
    }
}

fn transform() -> Transform {
    Transform {
        translation: vector3(1.0, -2.0, 0.5),
        rotation: quarter_turn_about_z(),
    }
}

fn transform_stamped() -> TransformStamped {
    TransformStamped {
        header: header("world", 3, 500),
        child_frame_id: "base_link".into(),
        transform: transform(),
    }
}

#[test]
fn point_clouds() {
    let xyz_f32 = f32_le(&[1.0, 2.0, 3.0, -1.5, 0.25, 8.0]);
    assert_eq!(golden("point_cloud2_xyz").len(), 133, "ros2.md's 133 bytes");
    check(
        "point_cloud2_xyz",
        cloud(xyz(PointField::FLOAT32, 4), 12, xyz_f32, 2),
    );

    let mut xyzi = xyz(PointField::FLOAT32, 4);
    xyzi.push(PointField::scalar("intensity", 16, PointField::FLOAT32));
    let padded = f32_le(&[
        1.0, 2.0, 3.0, 0.0, 9.5, 0.0, 0.0, 0.0, 4.0, 5.0, 6.0, 0.0, 7.25, 0.0, 0.0, 0.0,
    ]);
    check("point_cloud2_xyzi_padded", cloud(xyzi, 32, padded, 2));

    let xyz_f64 = [1.5f64, -2.5, 1e-3]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    check(
        "point_cloud2_float64",
        cloud(xyz(PointField::FLOAT64, 8), 24, xyz_f64, 1),
    );

    let xyz_be = [1.0f32, 2.0, 3.0]
        .iter()
        .flat_map(|v| v.to_be_bytes())
        .collect();
    let big_endian_data = PointCloud2 {
        is_bigendian: true,
        ..cloud(xyz(PointField::FLOAT32, 4), 12, xyz_be, 1)
    };
    check("point_cloud2_bigendian_data", big_endian_data);
}

#[test]
fn point_cloud_decodes_borrowing_its_data() {
    let bytes = golden("point_cloud2_xyz");
    let cloud = PointCloud2::decode_borrowed(&bytes).expect("decodes");
    assert!(matches!(cloud.data, Cow::Borrowed(_)));
    assert_eq!(cloud.data.as_ptr(), bytes[bytes.len() - 25..].as_ptr());
    assert_eq!(cloud.encode(), bytes);
}

#[test]
fn joint_states() {
    check("joint_state_positions", joint_state(vec![], vec![]));
    check(
        "joint_state_velocities",
        joint_state(vec![0.75, -0.2], vec![1.0, 2.0]),
    );
}

#[test]
fn markers() {
    check(
        "marker_array_triangle_list",
        MarkerArray {
            markers: vec![triangle_list_marker()],
        },
    );
    check("marker_array_empty", MarkerArray::default());
    let every_field = Marker {
        type_: Marker::SPHERE,
        lifetime: Duration {
            sec: 1,
            nanosec: 500,
        },
        frame_locked: true,
        points: vec![],
        colors: vec![],
        texture_resource: "file:///t.png".into(),
        texture: compressed_image("png", vec![1, 2, 3]),
        uv_coordinates: vec![UVCoordinate { u: 0.5, v: 0.25 }],
        text: "hi".into(),
        mesh_resource: "package://m.dae".into(),
        mesh_file: MeshFile {
            filename: "m.dae".into(),
            data: vec![9, 8],
        },
        mesh_use_embedded_materials: true,
        ..triangle_list_marker()
    };
    check("marker_every_field", every_field);
    check("uv_coordinate", UVCoordinate { u: 0.5, v: 0.75 });
    let mesh_file = MeshFile {
        filename: "m.stl".into(),
        data: vec![1, 2, 3, 4],
    };
    check("mesh_file", mesh_file);
}

#[test]
fn standard_messages() {
    check("float64", Float64 { data: -12.5 });
    check("time", time(-3, 999_999_999));
    check("duration", Duration { sec: 7, nanosec: 1 });
    check("header", header("base_link", 1_700_000_000, 123));
    check("color_rgba", color(0.1, 0.2, 0.3, 0.4));
    check(
        "point_field",
        PointField::scalar("rgb", 12, PointField::UINT32),
    );
    check(
        "compressed_image",
        compressed_image("jpeg", vec![255, 216, 255]),
    );
}

#[test]
fn diagnostics() {
    let key_value = |key: &str, value: &str| KeyValue {
        key: key.into(),
        value: value.into(),
    };
    let status = DiagnosticStatus {
        level: DiagnosticStatus::WARN,
        name: "shroud: lidar".into(),
        message: "late".into(),
        hardware_id: "scip0".into(),
        values: vec![key_value("rate", "9.5"), key_value("expected", "10")],
    };
    check("diagnostic_status", status);
    check("key_value", key_value("k", "v"));
}

#[test]
fn geometry_and_tf() {
    check("point", point(1.0, -2.0, 3.5));
    check("vector3", vector3(0.5, 0.25, -0.125));
    check("quaternion", quarter_turn_about_z());
    check("pose", pose());
    check("transform", transform());
    check("transform_stamped", transform_stamped());
    check(
        "tf_message",
        TFMessage {
            transforms: vec![transform_stamped()],
        },
    );
}

/// What the crate declares of one message type.
struct Declared {
    name: &'static str,
    hash: &'static str,
    min_cdr_bytes: usize,
    /// The length of its default value's payload, header aside.
    default_encoded: usize,
}

fn of<M: RosMessage + Default>() -> Declared {
    Declared {
        name: M::TYPE_NAME,
        hash: M::TYPE_HASH,
        min_cdr_bytes: M::MIN_CDR_BYTES,
        default_encoded: M::default().encode().len() - 4,
    }
}

/// Every message type of the crate.
fn declared() -> Vec<Declared> {
    vec![
        of::<Time>(),
        of::<Duration>(),
        of::<Header>(),
        of::<ColorRGBA>(),
        of::<Float64>(),
        of::<Point>(),
        of::<Vector3>(),
        of::<Quaternion>(),
        of::<Pose>(),
        of::<Transform>(),
        of::<TransformStamped>(),
        of::<TFMessage>(),
        of::<PointField>(),
        of::<PointCloud2<'static>>(),
        of::<JointState>(),
        of::<CompressedImage>(),
        of::<UVCoordinate>(),
        of::<MeshFile>(),
        of::<Marker>(),
        of::<MarkerArray>(),
        of::<KeyValue>(),
        of::<DiagnosticStatus>(),
    ]
}

#[test]
fn type_hashes_are_rosbags_hash_rihs01() {
    let mut ours: Vec<(String, String)> = declared()
        .into_iter()
        .map(|d| (d.name.to_string(), d.hash.to_string()))
        .collect();
    ours.sort();
    assert_eq!(ours, golden_pairs("type_hashes.txt"));
}

#[test]
fn type_hashes_quoted_in_ros2_md() {
    assert_eq!(
        PointCloud2::TYPE_HASH,
        "RIHS01_9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5"
    );
    assert_eq!(
        Marker::TYPE_HASH,
        "RIHS01_45b13ccf791f225962bf74e746f9644518855d783a6f42ba0cc14fde2b4f3ce0"
    );
    assert_eq!(
        MarkerArray::TYPE_HASH,
        "RIHS01_86cb8800b6fb05b5eff1abd7a56f62a5641d3ae9a1c29e78e67e704f1d067dcf"
    );
}

/// A sequence's count is checked against MIN_CDR_BYTES per element: it must
/// be positive and never exceed the smallest real encoding.
#[test]
fn min_cdr_bytes_bound_the_smallest_encoding() {
    for d in declared() {
        assert!(
            0 < d.min_cdr_bytes && d.min_cdr_bytes <= d.default_encoded,
            "{}: MIN_CDR_BYTES {} vs {} encoded",
            d.name,
            d.min_cdr_bytes,
            d.default_encoded
        );
    }
}

#[test]
fn gids_are_xxh3_128_of_the_token() {
    for (gid, token) in golden_pairs("gids.txt") {
        assert_eq!(entity_gid(&token).to_vec(), common::hex(&gid), "{token}");
    }
}

#[test]
fn dds_type_names() {
    assert_eq!(
        dds_type_name("sensor_msgs/msg/PointCloud2").unwrap(),
        "sensor_msgs::msg::dds_::PointCloud2_"
    );
    assert_eq!(
        dds_type_name("visualization_msgs/msg/MarkerArray").unwrap(),
        "visualization_msgs::msg::dds_::MarkerArray_"
    );
    for bad in [
        "",
        "sensor_msgs/PointCloud2",
        "a/msg/",
        "a/b/C",
        "a/msg/B/c",
        "a b/msg/C",
    ] {
        let error = dds_type_name(bad).unwrap_err();
        assert!(error.to_string().contains(&format!("{bad:?}")), "{error}");
    }
}
