//! The Foxglove bridge end to end: a real graph (scanner, fit, blend), the
//! `foxglove` node, and a Python client (`tests/python/foxglove_client.py`,
//! the `websockets` and `protobuf` packages from PyPI) that speaks the
//! Foxglove WebSocket protocol to it: subprotocol, advertise, subscribe,
//! binary message frames decoded with the advertised protobuf schemas, a JSON
//! status channel, and a client publish on `/shroud/blend` whose drop reaches
//! the blend node as a `BlendCommandMessage` while its malformed JSON is
//! counted.

mod common;

use common::status_board::StatusBoard;
use common::{hub_on_free_port, wiring, Proc};
use shroud_msg::{BlendCommandMessage, CloudMessage};
use std::process::Command;
use std::time::{Duration, Instant};
use zenoh::Wait;

const PACKAGES: [&str; 2] = ["websockets==15.0.1", "protobuf==6.33.5"];
const START: Duration = Duration::from_secs(30);
const BUDGET: usize = 3000;

fn node(args: &[&str], w: &[&str]) -> Proc {
    Proc::start(&[&["node"][..], args, w].concat())
}

/// The bridge on a free port and its `ws://` URL.
fn bridge(w: &[&str]) -> (Proc, String) {
    let budget = BUDGET.to_string();
    let args = [
        "foxglove",
        "--listen",
        "127.0.0.1:0",
        "--points-budget",
        &budget,
        "--log",
        "info",
    ];
    let proc = node(&args, w);
    let line = proc.expect_line("serving Foxglove at ", START);
    let url = line
        .split("serving Foxglove at ")
        .nth(1)
        .unwrap()
        .trim()
        .to_string();
    (proc, url)
}

/// Runs the client to completion; its JSON line.
fn run_client(url: &str, ns_topics: [&str; 3]) -> serde_json::Value {
    let py = common::python::python_with("foxglove-env", &PACKAGES);
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/python/foxglove_client.py"
    );
    let out = Command::new(py)
        .arg(script)
        .arg(url)
        .args(ns_topics)
        .output()
        .expect("python runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "the Foxglove client failed: {stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_str(stdout.trim()).expect("one JSON line")
}

/// The bounding box of a cloud heard on zenoh.
fn bounds(cloud: &CloudMessage) -> ([f32; 3], [f32; 3]) {
    let points = cloud.point_array().unwrap();
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in &points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

#[test]
fn a_foxglove_client_sees_the_graph_and_drives_a_drop() {
    let (endpoint, hub) = hub_on_free_port();
    let ns = "e2e-foxglove";
    let w = wiring(&endpoint, ns);
    let clouds = hub
        .declare_subscriber(format!("shroud/{ns}/cloud/table"))
        .wait()
        .unwrap();
    let commands = hub
        .declare_subscriber(format!("shroud/{ns}/blend/*"))
        .wait()
        .unwrap();
    let board = StatusBoard::new(&hub, ns);
    let scanner = [
        "scanner",
        "--stream",
        "table",
        "--scene",
        "table-top",
        "--points",
        "20000",
        "--rate",
        "4",
        "--time-scale",
        "0",
    ];
    let _scanner = node(&scanner, &w);
    let fit = [
        "fit", "--input", "table", "--grid", "12x12", "--side", "sandwich",
    ];
    let _fit = node(&fit, &w);
    let blend = [
        "blend",
        "--parent-stream",
        "table",
        "--stream",
        "blend",
        "--child-part",
        "hemisphere",
        "--part-size",
        "0.3",
        "--centres",
        "400",
    ];
    let _blend = node(&blend, &w);
    let (bridge, url) = bridge(&w);
    // The bridge knows the blend node it drives (from its status).
    board.wait_for("foxglove", "blend.drives", START, |s| {
        s.labels.get("blend.drives").map(String::as_str) == Some("blend")
    });
    let started = Instant::now();
    let topics = [
        "/shroud/cloud/table",
        "/shroud/surrogate/table",
        "/shroud/status/fit",
    ];
    let out = run_client(&url, topics);
    eprintln!("client ran {:?}: {out}", started.elapsed());
    assert_eq!(out["subprotocol"], "foxglove.sdk.v1");
    assert!(out["capabilities"]
        .as_array()
        .unwrap()
        .contains(&"clientPublish".into()));
    let decoded = &out["decoded"];

    let cloud = &decoded[topics[0]];
    assert_eq!(cloud["schemaName"], "foxglove.PointCloud");
    let points = cloud["points"].as_u64().unwrap() as usize;
    assert!(
        (1..=BUDGET).contains(&points),
        "{points} points, budget {BUDGET}"
    );
    assert_eq!(cloud["stride"], 12, "xyz f32, no intensity");
    let sample = clouds
        .recv_timeout(Duration::from_secs(30))
        .expect("the test subscriber")
        .expect("a cloud within 30 s");
    let heard = CloudMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
    assert_eq!(points, heard.point_array().unwrap().len().min(BUDGET));
    // The scene is still (time scale 0): every cloud has the same bounds.
    let (lo, hi) = bounds(&heard);
    for k in 0..3 {
        let (min, max) = (
            cloud["min"][k].as_f64().unwrap(),
            cloud["max"][k].as_f64().unwrap(),
        );
        assert!(
            lo[k] as f64 <= min && max <= hi[k] as f64,
            "axis {k}: [{min}, {max}] outside the scene's [{}, {}]",
            lo[k],
            hi[k]
        );
    }

    let surrogate = &decoded[topics[1]];
    assert_eq!(surrogate["schemaName"], "foxglove.SceneUpdate");
    for side in ["upper", "lower"] {
        let entity = &surrogate["entities"][format!("surrogate/table/{side}")];
        assert!(
            entity["triangles"].as_u64().unwrap() > 0,
            "{side}: {entity}"
        );
        assert_eq!(entity["indices_in_range"], true);
    }

    let status = &decoded[topics[2]];
    assert_eq!(status["schemaEncoding"], "jsonschema");
    assert_eq!(status["message"]["node"], "fit");
    assert!(status["message"]["counters"]["received"].as_u64().is_some());

    // The client's drop reaches zenoh as a blend command at its point.
    let deadline = Instant::now() + Duration::from_secs(10);
    let command = loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let sample = commands
            .recv_timeout(left)
            .unwrap()
            .expect("no blend command on zenoh after the client's drop");
        let msg = BlendCommandMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
        if msg.command == "drop" {
            break msg;
        }
    };
    let at = command.at.unwrap();
    for k in 0..3 {
        let sent = out["published"]["at"][k].as_f64().unwrap();
        assert!(
            (at[k] - sent).abs() < 1e-9,
            "{at:?} vs {}",
            out["published"]
        );
    }
    // Its malformed JSON was counted, and the drop sent.
    let counted = board.wait_for("foxglove", "counted client messages", START, |s| {
        s.counter("dropped_malformed") >= 1 && s.counter("blend_commands") >= 1
    });
    assert_eq!(counted.counter("client_messages"), 2, "{counted:?}");
    assert!(
        bridge.output().contains("blend request JSON"),
        "{}",
        bridge.output()
    );
}
