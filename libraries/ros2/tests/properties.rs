//! Properties over random values and random bytes: encode → decode gives the
//! value back (NaN-free floats, so `==` holds), decoders and parsers of
//! arbitrary input return errors instead of panicking.

use proptest::collection::vec;
use proptest::prelude::*;
use shroud_ros2::cdr::{decode_payload, CdrDecode};
use shroud_ros2::*;
use std::borrow::Cow;
use std::fmt::Debug;

fn f64s() -> impl Strategy<Value = f64> {
    any::<f64>().prop_filter("NaN never equals itself", |v| !v.is_nan())
}

fn f32s() -> impl Strategy<Value = f32> {
    any::<f32>().prop_filter("NaN never equals itself", |v| !v.is_nan())
}

fn text() -> impl Strategy<Value = String> {
    any::<String>().prop_map(|s| s.chars().take(12).collect())
}

fn header() -> impl Strategy<Value = Header> {
    (any::<i32>(), any::<u32>(), text()).prop_map(|(sec, nanosec, frame_id)| Header {
        stamp: Time { sec, nanosec },
        frame_id,
    })
}

fn point() -> impl Strategy<Value = Point> {
    (f64s(), f64s(), f64s()).prop_map(|(x, y, z)| Point { x, y, z })
}

fn vector3() -> impl Strategy<Value = Vector3> {
    point().prop_map(|Point { x, y, z }| Vector3 { x, y, z })
}

fn quaternion() -> impl Strategy<Value = Quaternion> {
    (point(), f64s()).prop_map(|(Point { x, y, z }, w)| Quaternion { x, y, z, w })
}

fn color() -> impl Strategy<Value = ColorRGBA> {
    (f32s(), f32s(), f32s(), f32s()).prop_map(|(r, g, b, a)| ColorRGBA { r, g, b, a })
}

fn joint_state() -> impl Strategy<Value = JointState> {
    (
        header(),
        vec(text(), 0..4),
        vec(f64s(), 0..4),
        vec(f64s(), 0..4),
        vec(f64s(), 0..4),
    )
        .prop_map(|(header, name, position, velocity, effort)| JointState {
            header,
            name,
            position,
            velocity,
            effort,
        })
}

fn point_field() -> impl Strategy<Value = PointField> {
    (text(), any::<u32>(), any::<u8>(), any::<u32>()).prop_map(|(name, offset, datatype, count)| {
        PointField {
            name,
            offset,
            datatype,
            count,
        }
    })
}

fn point_cloud() -> impl Strategy<Value = PointCloud2<'static>> {
    let sizes = (any::<u32>(), any::<u32>(), any::<u32>(), any::<u32>());
    let flags = (any::<bool>(), any::<bool>());
    (
        header(),
        sizes,
        vec(point_field(), 0..4),
        flags,
        vec(any::<u8>(), 0..64),
    )
        .prop_map(
            |(
                header,
                (height, width, point_step, row_step),
                fields,
                (is_bigendian, is_dense),
                data,
            )| {
                PointCloud2 {
                    header,
                    height,
                    width,
                    fields,
                    is_bigendian,
                    point_step,
                    row_step,
                    data: Cow::Owned(data),
                    is_dense,
                }
            },
        )
}

fn marker() -> impl Strategy<Value = Marker> {
    let shape = (
        text(),
        any::<i32>(),
        any::<i32>(),
        any::<i32>(),
        point(),
        quaternion(),
        vector3(),
        color(),
    );
    let lists = (
        vec(point(), 0..4),
        vec(color(), 0..4),
        vec((f32s(), f32s()), 0..3),
    );
    let resources = (
        text(),
        text(),
        text(),
        text(),
        vec(any::<u8>(), 0..8),
        text(),
        vec(any::<u8>(), 0..8),
    );
    let flags = (any::<bool>(), any::<bool>(), any::<i32>(), any::<u32>());
    (header(), shape, lists, resources, flags).prop_map(
        |(header, shape, lists, resources, flags)| {
            let (ns, id, type_, action, position, orientation, scale, color) = shape;
            let (points, colors, uvs) = lists;
            let (texture_resource, format, text, mesh_resource, texture_data, filename, mesh_data) =
                resources;
            let (frame_locked, mesh_use_embedded_materials, sec, nanosec) = flags;
            Marker {
                texture: CompressedImage {
                    header: header.clone(),
                    format,
                    data: texture_data,
                },
                header,
                ns,
                id,
                type_,
                action,
                pose: Pose {
                    position,
                    orientation,
                },
                scale,
                color,
                lifetime: Duration { sec, nanosec },
                frame_locked,
                points,
                colors,
                texture_resource,
                uv_coordinates: uvs
                    .into_iter()
                    .map(|(u, v)| UVCoordinate { u, v })
                    .collect(),
                text,
                mesh_resource,
                mesh_file: MeshFile {
                    filename,
                    data: mesh_data,
                },
                mesh_use_embedded_materials,
            }
        },
    )
}

fn diagnostic_status() -> impl Strategy<Value = DiagnosticStatus> {
    let values = vec(
        (text(), text()).prop_map(|(key, value)| KeyValue { key, value }),
        0..4,
    );
    (any::<u8>(), text(), text(), text(), values).prop_map(
        |(level, name, message, hardware_id, values)| DiagnosticStatus {
            level,
            name,
            message,
            hardware_id,
            values,
        },
    )
}

fn tf_message() -> impl Strategy<Value = TFMessage> {
    let transform = (header(), text(), vector3(), quaternion()).prop_map(
        |(header, child_frame_id, translation, rotation)| TransformStamped {
            header,
            child_frame_id,
            transform: Transform {
                translation,
                rotation,
            },
        },
    );
    vec(transform, 0..4).prop_map(|transforms| TFMessage { transforms })
}

fn qos() -> impl Strategy<Value = QosProfile> {
    let reliability = prop_oneof![Just(Reliability::Reliable), Just(Reliability::BestEffort)];
    let durability = prop_oneof![Just(Durability::TransientLocal), Just(Durability::Volatile)];
    let history = prop_oneof![
        any::<u32>().prop_map(History::KeepLast),
        Just(History::KeepAll)
    ];
    (reliability, durability, history).prop_map(|(reliability, durability, history)| QosProfile {
        reliability,
        durability,
        history,
    })
}

fn ros_name() -> impl Strategy<Value = String> {
    "(/[a-z][a-z0-9_]{0,5}){1,3}"
}

fn token() -> impl Strategy<Value = LivelinessToken> {
    let topic = (
        ros_name(),
        "[a-z_]{1,8}::msg::dds_::[A-Z][A-Za-z0-9]{0,8}_",
        "RIHS01_[0-9a-f]{64}",
        qos(),
    )
        .prop_map(|(name, type_name, type_hash, qos)| TopicInfo {
            name,
            type_name,
            type_hash,
            qos,
        });
    let kind = prop_oneof![
        Just(EntityKind::Publisher),
        Just(EntityKind::Subscription),
        Just(EntityKind::ServiceServer),
        Just(EntityKind::ServiceClient),
    ];
    let entity = prop_oneof![Just((EntityKind::Node, None)), (kind, topic.prop_map(Some))];
    let namespace = prop_oneof![Just("/".to_string()), ros_name()];
    let ids = (any::<u32>(), "[0-9a-f]{1,32}", any::<u64>(), any::<u64>());
    (
        ids,
        entity,
        namespace.clone(),
        namespace,
        "[a-z][a-z0-9_]{0,8}",
    )
        .prop_map(
            |(
                (domain_id, zid, node_id, entity_id),
                (kind, topic),
                enclave,
                namespace,
                node_name,
            )| {
                LivelinessToken {
                    domain_id,
                    zid,
                    node_id,
                    entity_id,
                    kind,
                    enclave,
                    namespace,
                    node_name,
                    topic,
                }
            },
        )
}

fn round_trips<M: RosMessage + PartialEq + Debug>(value: &M) -> Result<(), TestCaseError> {
    prop_assert_eq!(&M::decode(&value.encode()).expect("decodes"), value);
    Ok(())
}

/// Arbitrary bytes, half of them behind a CDR_LE or CDR_BE header.
fn payloads() -> impl Strategy<Value = Vec<u8>> {
    let header = prop_oneof![Just(vec![]), Just(vec![0, 1, 0, 0]), Just(vec![0, 0, 0, 0])];
    (header, vec(any::<u8>(), 0..512)).prop_map(|(mut header, body)| {
        header.extend(body);
        header
    })
}

fn decodes_or_errs<T: CdrDecode>(bytes: &[u8]) {
    if let Err(error) = decode_payload::<T>(bytes) {
        assert!(!error.to_string().is_empty());
    }
}

proptest! {
    #[test]
    fn joint_states_round_trip(value in joint_state()) { round_trips(&value)?; }

    #[test]
    fn marker_arrays_round_trip(markers in vec(marker(), 0..3)) {
        round_trips(&MarkerArray { markers })?;
    }

    #[test]
    fn point_clouds_round_trip(value in point_cloud()) {
        round_trips(&value)?;
        let bytes = value.encode();
        prop_assert_eq!(PointCloud2::decode_borrowed(&bytes).expect("decodes"), value);
    }

    #[test]
    fn diagnostic_statuses_round_trip(value in diagnostic_status()) { round_trips(&value)?; }

    #[test]
    fn tf_messages_round_trip(value in tf_message()) { round_trips(&value)?; }

    #[test]
    fn arbitrary_bytes_never_panic_a_decoder(bytes in payloads()) {
        decodes_or_errs::<JointState>(&bytes);
        decodes_or_errs::<MarkerArray>(&bytes);
        decodes_or_errs::<Marker>(&bytes);
        decodes_or_errs::<PointCloud2<'static>>(&bytes);
        decodes_or_errs::<DiagnosticStatus>(&bytes);
        decodes_or_errs::<TFMessage>(&bytes);
        decodes_or_errs::<Float64>(&bytes);
        let _ = PointCloud2::decode_borrowed(&bytes);
        let _ = Attachment::decode(&bytes);
    }

    #[test]
    fn attachments_round_trip(sequence_number: i64, source_timestamp_ns: i64, gid: [u8; 16]) {
        let attachment = Attachment { sequence_number, source_timestamp_ns, gid };
        prop_assert_eq!(Attachment::decode(&attachment.encode()), Ok(attachment));
    }

    #[test]
    fn tokens_round_trip(token in token()) {
        let keyexpr = token.to_keyexpr();
        prop_assert_eq!(LivelinessToken::parse(&keyexpr), Ok(token));
    }

    #[test]
    fn qos_round_trips(qos in qos()) {
        prop_assert_eq!(QosProfile::parse(&qos.to_keyexpr()), Ok(qos));
    }

    #[test]
    fn arbitrary_strings_never_panic_a_parser(text in any::<String>()) {
        let _ = LivelinessToken::parse(&text);
        let _ = QosProfile::parse(&text);
        let _ = topic_key(0, &text, &text, &text);
        let _ = dds_type_name(&text);
    }

    #[test]
    fn token_shaped_strings_never_panic_the_parser(
        segments in vec("@ros2_lv|[0-9]{1,3}|NN|MP|SS|%|[a-z%]{0,4}|[0-9:,]{0,12}", 0..15)
    ) {
        let _ = LivelinessToken::parse(&segments.join("/"));
    }
}
