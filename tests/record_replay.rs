//! Record and replay (MCAP), end to end with real processes over real zenoh:
//! a replayed recording makes a fresh fit node publish the very surrogates
//! that were recorded; a recorder killed with SIGKILL leaves a file that
//! `shroud mcap info` reads as truncated, with what its complete chunks hold;
//! a full disk ends the recording with a finished file; Python's `mcap`
//! package reads a recording, and Lichtblick's MCAP loader decodes its
//! Foxglove views.

mod common;

use common::status_board::StatusBoard;
use common::{hub_on_free_port, inbox, wiring, Proc};
use shroud_msg::{CloudMessage, SurrogateMessage};
use shroud_surrogate::SurrogateWire;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

const LONG: Duration = Duration::from_secs(60);

fn shroud(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shroud"))
        .args(args)
        .output()
        .expect("the shroud binary runs")
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// The payloads of a finished MCAP file by topic, in file order.
fn recorded(path: &Path) -> BTreeMap<String, Vec<Vec<u8>>> {
    let bytes = std::fs::read(path).unwrap();
    let mut by_topic: BTreeMap<String, Vec<Vec<u8>>> = BTreeMap::new();
    for message in mcap::MessageStream::new(&bytes).expect("an MCAP file") {
        let message = message.expect("a readable message");
        by_topic
            .entry(message.channel.topic.clone())
            .or_default()
            .push(message.data.into_owned());
    }
    by_topic
}

/// A surrogate's bytes with the times the fit node measures, `fit_ns` and
/// `pipeline_ns`, set to zero; checked first to re-encode to exactly the bytes
/// received (so that equal results mean byte-identical messages but for those
/// two fields).
fn without_measured_times(bytes: &[u8]) -> Vec<u8> {
    let (mut surrogate, _) = SurrogateMessage::from_bytes(bytes).expect("a surrogate");
    assert_eq!(surrogate.to_bytes().unwrap(), bytes, "re-encodes exactly");
    surrogate.fit_ns = 0;
    surrogate.pipeline_ns = 0;
    surrogate.to_bytes().unwrap()
}

fn start(args: &[&str], wiring: &[&str]) -> Proc {
    Proc::start(&[args, wiring].concat())
}

/// Records `frames` frames of a scanner through a fit node, recorder first
/// (so that the recorded fit node starts cold, as a fresh one will).
fn record_demo(
    (session, endpoint): (&zenoh::Session, &str),
    ns: &str,
    file: &Path,
    frames: u64,
) -> String {
    let board = StatusBoard::new(session, ns);
    let w = wiring(endpoint, ns);
    let mut recorder = start(
        &[
            "record",
            "-o",
            s(file),
            "--topics",
            "cloud/*,surrogate/*,status/*",
            // A view of every cloud and surrogate (at 5 Hz, jitter could
            // otherwise pace one out).
            "--foxglove-rate",
            "1000",
        ],
        &w,
    );
    board.wait_for("record", "its own status recorded", LONG, |st| {
        st.counter("received") > 0
    });
    let surrogates = inbox(session, format!("shroud/{ns}/surrogate/s"));
    let _fit = start(&["node", "fit", "--input", "s", "--grid", "12x12"], &w);
    board.wait_for("fit", "a status", LONG, |_| true);
    let frames_arg = frames.to_string();
    let mut scanner = start(
        &[
            "node",
            "scanner",
            "--points",
            "3000",
            "--rate",
            "5",
            "--stream",
            "s",
            "--frames",
            &frames_arg,
            // Its first cloud waits until the recorder and the fit node are
            // known (a zenoh peer drops what goes before).
            "--wait-subscribers",
            "30",
        ],
        &w,
    );
    assert!(scanner.wait_exit(LONG).success(), "{}", scanner.output());
    // The last cloud's surrogate ends the run (the fit node's status
    // counters lag its work); the recorder hears it through the same hub at
    // about the same time, and gets a second to queue it.
    let deadline = Instant::now() + LONG;
    loop {
        assert!(Instant::now() < deadline, "no surrogate of the last cloud");
        let Ok(Some(sample)) = surrogates.recv_timeout(Duration::from_millis(200)) else {
            continue;
        };
        let bytes = sample.payload().to_bytes();
        let (msg, _) = SurrogateMessage::from_bytes(&bytes).expect("a surrogate");
        if msg.source_sequence + 1 >= frames {
            break;
        }
    }
    std::thread::sleep(Duration::from_secs(1));
    recorder.signal(libc::SIGINT);
    assert!(recorder.wait_exit(LONG).success(), "{}", recorder.output());
    recorder.output()
}

#[test]
fn replayed_clouds_give_byte_identical_surrogates() {
    let (endpoint, session) = hub_on_free_port();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("demo.mcap");
    let summary = record_demo((&session, &endpoint), "rr-record", &file, 8);
    assert!(summary.contains("recorded"), "{summary}");
    let by_topic = recorded(&file);
    let clouds = &by_topic["shroud/rr-record/cloud/s"];
    let surrogates = &by_topic["shroud/rr-record/surrogate/s"];
    // The recorded fit node fitted exactly the recorded clouds, in order: the
    // fresh one will start from the same (cold) state and see the same ones.
    let cloud_sequences: Vec<u64> = clouds
        .iter()
        .map(|c| CloudMessage::from_bytes(c).unwrap().sequence)
        .collect();
    let fitted: Vec<u64> = surrogates
        .iter()
        .map(|b| SurrogateMessage::from_bytes(b).unwrap().0.source_sequence)
        .collect();
    assert_eq!(fitted, cloud_sequences);
    assert_eq!(clouds.len() as u64, 8, "every cloud recorded");

    let info = shroud(&["mcap", "info", s(&file)]);
    let text = String::from_utf8_lossy(&info.stdout);
    assert!(info.status.success(), "{text}");
    assert!(text.contains("state:       complete"), "{text}");
    let cloud_line = format!("shroud/rr-record/cloud/s  {} msgs", clouds.len());
    assert!(text.contains(&cloud_line), "{cloud_line} in {text}");

    let ns = "rr-replay";
    let w = wiring(&endpoint, ns);
    let replayed = inbox(&session, format!("shroud/{ns}/surrogate/s"));
    let _fit = start(
        &[
            "node", "fit", "--input", "s", "--grid", "12x12", "--queue", "64",
        ],
        &w,
    );
    // By the time its status reaches us its session has had our declarations
    // (exchanged when it connected to the hub): its first surrogate will not
    // be published before it knows of our subscriber.
    StatusBoard::new(&session, ns).wait_for("fit", "a status", LONG, |_| true);
    let mut replay = start(
        &[
            "replay",
            s(&file),
            "--topics",
            "cloud/*",
            "--speed",
            "4",
            "--wait-subscribers",
            "30",
        ],
        &w,
    );
    assert!(replay.wait_exit(LONG).success(), "{}", replay.output());
    let deadline = Instant::now() + LONG;
    let mut fresh = Vec::new();
    while fresh.len() < surrogates.len() && Instant::now() < deadline {
        if let Ok(Some(sample)) = replayed.recv_timeout(Duration::from_millis(200)) {
            fresh.push(sample.payload().to_bytes().into_owned());
        }
    }
    assert_eq!(fresh.len(), surrogates.len(), "every replayed cloud fitted");
    for (i, (old, new)) in surrogates.iter().zip(&fresh).enumerate() {
        assert!(
            without_measured_times(old) == without_measured_times(new),
            "surrogate {i} differs"
        );
    }
}

#[test]
fn a_recorder_killed_mid_recording_leaves_a_file_info_reads_as_truncated() {
    let (endpoint, session) = hub_on_free_port();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("killed.mcap");
    let ns = "rr-kill";
    let board = StatusBoard::new(&session, ns);
    let w = wiring(&endpoint, ns);
    let mut recorder = start(&["record", "-o", s(&file), "--topics", "cloud/*"], &w);
    board.wait_for("record", "a status", LONG, |_| true);
    let _scanner = start(
        &[
            "node", "scanner", "--points", "20000", "--rate", "10", "--stream", "k",
        ],
        &w,
    );
    // Chunks close every second or 4 MB: after 30 clouds (3 s), some are
    // complete on disk.
    let written = board
        .wait_for("record", "30 clouds written", LONG, |st| {
            st.counter("written") >= 30
        })
        .counter("written");
    recorder.signal(libc::SIGKILL);
    recorder.wait_exit(LONG);

    let recovered = |out: &Output| -> u64 {
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert_eq!(
            out.status.code(),
            Some(3),
            "{text} {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("truncated"),
            "{out:?}"
        );
        assert!(text.contains("recovered "), "{text}");
        // The raw clouds' channel (the Foxglove views have their own).
        text.lines()
            .find_map(|l| l.split_once("shroud/rr-kill/cloud/k  "))
            .and_then(|(_, r)| r.split(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("no count of shroud/rr-kill/cloud/k in {text}"))
    };
    let first = recovered(&shroud(&["mcap", "info", s(&file)]));
    assert!(first > 0, "messages of complete chunks are readable");
    // The kill is not after the messages the status counted last: at least
    // those were written, at most those plus a second's.
    assert!(first <= written + 15, "{first} of {written}");
    // Cut inside a chunk too: fewer messages, still no crash.
    let len = std::fs::metadata(&file).unwrap().len();
    let f = std::fs::OpenOptions::new().write(true).open(&file).unwrap();
    f.set_len(len * 2 / 3).unwrap();
    let cut = recovered(&shroud(&["mcap", "info", s(&file)]));
    assert!(cut < first, "{cut} of {first}");
}

#[test]
fn a_full_disk_stops_the_recording_and_finishes_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("full.mcap");
    // A reserve no disk has: the first message (the recorder's own status)
    // finds the disk full.
    let mut recorder = Proc::start(&[
        "record",
        "-o",
        s(&file),
        "--topics",
        "status/*",
        "--min-free",
        "1000000000",
        "--multicast",
        "off",
        "--namespace",
        "rr-full",
    ]);
    let status = recorder.wait_exit(LONG);
    let output = recorder.output();
    assert!(!status.success(), "{output}");
    assert!(
        output.contains("recording stopped early (disk full)"),
        "{output}"
    );
    assert!(output.contains("disk full 1"), "{output}");
    let info = shroud(&["mcap", "info", s(&file)]);
    let text = String::from_utf8_lossy(&info.stdout);
    assert!(info.status.success(), "{text}");
    assert!(text.contains("messages:    0"), "{text}");
}

const PYTHON_MCAP: [&str; 3] = [
    "mcap==1.6.0",
    "mcap-protobuf-support==0.6.0",
    "protobuf==7.36.2",
];

/// Python's `mcap` reads a recording: its channels, schemas and counts are
/// the ones shroud wrote, and `mcap-protobuf-support` decodes its Foxglove
/// point clouds (the `--foxglove` views, on by default) into the very points
/// of the raw clouds.
#[test]
fn python_mcap_reads_a_recording() {
    let (endpoint, session) = hub_on_free_port();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("py.mcap");
    let ns = "rr-python";
    let board = StatusBoard::new(&session, ns);
    let w = wiring(&endpoint, ns);
    // Every cloud gets its Foxglove view (the scanner's 10 Hz is below this).
    let mut recorder = start(
        &[
            "record",
            "-o",
            s(&file),
            "--topics",
            "cloud/*",
            "--foxglove-rate",
            "1000",
        ],
        &w,
    );
    board.wait_for("record", "a status", LONG, |_| true);
    // A scanner that keeps publishing: the last cloud of one that exits
    // could still be on its way when the recorder stops (the counts below
    // come from the file either way).
    let _scanner = start(
        &[
            "node", "scanner", "--points", "2000", "--rate", "10", "--stream", "p",
        ],
        &w,
    );
    board.wait_for("record", "5 clouds", LONG, |st| st.counter("written") >= 5);
    recorder.signal(libc::SIGTERM);
    assert!(recorder.wait_exit(LONG).success(), "{}", recorder.output());
    let expected = recorded(&file)["shroud/rr-python/cloud/p"].len();

    let py = common::python::python_with("mcap-env", &PYTHON_MCAP);
    let script = r#"
import json, sys
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory
with open(sys.argv[1], "rb") as f:
    reader = make_reader(f, decoder_factories=[DecoderFactory()])
    summary = reader.get_summary()
    channels = {}
    for cid, ch in summary.channels.items():
        schema = summary.schemas[ch.schema_id]
        channels[ch.topic] = {
            "message_encoding": ch.message_encoding,
            "schema": schema.name,
            "schema_encoding": schema.encoding,
            "schema_data": json.loads(schema.data) if schema.encoding == "shroud-msgpack" else None,
            "count": summary.statistics.channel_message_counts.get(cid, 0),
        }
    read = sum(1 for _ in reader.iter_messages(topics=[sys.argv[2]]))
    compression = sorted({c.compression for c in summary.chunk_indexes})
    first = None
    for _, _, message, cloud in reader.iter_decoded_messages(topics=["/shroud/cloud/p"]):
        first = {
            "log_time": message.log_time,
            "frame_id": cloud.frame_id,
            "point_stride": cloud.point_stride,
            "fields": [(f.name, f.offset, f.type) for f in cloud.fields],
            "data": cloud.data.hex(),
        }
        break
    print(json.dumps({"channels": channels, "read": read, "compression": compression,
                      "first_cloud": first}))
"#;
    let out = Command::new(&py)
        .args(["-c", script, s(&file), "shroud/rr-python/cloud/p"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let cloud = &v["channels"]["shroud/rr-python/cloud/p"];
    assert_eq!(cloud["message_encoding"], "msgpack");
    assert_eq!(cloud["schema"], "shroud.CloudMessage");
    assert_eq!(cloud["schema_encoding"], "shroud-msgpack");
    assert_eq!(cloud["schema_data"]["schema_version"], 2);
    assert_eq!(cloud["count"], expected as u64);
    assert_eq!(v["read"], expected as u64);
    assert_eq!(v["compression"], serde_json::json!(["zstd"]));
    let view = &v["channels"]["/shroud/cloud/p"];
    assert_eq!(view["message_encoding"], "protobuf");
    assert_eq!(view["schema"], "foxglove.PointCloud");
    assert_eq!(view["count"], expected as u64);
    // The first view holds the first raw cloud's points (2000 < the budget,
    // no intensity), as packed little-endian f32 x y z: the same bytes.
    let first = &v["first_cloud"];
    assert_eq!(first["frame_id"], "world");
    assert_eq!(first["point_stride"], 12);
    assert_eq!(first["fields"][0], serde_json::json!(["x", 0, 7]));
    let raw = &recorded(&file)["shroud/rr-python/cloud/p"][0];
    let cloud = CloudMessage::from_bytes(raw).expect("a cloud");
    let hex: String = cloud.points.iter().map(|b| format!("{b:02x}")).collect();
    assert_eq!(
        first["data"],
        hex.as_str(),
        "the view's points are the cloud's"
    );
}

/// Lichtblick's way of opening a local MCAP file (`tests/browser/lichtblick_mcap.mjs`:
/// @mcap/core's indexed reader, zstd, protobuf and JSON channels parsed from
/// their schemas) takes a recording of a scanner and a fit node: every
/// Foxglove view decodes, the clouds and surfaces are what the 3D panel
/// needs, and only the raw msgpack channels are listed as problems.
#[test]
fn lichtblick_decodes_the_foxglove_views_of_a_recording() {
    let packages = ["@mcap/core", "protobufjs", "@lichtblick/wasm-zstd"];
    if !common::browser::node_modules_available("Lichtblick MCAP", &packages) {
        return;
    }
    let (endpoint, session) = hub_on_free_port();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("lichtblick.mcap");
    record_demo((&session, &endpoint), "rr-lichtblick", &file, 4);
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/browser/lichtblick_mcap.mjs");
    let out = Command::new("node")
        .arg(&script)
        .arg(&file)
        .output()
        .expect("node runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // The raw channels, and only they, are problems.
    let problems = v["problems"].as_array().unwrap();
    assert!(!problems.is_empty());
    for p in problems {
        assert!(p["topic"].as_str().unwrap().starts_with("shroud/"), "{p}");
        assert_eq!(p["message"], "Unsupported encoding msgpack", "{p}");
    }
    let topics = v["topics"].as_object().unwrap();
    for (topic, t) in topics {
        assert!(topic.starts_with("/shroud/"), "{topic}");
        assert_eq!(t["decoded"], t["count"], "{topic}: every message decodes");
    }
    let raw = recorded(&file);
    let clouds = raw["shroud/rr-lichtblick/cloud/s"].len() as u64;
    assert_eq!(topics["/shroud/cloud/s"]["count"], clouds);
    assert_eq!(topics["/shroud/cloud/s"]["schema"], "foxglove.PointCloud");
    assert_eq!(
        topics["/shroud/surrogate/s"]["schema"],
        "foxglove.SceneUpdate"
    );
    assert_eq!(
        topics["/shroud/certificate/s"]["schema"],
        "shroud.CertificateView"
    );
    let cloud = &v["first"]["/shroud/cloud/s"];
    assert_eq!(cloud["frame_id"], "world");
    assert_eq!(cloud["point_stride"], 12);
    assert_eq!(cloud["fields"], serde_json::json!(["x", "y", "z"]));
    assert_eq!(cloud["points"], 3000);
    // A sandwich: an upper and a lower surface, each with triangles.
    let scene = v["first"]["/shroud/surrogate/s"]["entities"]
        .as_array()
        .unwrap();
    assert_eq!(scene.len(), 2, "{scene:?}");
    for entity in scene {
        assert_eq!(entity["frame_id"], "world");
        assert!(entity["triangles"].as_u64().unwrap() > 100, "{entity}");
    }
    let certificate = &v["first"]["/shroud/certificate/s"];
    assert_eq!(certificate["upper"]["violations"], 0);
    assert!(certificate["upper"]["min_gap"].as_f64().unwrap() >= 0.0);
}

/// `--split-size` continues in numbered files, each finished, none past the
/// size by more than its summary, the messages in order across them; a
/// second recording to the same name does not replace them without
/// `--overwrite`.
#[test]
fn a_split_recording_keeps_each_file_under_its_size() {
    let (endpoint, session) = hub_on_free_port();
    let dir = tempfile::tempdir().unwrap();
    let base = dir.path().join("split.mcap");
    let ns = "rr-split";
    let board = StatusBoard::new(&session, ns);
    let w = wiring(&endpoint, ns);
    let args = [
        "record",
        "-o",
        s(&base),
        "--topics",
        "cloud/*",
        "--split-size",
        "1",
        "--foxglove",
        "false",
    ];
    let mut recorder = start(&args, &w);
    board.wait_for("record", "a status", LONG, |_| true);
    let _scanner = start(
        &[
            "node", "scanner", "--points", "20000", "--rate", "10", "--stream", "c",
        ],
        &w,
    );
    board.wait_for("record", "25 clouds written", LONG, |st| {
        st.counter("written") >= 25
    });
    recorder.signal(libc::SIGTERM);
    assert!(recorder.wait_exit(LONG).success(), "{}", recorder.output());
    let mut sequences = Vec::new();
    let mut files = 0;
    for index in 0.. {
        let path = dir.path().join(format!("split-{index:03}.mcap"));
        if !path.exists() {
            break;
        }
        let len = std::fs::metadata(&path).unwrap().len();
        assert!(
            len <= 1_000_000 + 65_536,
            "{} is {len} bytes",
            path.display()
        );
        let info = shroud(&["mcap", "info", s(&path)]);
        let text = String::from_utf8_lossy(&info.stdout);
        assert!(info.status.success(), "{text}");
        let clouds = recorded(&path).remove("shroud/rr-split/cloud/c");
        for cloud in clouds.unwrap_or_default() {
            sequences.push(CloudMessage::from_bytes(&cloud).unwrap().sequence);
        }
        files += 1;
    }
    assert!(files >= 3, "{files} files");
    assert!(sequences.len() >= 25, "{} clouds", sequences.len());
    assert!(
        sequences.windows(2).all(|w| w[1] == w[0] + 1),
        "in order, none lost between files: {sequences:?}"
    );
    let again = shroud(&[&args[..], &w[..]].concat());
    assert!(!again.status.success());
    let text = String::from_utf8_lossy(&again.stderr);
    assert!(text.contains("split-000.mcap exists"), "{text}");
}

/// `--restamp` (a replay in place of a sensor): each cloud is stamped when
/// it is published, its points as recorded; without it, the recorded stamp.
#[test]
fn a_restamped_replay_stamps_clouds_when_it_publishes_them() {
    let (endpoint, session) = hub_on_free_port();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("restamp.mcap");
    record_demo((&session, &endpoint), "rr-restamp", &file, 3);
    let recorded_clouds: Vec<CloudMessage> = recorded(&file)["shroud/rr-restamp/cloud/s"]
        .iter()
        .map(|c| CloudMessage::from_bytes(c).unwrap())
        .collect();
    for restamp in [true, false] {
        let ns = if restamp {
            "rr-restamped"
        } else {
            "rr-as-recorded"
        };
        let heard = inbox(&session, format!("shroud/{ns}/cloud/s"));
        let mut args = vec![
            "replay",
            s(&file),
            "--topics",
            "cloud/*",
            "--wait-subscribers",
            "30",
        ];
        if restamp {
            args.push("--restamp");
        }
        let before = common::unix_ns();
        let mut replay = start(&args, &wiring(&endpoint, ns));
        assert!(replay.wait_exit(LONG).success(), "{}", replay.output());
        let after = common::unix_ns();
        for want in &recorded_clouds {
            let sample = heard
                .recv_timeout(Duration::from_secs(30))
                .unwrap()
                .expect("a replayed cloud");
            let got = CloudMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            assert_eq!(got.points, want.points, "the points as recorded");
            assert_eq!(got.sequence, want.sequence);
            if restamp {
                assert!((before..=after).contains(&got.stamp_ns), "stamped now");
            } else {
                assert_eq!(got.stamp_ns, want.stamp_ns, "stamped as recorded");
            }
        }
    }
}
