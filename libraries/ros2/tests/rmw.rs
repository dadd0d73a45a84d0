//! rmw_zenoh's keys, tokens, QoS strings and attachment against literals
//! quoted from /work/shared/research/ros2.md (which cites rmw_zenoh's
//! docs/design.md@99a6a2bd, liveliness_utils.cpp@3411fdec,
//! attachment_helpers.cpp@534747dc).

use shroud_ros2::*;

const POINT_CLOUD2_KEY: &str = "0/shroud/cloud/sensor_msgs::msg::dds_::PointCloud2_/RIHS01_9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5";
const ZID: &str = "aabbccddeeff00112233445566778899";
const NODE_TOKEN: &str = "@ros2_lv/0/aabbccddeeff00112233445566778899/0/0/NN/%/%/shroud_bridge";
const PUBLISHER_TOKEN: &str = "@ros2_lv/0/aabbccddeeff00112233445566778899/0/1/MP/%/%/shroud_bridge/%shroud%cloud/sensor_msgs::msg::dds_::PointCloud2_/RIHS01_9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5/2:2:1,5:,:,:,,";

fn node_token() -> LivelinessToken {
    LivelinessToken {
        domain_id: 0,
        zid: ZID.into(),
        node_id: 0,
        entity_id: 0,
        kind: EntityKind::Node,
        enclave: "/".into(),
        namespace: "/".into(),
        node_name: "shroud_bridge".into(),
        topic: None,
    }
}

fn publisher_token() -> LivelinessToken {
    LivelinessToken {
        entity_id: 1,
        kind: EntityKind::Publisher,
        topic: Some(TopicInfo::for_message::<PointCloud2<'static>>(
            "/shroud/cloud",
            QosProfile::SENSOR_DATA,
        )),
        ..node_token()
    }
}

#[test]
fn topic_key_of_the_point_cloud() {
    let from_ros_name = topic_key(
        0,
        "/shroud/cloud",
        PointCloud2::TYPE_NAME,
        PointCloud2::TYPE_HASH,
    )
    .unwrap();
    assert_eq!(from_ros_name, POINT_CLOUD2_KEY);
    let from_dds_name = topic_key(
        0,
        "shroud/cloud",
        "sensor_msgs::msg::dds_::PointCloud2_",
        PointCloud2::TYPE_HASH,
    );
    assert_eq!(from_dds_name.unwrap(), POINT_CLOUD2_KEY);
    assert!(
        topic_key(42, "/a", "std_msgs/msg/Float64", Float64::TYPE_HASH)
            .unwrap()
            .starts_with("42/a/std_msgs::msg::dds_::Float64_/RIHS01_705ba9c3")
    );
}

#[test]
fn topic_names_follow_ros_rules() {
    for bad in [
        "", "/", "a//b", "a/", "/a b", "a/1b", "~/a", "a/{node}", "é",
    ] {
        let error = topic_key(0, bad, Float64::TYPE_NAME, Float64::TYPE_HASH).unwrap_err();
        assert!(
            matches!(error, RmwError::TopicName { .. }),
            "{bad:?}: {error}"
        );
        assert!(error.to_string().contains(&format!("{bad:?}")), "{error}");
    }
    assert_eq!(validate_topic_name("/tf_static").unwrap(), "tf_static");
    assert_eq!(validate_topic_name("a1/_b/C").unwrap(), "a1/_b/C");
}

#[test]
fn topic_keys_refuse_bad_types_and_hashes() {
    for (type_name, hash) in [
        ("sensor_msgs/PointCloud2", "RIHS01_x"),
        ("a::b", ""),
        ("a::b", "RIHS01/x"),
        ("a::*", "h"),
    ] {
        let error = topic_key(0, "a", type_name, hash).unwrap_err();
        assert!(matches!(error, RmwError::KeyPart { .. }), "{error}");
    }
}

#[test]
fn tokens_are_written_as_ros2_md_quotes() {
    assert_eq!(node_token().to_keyexpr(), NODE_TOKEN);
    assert_eq!(publisher_token().to_keyexpr(), PUBLISHER_TOKEN);
    assert_eq!(
        liveliness_subscription_key(0),
        "@ros2_lv/0/**",
        "liveliness_utils.cpp's subscription_token"
    );
}

#[test]
fn tokens_parse_into_their_fields() {
    assert_eq!(LivelinessToken::parse(NODE_TOKEN).unwrap(), node_token());
    let publisher = LivelinessToken::parse(PUBLISHER_TOKEN).unwrap();
    assert_eq!(publisher, publisher_token());
    let topic = publisher.topic.unwrap();
    assert_eq!(topic.name, "/shroud/cloud");
    assert_eq!(topic.type_name, "sensor_msgs::msg::dds_::PointCloud2_");
    assert_eq!(topic.qos.reliability, Reliability::BestEffort);
    assert_eq!(topic.qos.history, History::KeepLast(5));
}

#[test]
fn namespaced_tokens_mangle_every_slash() {
    let token = LivelinessToken {
        namespace: "/robot/arm".into(),
        enclave: "/secure".into(),
        ..publisher_token()
    };
    let keyexpr = token.to_keyexpr();
    assert!(
        keyexpr.contains("/MP/%secure/%robot%arm/shroud_bridge/%shroud%cloud/"),
        "{keyexpr}"
    );
    assert_eq!(LivelinessToken::parse(&keyexpr).unwrap(), token);
}

#[test]
fn malformed_tokens_are_refused_with_the_reason() {
    let cases = [
        (NODE_TOKEN.replace("/NN/", "/XX/"), "kind"),
        (NODE_TOKEN.replace("@ros2_lv", "@ros2"), "@ros2_lv"),
        (NODE_TOKEN.replace("/%/%/", "//%/"), "empty"),
        (format!("{NODE_TOKEN}/extra"), "9"),
        (PUBLISHER_TOKEN.replace("/2:2:1,5:,:,:,,", ""), "13"),
        (PUBLISHER_TOKEN.replace("2:2:1,5:,:,:,,", "2:2:1,5"), "QoS"),
        (
            NODE_TOKEN.replace("@ros2_lv/0/", "@ros2_lv/-1/"),
            "domain id",
        ),
        (NODE_TOKEN.replace("/0/0/NN", "/+0/0/NN"), "node id"),
        ("@ros2_lv/0/zid".to_string(), "segments"),
        (String::new(), "empty"),
    ];
    for (token, reason) in cases {
        let error = LivelinessToken::parse(&token).unwrap_err();
        assert!(matches!(error, RmwError::Token { .. }), "{token}: {error}");
        assert!(
            error.to_string().contains(reason),
            "{token}: {error} lacks {reason:?}"
        );
    }
}

#[test]
fn qos_strings() {
    assert_eq!(QosProfile::SENSOR_DATA.to_keyexpr(), "2:2:1,5:,:,:,,");
    assert_eq!(QosProfile::DEFAULT.to_keyexpr(), "1:2:1,10:,:,:,,");
    let latched = QosProfile {
        reliability: Reliability::Reliable,
        durability: Durability::TransientLocal,
        history: History::KeepAll,
    };
    assert_eq!(latched.to_keyexpr(), "1:1:2,:,:,:,,");
    for profile in [QosProfile::SENSOR_DATA, QosProfile::DEFAULT, latched] {
        assert_eq!(QosProfile::parse(&profile.to_keyexpr()).unwrap(), profile);
    }
}

#[test]
fn qos_empty_fields_are_rmw_zenoh_defaults() {
    // qos.cpp@7efeee2b: reliable, volatile, keep last 42.
    let defaults = QosProfile {
        reliability: Reliability::Reliable,
        durability: Durability::Volatile,
        history: History::KeepLast(RMW_ZENOH_DEFAULT_DEPTH),
    };
    assert_eq!(QosProfile::parse("::,:,:,:,,").unwrap(), defaults);
    // Explicit deadline, lifespan and liveliness numbers are accepted.
    assert_eq!(QosProfile::parse("::,:1,2:3,4:1,5,6").unwrap(), defaults);
}

#[test]
fn qos_malformed_strings_name_the_problem() {
    for (qos, reason) in [
        ("2:2:1,5:,:,", "parts"),
        ("3:2:1,5:,:,:,,", "reliability"),
        ("2:9:1,5:,:,:,,", "durability"),
        ("2:2:7,5:,:,:,,", "history"),
        ("2:2:1:,:,:,,", "history"),
        ("2:2:1,x:,:,:,,", "depth"),
        ("2:2:1,99999999999:,:,:,,", "depth"),
        ("2:2:1,5:,:,:,", "liveliness"),
        ("2:2:1,5:-1,:,:,,", "deadline"),
    ] {
        let error = QosProfile::parse(qos).unwrap_err();
        assert!(
            error.to_string().contains(reason),
            "{qos}: {error} lacks {reason:?}"
        );
    }
}

#[test]
fn attachment_layout() {
    let attachment = Attachment {
        sequence_number: 1,
        source_timestamp_ns: 0x0102_0304_0506_0708,
        gid: [
            0xA0, 0xA1, 0xA2, 0xA3, 0xA4, 0xA5, 0xA6, 0xA7, 0xA8, 0xA9, 0xAA, 0xAB, 0xAC, 0xAD,
            0xAE, 0xAF,
        ],
    };
    // i64 LE | i64 LE | 0x10 | 16-byte gid (ros2.md, attachment_helpers.cpp@534747dc).
    let expected: [u8; 33] = [
        0x01, 0, 0, 0, 0, 0, 0, 0, //
        0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01, //
        0x10, //
        0xA0, 0xA1, 0xA2, 0xA3, 0xA4, 0xA5, 0xA6, 0xA7, 0xA8, 0xA9, 0xAA, 0xAB, 0xAC, 0xAD, 0xAE,
        0xAF,
    ];
    assert_eq!(attachment.encode(), expected);
    assert_eq!(Attachment::decode(&expected).unwrap(), attachment);
}

#[test]
fn attachment_errors() {
    let good = Attachment::default().encode();
    for len in [0, 1, 32, 34] {
        let mut bytes = good.to_vec();
        bytes.resize(len, 0);
        let error = Attachment::decode(&bytes).unwrap_err();
        assert_eq!(error, RmwError::AttachmentLength { len });
        assert!(error.to_string().contains("33"));
    }
    let mut bad_marker = good;
    bad_marker[16] = 0x0F;
    assert_eq!(
        Attachment::decode(&bad_marker).unwrap_err(),
        RmwError::AttachmentGidMarker { found: 0x0F }
    );
}

#[test]
fn publisher_gid_hashes_its_token() {
    let gid = entity_gid(PUBLISHER_TOKEN);
    assert_eq!(gid, entity_gid(&publisher_token().to_keyexpr()));
    assert_ne!(gid, entity_gid(NODE_TOKEN));
}
