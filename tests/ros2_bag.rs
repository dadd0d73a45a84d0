//! ROS 2 recordings (rosbag2, MCAP storage), end to end with real processes:
//! a bag written by rosbags (tests/ros2/write_bag.py: a camera 3 m up looking
//! down at a plane, and the demo arm's joint states) replays through a fit
//! node and the guard with the verdicts the plane's height calls for, as a
//! bag directory and as a bare `.mcap`; `shroud record --ros2` of that graph
//! writes a ROS 2 file that rosbags reads back; a truncated bag, garbage
//! CDR, a mapped topic of another type, another message encoding or no
//! schema are named errors or counted drops, never a panic.

mod common;

use common::python::python_with;
use common::status_board::StatusBoard;
use common::{hub_on_free_port, inbox, wiring, Proc};
use shroud_msg::{CollisionMessage, GuardVerdict};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

const LONG: Duration = Duration::from_secs(30);
const ARM_FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/launch/arms/demo_arm.toml");
/// The camera of write_bag.py: 3 m up, its optical frame turned 180 degrees
/// about x (looking straight down).
const MOUNT: &str = "0,0,3,1,0,0,0";

fn python() -> PathBuf {
    python_with("ros2-env", &["eclipse-zenoh==1.10.2", "rosbags==0.11.9"])
}

fn script(name: &str) -> String {
    format!("{}/tests/ros2/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// Writes a bag of `seconds` with the plane at `plane_z` to `out` (a bag
/// directory; with `mcap_only`, `out.mcap`); returns what to replay.
fn write_bag(out: &Path, plane_z: f64, seconds: f64, mcap_only: bool) -> PathBuf {
    let mut command = Command::new(python());
    command.arg(script("write_bag.py")).arg(out).args([
        "--plane-z",
        &plane_z.to_string(),
        "--seconds",
        &seconds.to_string(),
    ]);
    if mcap_only {
        command.arg("--mcap-only");
    }
    let done = command.output().expect("write_bag.py runs");
    assert!(
        done.status.success(),
        "write_bag.py: {}",
        String::from_utf8_lossy(&done.stderr)
    );
    match mcap_only {
        true => PathBuf::from(format!("{}.mcap", out.display())),
        false => out.to_path_buf(),
    }
}

/// The replay's arguments for write_bag.py's topics.
fn replay_args(input: &Path) -> Vec<String> {
    [
        "replay",
        s(input),
        "--ros2-topic",
        "/points=cloud/camera",
        "--ros2-topic",
        "/joint_states=joints/demo_arm",
        "--arm-file",
        ARM_FILE,
        "--cloud-mount",
        MOUNT,
        "--camera-fov",
        "90,70",
        "--camera-range",
        "6",
    ]
    .iter()
    .map(|a| a.to_string())
    .collect()
}

fn start(args: &[&str], wiring: &[&str]) -> Proc {
    Proc::start(&[args, wiring].concat())
}

/// Replays `input` (restamped, at twice real time) into a fit node and the
/// guard; with `record`, a recorder with `--ros2` writes it to that file.
/// Returns the verdicts by name.
fn replay_through_guard(input: &Path, ns: &str, record: Option<&Path>) -> BTreeMap<String, u64> {
    let (endpoint, session) = hub_on_free_port();
    let w = wiring(&endpoint, ns);
    let verdicts = inbox(&session, format!("shroud/{ns}/collision/demo_arm"));
    let board = StatusBoard::new(&session, ns);
    let mut recorder = record.map(|file| {
        let args = [
            "record",
            "-o",
            s(file),
            "--ros2",
            "--topics",
            "cloud/*,joints/*,collision/*",
            "--foxglove",
            "false",
        ];
        start(&args, &w)
    });
    let fit = start(
        &[
            "node", "fit", "--input", "camera", "--grid", "20x20", "--side", "sandwich",
        ],
        &w,
    );
    let guard = start(
        &[
            "node",
            "guard",
            "--arm-file",
            ARM_FILE,
            "--surrogate",
            "camera",
        ],
        &w,
    );
    for node in ["fit", "guard"].iter().chain(record.map(|_| &"record")) {
        board.wait_for(node, "a status", LONG, |_| true);
    }
    let mut args = replay_args(input);
    args.extend(["--restamp", "--speed", "2", "--wait-subscribers", "10"].map(String::from));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let mut replay = start(&args, &w);
    let status = replay.wait_exit(LONG);
    assert!(status.success(), "replay:\n{}", replay.output());
    // The last joint states' verdicts.
    std::thread::sleep(Duration::from_millis(300));
    let mut seen = BTreeMap::new();
    while let Ok(Some(sample)) = verdicts.try_recv() {
        let msg = CollisionMessage::from_bytes(&sample.payload().to_bytes()).expect("a verdict");
        *seen.entry(msg.verdict.name().to_owned()).or_insert(0) += 1;
        *seen
            .entry(format!(
                "DEBUG {} {} {} {}",
                msg.reason, msg.limiting_link, msg.views, msg.unobserved
            ))
            .or_insert(0) += 1;
    }
    assert!(
        !seen.is_empty(),
        "no verdict:\n{}\n---\n{}\n---\n{}",
        replay.output(),
        fit.output(),
        guard.output()
    );
    assert!(!replay.output().contains("panicked"), "{}", replay.output());
    assert!(
        replay
            .output()
            .contains("/joint_states: joint \"gripper_finger\" is not a joint"),
        "{}",
        replay.output()
    );
    if let Some(recorder) = recorder.as_mut() {
        recorder.signal(libc::SIGINT);
        assert!(recorder.wait_exit(LONG).success(), "{}", recorder.output());
    }
    seen
}

fn count(seen: &BTreeMap<String, u64>, verdict: GuardVerdict) -> u64 {
    seen.get(verdict.name()).copied().unwrap_or(0)
}

/// A bag directory with the plane on the floor replays to `clear` verdicts;
/// `shroud record --ros2` of that graph is read back by rosbags with its
/// clouds, joint states and verdicts decoded.
#[test]
fn a_bag_directory_replays_to_clear_and_a_ros2_recording_of_it_reads_in_rosbags() {
    let dir = tempfile::tempdir().unwrap();
    let bag = write_bag(&dir.path().join("floor"), 0.0, 4.0, false);
    let recording = dir.path().join("run.mcap");
    let seen = replay_through_guard(&bag, "bag-floor", Some(&recording));
    assert!(count(&seen, GuardVerdict::Clear) > 0, "{seen:?}");
    assert_eq!(count(&seen, GuardVerdict::Stop), 0, "{seen:?}");

    let ros_file = dir.path().join("run.ros2.mcap");
    let read = Command::new(python())
        .arg(script("read_bag.py"))
        .arg(&ros_file)
        .output()
        .expect("read_bag.py runs");
    let text = String::from_utf8_lossy(&read.stdout);
    assert!(
        read.status.success(),
        "read_bag.py: {}",
        String::from_utf8_lossy(&read.stderr)
    );
    let json: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let connections = json["connections"].as_array().expect("connections");
    let by_topic = |topic: &str| {
        connections
            .iter()
            .find(|c| c["topic"] == topic)
            .unwrap_or_else(|| panic!("no {topic} in {text}"))
    };
    let cloud = by_topic("/shroud/cloud/camera");
    assert_eq!(cloud["msgtype"], "sensor_msgs/msg/PointCloud2");
    assert_eq!(cloud["first"]["frame_id"], "world", "{text}");
    let joints = by_topic("/shroud/joints/demo_arm");
    assert_eq!(joints["msgtype"], "sensor_msgs/msg/JointState");
    let verdict = by_topic("/shroud/verdict/demo_arm");
    assert_eq!(verdict["msgtype"], "diagnostic_msgs/msg/DiagnosticStatus");
    for c in [cloud, joints, verdict] {
        assert!(c["count"].as_u64().unwrap() > 0, "{text}");
        assert!(!c["first"].is_null(), "decoded: {text}");
    }
}

/// A bare `.mcap` with the plane across the hanging arm replays to `stop`.
#[test]
fn a_bare_mcap_with_the_plane_through_the_arm_replays_to_stop() {
    let dir = tempfile::tempdir().unwrap();
    let bag = write_bag(&dir.path().join("high"), 0.5, 4.0, true);
    let seen = replay_through_guard(&bag, "bag-high", None);
    assert!(count(&seen, GuardVerdict::Stop) > 0, "{seen:?}");
    assert_eq!(count(&seen, GuardVerdict::Clear), 0, "{seen:?}");
}

/// Rewrites the bare bag `from` into `to`, each message through `change`
/// (topic, payload) -> payload, with the channels of `topic` given another
/// message encoding, or no schema.
fn rewrite(
    from: &Path,
    to: &Path,
    change: impl Fn(&str, &[u8]) -> Vec<u8>,
    encoding_of: impl Fn(&str) -> Option<(&str, bool)>,
) {
    let bytes = std::fs::read(from).unwrap();
    let mut out =
        mcap::Writer::new(std::io::BufWriter::new(std::fs::File::create(to).unwrap())).unwrap();
    let mut channels = BTreeMap::new();
    for message in mcap::MessageStream::new(&bytes).unwrap() {
        let message = message.unwrap();
        let topic = message.channel.topic.clone();
        let id = *channels.entry(topic.clone()).or_insert_with(|| {
            let (encoding, schema) =
                encoding_of(&topic).unwrap_or((&message.channel.message_encoding, true));
            let schema_id = match (schema, &message.channel.schema) {
                (true, Some(s)) => out.add_schema(&s.name, &s.encoding, &s.data).unwrap(),
                _ => 0,
            };
            out.add_channel(schema_id, &topic, encoding, &BTreeMap::new())
                .unwrap()
        });
        let header = mcap::records::MessageHeader {
            channel_id: id,
            sequence: message.sequence,
            log_time: message.log_time,
            publish_time: message.publish_time,
        };
        out.write_to_known_channel(&header, &change(&topic, &message.data))
            .unwrap();
    }
    out.finish().unwrap();
}

/// `shroud replay` of `input` as fast as it goes, on its own; its exit and
/// output.
fn replay_alone(input: &Path, extra: &[&str]) -> (bool, String) {
    let mut args = replay_args(input);
    args.extend(["--max", "--multicast", "off"].map(String::from));
    args.extend(extra.iter().map(|a| a.to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let mut replay = Proc::start(&args);
    let ok = replay.wait_exit(LONG).success();
    let output = replay.output();
    assert!(!output.contains("panicked"), "{output}");
    (ok, output)
}

#[test]
fn broken_bags_are_named_errors_or_counted_drops() {
    let started = Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let bag = write_bag(&dir.path().join("bag"), 0.0, 2.0, true);

    // Garbage CDR in every cloud: each is dropped, counted and named; the
    // joint states replay.
    let garbage = dir.path().join("garbage.mcap");
    let junk = |topic: &str, data: &[u8]| match topic {
        "/points" => [&data[..4], &[0xff; 40][..]].concat(),
        _ => data.to_vec(),
    };
    rewrite(&bag, &garbage, junk, |_| None);
    let (ok, output) = replay_alone(&garbage, &[]);
    assert!(ok, "{output}");
    let drops = output.matches("dropped a malformed message").count();
    assert_eq!(drops, 20, "every cloud of 2 s at 10 Hz: {output}");
    assert!(output.contains("PointCloud2: "), "{output}");

    // A mapped topic of another type, another message encoding, no schema:
    // refused before anything is published, naming the topic.
    let mut wrong_type = replay_args(&bag);
    wrong_type[3] = "/joint_states=cloud/camera".into();
    wrong_type[5] = "/points=joints/demo_arm".into();
    let args: Vec<&str> = wrong_type.iter().map(String::as_str).collect();
    let mut p = Proc::start(&[&args[..], &["--max", "--multicast", "off"]].concat());
    assert!(!p.wait_exit(LONG).success());
    assert!(
        p.output()
            .contains("but joints/demo_arm takes sensor_msgs/msg/JointState"),
        "{}",
        p.output()
    );
    for (name, change) in [("json", ("json", true)), ("schemaless", ("cdr", false))] {
        let file = dir.path().join(format!("{name}.mcap"));
        rewrite(
            &bag,
            &file,
            |_, d| d.to_vec(),
            |t| (t == "/points").then_some(change),
        );
        let (ok, output) = replay_alone(&file, &[]);
        assert!(!ok, "{name}: {output}");
        assert!(output.contains("\"/points\""), "{name}: {output}");
    }

    // A truncated bag replays up to its cut, with a warning; cut inside its
    // first chunk, nothing is left: an error, never a panic.
    let whole = std::fs::read(&bag).unwrap();
    let cut = dir.path().join("cut.mcap");
    std::fs::write(&cut, &whole[..whole.len() * 3 / 4]).unwrap();
    let (_, output) = replay_alone(&cut, &[]);
    assert!(output.contains("truncated"), "{output}");
    std::fs::write(&cut, &whole[..200]).unwrap();
    let (ok, output) = replay_alone(&cut, &[]);
    assert!(!ok && output.contains("nothing to replay"), "{output}");

    // A directory that is not a bag; a foreign file.
    let (ok, output) = replay_alone(dir.path(), &[]);
    assert!(!ok && output.contains("metadata.yaml"), "{output}");
    let foreign = dir.path().join("x.mcap");
    std::fs::write(&foreign, b"not an mcap file at all").unwrap();
    let (ok, output) = replay_alone(&foreign, &[]);
    assert!(!ok && output.contains("not an MCAP file"), "{output}");
    eprintln!("broken bags: {:.1} s", started.elapsed().as_secs_f64());
}
