//! shroud as a ROS 2 node over rmw_zenoh, against a ROS 2 peer that is a real
//! zenoh session speaking rmw_zenoh's wire format (`tests/ros2/rmw_peer.py`,
//! eclipse-zenoh and rosbags from PyPI, in a venv the test makes): the peer
//! publishes PointCloud2 in several layouts and JointState with rmw_zenoh's
//! keys, tokens and attachment; `launch/ros2.toml` ingests, fits and
//! guards; the peer decodes what the bridge sends and parses its tokens as
//! rmw_zenoh's graph cache does. Keys, type names and hashes below are
//! literals from rmw_zenoh's sources and rosbags 0.11.9 (`hash_rihs01`).

mod common;

use common::launched::endpoint_of;
use common::{client_of, Proc};
use serde_json::Value;
use shroud_msg::{CloudView, NodeStatusMessage};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};
use zenoh::Wait;

const PACKAGES: [&str; 2] = ["eclipse-zenoh==1.10.2", "rosbags==0.11.9"];
const LONG: Duration = Duration::from_secs(60);

/// Literals: rmw_zenoh's DDS type names and rosbags' RIHS01 hashes.
const DIAGNOSTIC_STATUS: (&str, &str) = (
    "diagnostic_msgs::msg::dds_::DiagnosticStatus_",
    "RIHS01_b0e3e692ea2d54a8af2f4ef1930e81556a2db55216b771f8a7d2724ed47bf0e4",
);
const MARKER_ARRAY: (&str, &str) = (
    "visualization_msgs::msg::dds_::MarkerArray_",
    "RIHS01_86cb8800b6fb05b5eff1abd7a56f62a5641d3ae9a1c29e78e67e704f1d067dcf",
);
const FLOAT64: (&str, &str) = (
    "std_msgs::msg::dds_::Float64_",
    "RIHS01_705ba9c3d1a09df43737eb67095534de36fd426c0587779bda2bc51fe790182a",
);
const POINT_CLOUD2: (&str, &str) = (
    "sensor_msgs::msg::dds_::PointCloud2_",
    "RIHS01_9198cabf7da3796ae6fe19c4cb3bdd3525492988c70522628af5daa124bae2b5",
);
const JOINT_STATE: (&str, &str) = (
    "sensor_msgs::msg::dds_::JointState_",
    "RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e",
);

fn python() -> PathBuf {
    common::python::python_with("ros2-env", &PACKAGES)
}

fn script(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/ros2")
        .join(name)
}

/// `launch/ros2.toml` without its rmw_zenohd endpoint (the peer joins
/// through the launcher's), in a temp dir.
fn launch_file(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/launch/ros2.toml"))
        .unwrap()
        .replace("connect = [\"tcp/127.0.0.1:7447\"]", "connect = []")
        .replace(
            "camera_range = 6.0",
            "camera_range = 6.0\npublish_mount_tf = true",
        );
    let path = dir.join("ros2.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs the peer for `seconds` with `args`; its JSON report.
fn peer(endpoint: &str, seconds: f64, args: &[&str], dir: &Path) -> Value {
    let report = dir.join(format!("report-{}.json", args.join("_").replace('-', "")));
    let out = Command::new(python())
        .arg(script("rmw_peer.py"))
        .args(["--connect", endpoint, "--seconds", &seconds.to_string()])
        .arg("--report")
        .arg(&report)
        .args(args)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "rmw_peer.py {args:?} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap()
}

fn received<'a>(report: &'a Value, topic: &str) -> &'a Value {
    &report["received"][topic]
}

fn count(report: &Value, topic: &str) -> u64 {
    received(report, topic)["count"].as_u64().unwrap_or(0)
}

/// Every sample of every topic came with a valid attachment, in order,
/// and decoded.
fn assert_well_formed(report: &Value) {
    for (topic, stats) in report["received"].as_object().unwrap() {
        for field in ["bad_attachment", "undecodable"] {
            assert_eq!(stats[field], 0, "{topic}: {field}: {stats}");
        }
    }
    assert_eq!(report["other_hash"], 0, "samples with another type hash");
    for (topic, stats) in report["received"].as_object().unwrap() {
        assert_eq!(stats["sequence_not_increasing"], 0, "{topic}: {stats}");
    }
    let errors = report["callback_errors"].as_array().map_or(0, Vec::len);
    assert_eq!(
        errors, 0,
        "the peer's callbacks failed: {}",
        report["callback_errors"]
    );
}

/// The verdicts the peer decoded, by name.
fn verdicts(report: &Value) -> Vec<String> {
    received(report, "/shroud/verdict")["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["values"]["verdict"].as_str().unwrap().to_owned())
        .collect()
}

/// The bridge's publishers as the peer's graph cache parsed them from its
/// liveliness tokens.
fn bridge_publishers(report: &Value) -> Vec<(String, String, String)> {
    report["graph"]["publishers"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["node"] == "shroud_bridge")
        .map(|p| {
            let s = |k: &str| p[k].as_str().unwrap_or_default().to_owned();
            (s("topic"), s("dds_type"), s("type_hash"))
        })
        .collect()
}

/// A counter of the bridge's latest status.
fn bridge_counter(session: &zenoh::Session, counter: &str) -> u64 {
    bridge_counter_if_heard(session, counter).expect("a status of the bridge within 5 s")
}

/// The bridge's `counter` from its next status, if one comes within 5 s.
fn bridge_counter_if_heard(session: &zenoh::Session, counter: &str) -> Option<u64> {
    let status = session
        .declare_subscriber("shroud/ros2/status/ros2")
        .wait()
        .unwrap();
    let sample = status.recv_timeout(Duration::from_secs(5)).ok()??;
    let message = NodeStatusMessage::from_bytes(&sample.payload().to_bytes()).ok()?;
    Some(message.counter(counter))
}

#[test]
fn a_ros2_robot_feeds_shroud_and_hears_its_verdicts_markers_and_tokens() {
    let dir = tempfile::tempdir().unwrap();
    let python = python();
    assert!(python.exists());
    let file = launch_file(dir.path());
    let mut launcher = Proc::start(&["launch", file.to_str().unwrap(), "--duration", "60"]);
    let endpoint = endpoint_of(&launcher);
    let session = client_of(&endpoint);
    let clouds = session
        .declare_subscriber("shroud/ros2/cloud/camera")
        .wait()
        .unwrap();

    // Every layout a driver publishes, over a floor far below the arm.
    for layout in [
        "xyz32",
        "xyzi_padded",
        "xyz64",
        "big_endian",
        "organised_nan",
    ] {
        let report = peer(
            &endpoint,
            5.0,
            &["--layout", layout, "--plane-z", "0"],
            dir.path(),
        );
        assert_well_formed(&report);
        let published = report["published"]["/points"].as_u64().unwrap();
        assert!(published >= 30, "{layout}: {published} clouds sent");
        assert!(count(&report, "/shroud/verdict") > 50, "{layout}: {report}");
        assert!(count(&report, "/shroud/speed_scale") > 50, "{layout}");
        assert!(
            count(&report, "/shroud/surrogates") > 0,
            "{layout}: no surrogate markers"
        );
        assert!(
            count(&report, "/shroud/arm_clearance") > 0,
            "{layout}: no arm markers"
        );
        let last = verdicts(&report).last().cloned().unwrap();
        assert_eq!(
            last,
            "clear",
            "{layout}: {}",
            received(&report, "/shroud/verdict")
        );
        let markers = &received(&report, "/shroud/surrogates")["samples"][0]["markers"][0];
        assert_eq!(markers["type"], 11, "a TRIANGLE_LIST: {markers}");
        assert!(markers["points"].as_u64().unwrap() >= 3, "{markers}");
        assert_eq!(markers["frame_id"], "world");
    }
    // The organised cloud's dark block (rows 70..90, columns 90..120 of the
    // peer's 128 x 96 image) reached shroud as an unseen cone. Its centre's
    // direction by depth_image_proc's model ((u - cx) / fx, fx = (W / 2) /
    // tan(hfov / 2), cx = W / 2), from the optical frame (z forward, y down)
    // to the world (the camera looks down: x, -y, -z).
    let (fx, fy) = (
        64.0 / 45f64.to_radians().tan(),
        48.0 / 35f64.to_radians().tan(),
    );
    let (u, v) = (105.0 - 64.0, 80.0 - 48.0);
    let block = glam::DVec3::new(u / fx, -(v / fy), -1.0).normalize();
    let mut stated = false;
    while let Ok(Some(sample)) = clouds.try_recv() {
        let bytes = sample.payload().to_bytes();
        let cloud = CloudView::from_bytes(&bytes).unwrap();
        let covers = |nr: &shroud_msg::NoReturn| {
            nr.cones
                .iter()
                .any(|c| glam::DVec3::from_array(c.axis).angle_between(block) <= c.half_angle)
        };
        stated |= cloud.field_of_view.is_some() && cloud.no_return.as_ref().is_some_and(covers);
    }
    assert!(
        stated,
        "no cloud stated the dark block's direction as unseen"
    );
    assert!(bridge_counter(&session, "ros2_empty_rays") > 0);

    // A floor raised into the arm: the guard stops it, on the ROS side too.
    let report = peer(&endpoint, 4.0, &["--plane-z", "1.2"], dir.path());
    let seen = verdicts(&report);
    assert_eq!(seen.last().map(String::as_str), Some("stop"), "{seen:?}");
    let speed = &received(&report, "/shroud/speed_scale")["samples"];
    assert_eq!(speed.as_array().unwrap().last().unwrap()["data"], 0.0);

    // The bridge is in the ROS graph with its entities' types and hashes.
    let publishers = bridge_publishers(&report);
    for (topic, (dds, hash)) in [
        ("/shroud/verdict", DIAGNOSTIC_STATUS),
        ("/shroud/speed_scale", FLOAT64),
        ("/shroud/surrogates", MARKER_ARRAY),
        ("/shroud/arm_clearance", MARKER_ARRAY),
    ] {
        let entry = (topic.to_owned(), dds.to_owned(), hash.to_owned());
        assert!(
            publishers.contains(&entry),
            "{entry:?} not in {publishers:?}"
        );
    }
    let subscriptions: Vec<(String, String)> = report["graph"]["subscriptions"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["node"] == "shroud_bridge")
        .map(|p| {
            let s = |k: &str| p[k].as_str().unwrap_or_default().to_owned();
            (s("topic"), s("type_hash"))
        })
        .collect();
    for (topic, (_, hash)) in [("/points", POINT_CLOUD2), ("/joint_states", JOINT_STATE)] {
        assert!(
            subscriptions.contains(&(topic.to_owned(), hash.to_owned())),
            "{topic} not in {subscriptions:?}"
        );
    }
    assert_eq!(report["graph"]["rejected"].as_array().unwrap().len(), 0);
    let tf = &received(&report, "/tf_static")["samples"][0];
    assert!(tf.to_string().contains("camera_optical"), "{tf}");

    // Malformed samples: counted and named, and the bridge lives on.
    let before = bridge_counter(&session, "dropped_malformed");
    let bad_before = bridge_counter(&session, "ros2_bad_attachment");
    peer(
        &endpoint,
        4.0,
        // No good clouds beside the bad one: a cloud the bridge's one-slot
        // queue drops is counted as a backlog drop, not as malformed.
        &["--malformed", "--no-clouds", "--plane-z", "0"],
        dir.path(),
    );
    // The bridge's status comes once a second, later on a loaded machine.
    let counted = |counter: &str, at_least: u64| {
        let deadline = std::time::Instant::now() + Duration::from_secs(15);
        loop {
            let now = bridge_counter_if_heard(&session, counter).unwrap_or(0);
            if now >= at_least || std::time::Instant::now() > deadline {
                return now;
            }
        }
    };
    let bad = counted("ros2_bad_attachment", bad_before + 2);
    assert!(
        bad >= bad_before + 2,
        "ros2_bad_attachment {bad_before} -> {bad}"
    );
    let malformed = counted("dropped_malformed", before + 3);
    assert!(
        malformed >= before + 3,
        "dropped_malformed {before} -> {malformed}"
    );
    let output = launcher.output();
    for needle in [
        "without rmw_zenoh's attachment",
        "JointState",
        "PointCloud2",
    ] {
        assert!(
            output.contains(needle),
            "no {needle:?} in the log:\n{output}"
        );
    }
    assert!(!output.contains("panicked"), "{output}");
    drop(launcher.child.kill());
    let _ = launcher.wait_exit(LONG);
}

#[test]
fn shroud_clouds_reach_ros_as_point_cloud2() {
    let dir = tempfile::tempdir().unwrap();
    python();
    let hub = common::free_port();
    let endpoint = format!("tcp/127.0.0.1:{hub}");
    let _hub = common::hub(&endpoint);
    let wiring = [
        "--namespace",
        "r2c",
        "--connect",
        &endpoint,
        "--multicast",
        "off",
    ];
    let mut scanner = Proc::start(
        &[
            &["node", "scanner", "--stream", "camera", "--points", "2000"][..],
            &wiring,
        ]
        .concat(),
    );
    let mut bridge =
        Proc::start(&[&["node", "ros2", "--publish-cloud", "camera"][..], &wiring].concat());
    let start = Instant::now();
    let report = peer(&endpoint, 5.0, &["--no-clouds", "--no-joints"], dir.path());
    assert_well_formed(&report);
    let clouds = received(&report, "/shroud/cloud/camera");
    assert!(clouds["count"].as_u64().unwrap() > 3, "{report}");
    let first = &clouds["samples"][0];
    assert_eq!(first["frame_id"], "world", "{first}");
    assert_eq!(first["height"], 1);
    assert!(first["width"].as_u64().unwrap() > 100, "{first}");
    assert_eq!(first["all_finite"], true, "{first}");
    let publishers = bridge_publishers(&report);
    let entry = (
        "/shroud/cloud/camera".to_owned(),
        POINT_CLOUD2.0.to_owned(),
        POINT_CLOUD2.1.to_owned(),
    );
    assert!(publishers.contains(&entry), "{publishers:?}");
    assert!(start.elapsed() < LONG);
    for p in [&mut scanner, &mut bridge] {
        let _ = p.child.kill();
        let _ = p.wait_exit(LONG);
    }
}
