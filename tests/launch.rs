//! End-to-end tests of `shroud launch`: the supervisor starts real node processes,
//! restarts failures with backoff, stops everything on a signal, and leaves no
//! orphan even when it is killed outright.

mod common;

use common::launched::{endpoint_of, pids_of, write_launch};
use common::{alive, assert_all_gone, client_of, joint_spread, KillOnDrop, Proc, Reaped};
use shroud_msg::{CollisionMessage, NodeStatusMessage, SurrogateMessage};
use shroud_surrogate::SurrogateWire;
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use zenoh::Wait;

const LONG: Duration = Duration::from_secs(60);

const GRAPH: &str = r#"
namespace = "NS"
shutdown_grace_s = 5
[summary]
period_s = 0.5
[[node]]
name = "scanner"
kind = "scanner"
outputs = { cloud = "s" }
settings = { points = 2000, rate = 10 }
[[node]]
name = "fit"
kind = "fit"
inputs = { cloud = "s" }
outputs = { surrogate = "s" }
settings = { grid = "10x10" }
"#;

#[test]
fn sigint_stops_every_node_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_launch(dir.path(), &GRAPH.replace("NS", "e2e-sigint"));
    let mut launcher = Proc::start(&["launch", &file]);
    let endpoint = endpoint_of(&launcher);
    let pids = pids_of(&launcher, &["scanner", "fit"]);
    let session = client_of(&endpoint);
    let surrogates = session
        .declare_subscriber("shroud/e2e-sigint/surrogate/s")
        .wait()
        .unwrap();
    let sample = surrogates
        .recv_timeout(LONG)
        .unwrap()
        .expect("a surrogate through the launched graph");
    let (msg, _) = SurrogateMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
    assert!(msg.surfaces.iter().all(|s| s.certificate.violations == 0));
    // Log lines are prefixed by node name, and the summary line is printed.
    launcher.expect_line("certified 2000 pts, 0 violations", LONG);
    assert!(
        launcher.output().contains("[fit]") || launcher.output().contains("[scanner]"),
        "{}",
        launcher.output()
    );
    launcher.signal(libc::SIGINT);
    let status = launcher.wait_exit(LONG);
    assert!(status.success(), "{}", launcher.output());
    assert!(launcher.output().contains("all nodes stopped cleanly"));
    assert_all_gone(&pids, Duration::from_secs(5));
}

#[test]
fn a_killed_launcher_leaves_no_orphan() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_launch(dir.path(), &GRAPH.replace("NS", "e2e-kill"));
    let mut launcher = Proc::start(&["launch", &file]);
    let pids = pids_of(&launcher, &["scanner", "fit"]);
    assert!(pids.iter().all(|&p| alive(p)));
    launcher.signal(libc::SIGKILL);
    launcher.wait_exit(LONG);
    assert_all_gone(&pids, Duration::from_secs(15));
}

/// The launcher killed outright while its parent does not reap it (it stays a
/// zombie, as under a shell script busy elsewhere): its nodes stop all the same.
/// Repeated, since whether they did used to depend on a race.
#[test]
fn a_killed_unreaped_launcher_leaves_no_live_node() {
    for round in 0..8 {
        let dir = tempfile::tempdir().unwrap();
        let namespace = format!("e2e-zombie-{round}");
        let file = write_launch(dir.path(), &GRAPH.replace("NS", &namespace));
        let launcher = Proc::start(&["launch", &file]);
        let nodes = KillOnDrop(pids_of(&launcher, &["scanner", "fit"]));
        // Both nodes running: the fitter has certified the scanner's cloud.
        launcher.expect_line("certified 2000 pts", LONG);
        launcher.signal(libc::SIGKILL);
        assert_all_gone(&nodes.0, Duration::from_secs(15));
        assert!(
            std::path::Path::new(&format!("/proc/{}", launcher.pid())).exists(),
            "the launcher is still unreaped"
        );
    }
}

/// A node whose stdout and stderr readers are gone (as when its launcher died)
/// stops on SIGTERM: its stop log line used to panic on EPIPE before the stop
/// flag was set, leaving the runtime waiting forever for the looping body.
#[test]
fn a_node_without_output_readers_stops_on_sigterm() {
    for round in 0..3 {
        let namespace = format!("e2e-nopipe-{round}");
        let mut node = Reaped(
            Command::new(env!("CARGO_BIN_EXE_shroud"))
                .args(["--log", "info", "node", "scanner", "--points", "2000"])
                .args(["--rate", "10", "--stream", "s", "--multicast", "off"])
                .args(["--namespace", &namespace])
                .stdin(Stdio::null())
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .expect("the shroud binary starts"),
        );
        // The body is looping once it logs "scanning"; then close both readers.
        let stderr = BufReader::new(node.0.stderr.take().unwrap());
        let mut lines = stderr.lines().map_while(Result::ok);
        assert!(lines.any(|l| l.contains("scanning")), "the scanner starts");
        drop(lines);
        drop(node.0.stdout.take());
        unsafe {
            libc::kill(node.0.id() as i32, libc::SIGTERM);
        }
        let status = node.wait_timeout(Duration::from_secs(20));
        assert!(
            status.is_some_and(|s| s.success()),
            "round {round}: {status:?}"
        );
    }
}

#[test]
fn a_failing_node_is_restarted_with_backoff_then_given_up() {
    let dir = tempfile::tempdir().unwrap();
    // `grid = "0x0"` passes the option parser (a grid is text) but makes the
    // fit node exit with an error at once.
    let file = write_launch(
        dir.path(),
        r#"
namespace = "e2e-restart"
external = ["cloud/c"]
[summary]
enabled = false
[[node]]
name = "broken"
kind = "fit"
inputs = { cloud = "c" }
outputs = { surrogate = "c" }
settings = { grid = "0x0" }
restart = "on-failure"
max_restarts = 2
backoff_ms = 100
backoff_max_ms = 1000
"#,
    );
    let mut launcher = Proc::start(&["launch", &file]);
    let start = Instant::now();
    launcher.expect_line("restarting broken in 0.10 s", LONG);
    launcher.expect_line("restarting broken in 0.20 s", LONG);
    launcher.expect_line("giving up on broken after 3 failures", LONG);
    let status = launcher.wait_exit(LONG);
    assert!(!status.success(), "a graph whose node gave up must fail");
    assert!(
        start.elapsed() >= Duration::from_millis(300),
        "backoff delays were waited"
    );
    let out = launcher.output();
    assert!(
        out.contains("[broken] error:"),
        "child errors are prefixed: {out}"
    );
    assert!(!out.contains("panicked"), "{out}");
}

/// A fit node fed from outside, at line 2.
const FIT: &str = "external = [\"cloud/c\"]\n[[node]]\nname = \"a\"\nkind = \"fit\"\n\
                   inputs = { cloud = \"c\" }\noutputs = { surrogate = \"s\" }\n";

#[test]
fn bad_launch_files_are_named_errors() {
    let dir = tempfile::tempdir().unwrap();
    for (body, needle) in [
        (
            format!("{FIT}settings = {{ namespace = \"x\" }}"),
            "line 2: node \"a\": settings.namespace: --namespace is set by the launcher",
        ),
        (format!("namespace = \"a b\"\n{FIT}"), "namespace"),
        ("[[node]]\nname = \"a\"".into(), "missing field `kind`"),
        (String::new(), "no node"),
        // A misspelt setting, refused with its line before any node starts.
        (
            format!("{FIT}settings = {{ gird = \"8x8\" }}"),
            "line 2: node \"a\": settings.gird is not an option of a fit node",
        ),
        (
            FIT.replace("external = [\"cloud/c\"]", ""),
            "input cloud/c has no producer",
        ),
    ] {
        let file = write_launch(dir.path(), &body);
        let mut p = Proc::start(&["launch", &file]);
        assert!(!p.wait_exit(LONG).success());
        let out = p.output();
        assert!(
            out.contains(needle) && !out.contains("panicked"),
            "{body:?}: {out}"
        );
    }
    let mut missing = Proc::start(&["launch", "/nonexistent/graph.toml"]);
    assert!(!missing.wait_exit(LONG).success());
    assert!(missing.output().contains("cannot read launch file"));
}

fn collision(sample: &zenoh::sample::Sample) -> CollisionMessage {
    CollisionMessage::from_bytes(&sample.payload().to_bytes()).unwrap()
}

/// The sheet of points at height `z` as a cloud message.
fn sheet(z: f32, sequence: u64) -> Vec<u8> {
    let points = common::sheet(z);
    shroud_msg::CloudMessage::new(
        common::unix_ns(),
        sequence,
        "test",
        Default::default(),
        &points,
    )
    .to_bytes()
    .unwrap()
}

/// Waits for a collision message satisfying `pred`, publishing `cloud` on the
/// way so that the surrogate stays fresh.
fn wait_collision(
    session: &zenoh::Session,
    sub: &zenoh::pubsub::Subscriber<zenoh::handlers::FifoChannelHandler<zenoh::sample::Sample>>,
    cloud: impl Fn(u64) -> Vec<u8>,
    pred: impl Fn(&CollisionMessage) -> bool,
    launcher: &Proc,
) -> CollisionMessage {
    let deadline = Instant::now() + LONG;
    let mut seq = 0;
    let mut last = Instant::now() - Duration::from_secs(1);
    loop {
        assert!(
            Instant::now() < deadline,
            "no matching collision message; launcher:\n{}",
            launcher.output()
        );
        if last.elapsed() > Duration::from_millis(100) {
            session
                .put("shroud/e2e-guard/cloud/inj", cloud(seq))
                .wait()
                .unwrap();
            seq += 1;
            last = Instant::now();
        }
        if let Ok(Some(sample)) = sub.recv_timeout(Duration::from_millis(20)) {
            let msg = collision(&sample);
            if pred(&msg) {
                return msg;
            }
        }
    }
}

/// The guard clears the arm over a distant cloud, and stops it when a cloud is
/// injected across its path; the halted arm then stops moving.
#[test]
fn the_guard_stops_the_arm_on_an_injected_collision() {
    let dir = tempfile::tempdir().unwrap();
    let arm_file = concat!(env!("CARGO_MANIFEST_DIR"), "/launch/arms/demo_arm.toml");
    let file = write_launch(
        dir.path(),
        &format!(
            r#"
namespace = "e2e-guard"
external = ["cloud/inj"]
[summary]
period_s = 0.5
[[node]]
name = "fit"
kind = "fit"
inputs = {{ cloud = "inj" }}
outputs = {{ surrogate = "inj" }}
settings = {{ grid = "8x8" }}
[[node]]
name = "guard"
kind = "guard"
inputs = {{ surrogate = "inj", joints = "demo_arm" }}
outputs = {{ collision = "demo_arm" }}
settings = {{ arm_file = "{arm_file}", max_age = 5, unobserved = "ignore" }}
[[node]]
name = "arm"
kind = "arm"
inputs = {{ collision = "demo_arm" }}
outputs = {{ joints = "demo_arm" }}
settings = {{ arm_file = "{arm_file}", rate = 20 }}
"#
        ),
    );
    let mut launcher = Proc::start(&["launch", &file]);
    let endpoint = endpoint_of(&launcher);
    let pids = pids_of(&launcher, &["fit", "guard", "arm"]);
    let session = client_of(&endpoint);
    let verdicts = session
        .declare_subscriber("shroud/e2e-guard/collision/demo_arm")
        .wait()
        .unwrap();
    let joints = session
        .declare_subscriber("shroud/e2e-guard/joints/demo_arm")
        .wait()
        .unwrap();

    // Far below the arm: clear, and the arm moves.
    let clear = wait_collision(
        &session,
        &verdicts,
        |s| sheet(-2.0, s),
        |m| !m.stop,
        &launcher,
    );
    assert!(clear.min_clearance > clear.stop_distance);
    let mut moved = 0.0;
    for _ in 0..4 {
        session
            .put("shroud/e2e-guard/cloud/inj", sheet(-2.0, 1000))
            .wait()
            .unwrap();
        moved = f64::max(moved, joint_spread(&joints, Duration::from_millis(400)));
    }
    assert!(moved > 1e-4, "the arm moves while clear");

    // A sheet across the arm: stop, and the arm halts.
    let stop = wait_collision(
        &session,
        &verdicts,
        |s| sheet(1.2, 2000 + s),
        |m| m.stop,
        &launcher,
    );
    assert_eq!(stop.min_clearance, 0.0, "{stop:?}");
    assert!(stop.links.iter().any(|l| l.clearance == 0.0));
    std::thread::sleep(Duration::from_millis(300));
    session
        .put("shroud/e2e-guard/cloud/inj", sheet(1.2, 5000))
        .wait()
        .unwrap();
    assert_eq!(
        joint_spread(&joints, Duration::from_millis(600)),
        0.0,
        "the halted arm holds still"
    );

    launcher.signal(libc::SIGTERM);
    assert!(launcher.wait_exit(LONG).success(), "{}", launcher.output());
    assert_all_gone(&pids, Duration::from_secs(5));
}

/// `shroud node list`, `topic list`, `topic echo` and `topic hz` against a
/// launched graph.
#[test]
fn introspection_tools_see_the_running_graph() {
    let dir = tempfile::tempdir().unwrap();
    let file = write_launch(dir.path(), &GRAPH.replace("NS", "e2e-tools"));
    let mut launcher = Proc::start(&["launch", &file]);
    let endpoint = endpoint_of(&launcher);
    let pids = pids_of(&launcher, &["scanner", "fit"]);
    launcher.expect_line("certified 2000 pts", LONG);
    let wiring = [
        "--namespace",
        "e2e-tools",
        "--connect",
        endpoint.as_str(),
        "--multicast",
        "off",
    ];
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_shroud"))
            .args(args)
            .args(wiring)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let nodes = run(&["node", "list"]);
    assert!(
        nodes.contains("scanner") && nodes.contains("fit") && nodes.contains("published="),
        "{nodes}"
    );
    let topics = run(&["topic", "list", "--duration", "1.5"]);
    assert!(
        topics.contains("shroud/e2e-tools/cloud/s") && topics.contains("surrogate"),
        "{topics}"
    );
    let echo = run(&[
        "topic",
        "echo",
        "surrogate/s",
        "--count",
        "1",
        "--timeout",
        "30",
    ]);
    let line: serde_json::Value = serde_json::from_str(echo.lines().next().unwrap()).unwrap();
    assert_eq!(
        line["message"]["surfaces"][0]["certificate"]["violations"], 0,
        "{echo}"
    );
    let hz = run(&["topic", "hz", "cloud/s", "--duration", "2"]);
    assert!(hz.contains("messages in"), "{hz}");
    let silent = std::process::Command::new(env!("CARGO_BIN_EXE_shroud"))
        .args(["topic", "echo", "cloud/nothing", "--timeout", "1"])
        .args(wiring)
        .output()
        .unwrap();
    assert!(
        !silent.status.success(),
        "echo with nothing to hear fails after its timeout"
    );
    launcher.signal(libc::SIGTERM);
    assert!(launcher.wait_exit(LONG).success());
    assert_all_gone(&pids, Duration::from_secs(5));
}

/// The README's main command: `launch/demo.toml` runs, the launcher prints the
/// dashboard's address and the summary line, the page answers at that
/// address, and the launcher's own status counts every node's starts.
#[test]
fn the_demo_launch_file_runs_and_prints_the_dashboard() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/launch/demo.toml");
    let mut launcher = Proc::start(&["launch", file, "--duration", "20"]);
    let endpoint = endpoint_of(&launcher);
    let line = launcher.expect_line("open http://127.0.0.1:8080/ in a browser", LONG);
    assert!(line.contains("dashboard"), "{line}");
    let page = http_get("127.0.0.1:8080", "/");
    assert!(
        page.starts_with("HTTP/1.1 200") && page.contains("<html"),
        "{page}"
    );
    launcher.expect_line("arm: ", LONG);
    let session = client_of(&endpoint);
    let statuses = session
        .declare_subscriber("shroud/demo/status/launcher")
        .wait()
        .unwrap();
    let sample = statuses
        .recv_timeout(LONG)
        .unwrap()
        .expect("the launcher's status");
    let status = NodeStatusMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
    assert_eq!(status.kind, "launch");
    for node in ["scanner", "fit", "guard", "arm", "dashboard"] {
        assert_eq!(status.counter(&format!("starts.{node}")), 1, "{status:?}");
        assert_eq!(status.counter(&format!("restarts.{node}")), 0, "{status:?}");
    }
    assert!(launcher.wait_exit(LONG).success(), "{}", launcher.output());
}

/// A plain HTTP/1.1 GET on loopback: the response's head and body as text.
fn http_get(address: &str, path: &str) -> String {
    use std::io::{Read, Write};
    let mut stream = std::net::TcpStream::connect(address).expect("the dashboard listens");
    write!(
        stream,
        "GET {path} HTTP/1.1\r\nHost: {address}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut response = String::new();
    stream.read_to_string(&mut response).unwrap();
    response
}

/// The speed and separation monitoring demo, `launch/cell.toml` (its
/// dashboard left out, so that it runs beside the demo test's): as the
/// person walks past, the guard's verdicts go from full speed to scaled
/// clears (with the link that limits them) to stops, and back to clears as
/// the person leaves.
#[test]
fn the_cell_demo_slows_stops_and_resumes_the_arm_as_the_person_passes() {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/launch/cell.toml")).unwrap();
    let graph = text.split("[[node]]\nname = \"dashboard\"").next().unwrap();
    assert!(graph.len() < text.len(), "cell.toml has a dashboard node");
    let dir = tempfile::tempdir().unwrap();
    let file = write_launch(dir.path(), graph);
    let launcher = Proc::start(&["launch", &file, "--duration", "20"]);
    let session = client_of(&endpoint_of(&launcher));
    let verdicts = session
        .declare_subscriber("shroud/cell/collision/cell_arm")
        .wait()
        .unwrap();
    let joints = session
        .declare_subscriber("shroud/cell/joints/cell_arm")
        .wait()
        .unwrap();
    let (mut full, mut scaled, mut stops, mut resumed) = (0, 0, 0, 0);
    let mut limiting = std::collections::BTreeSet::new();
    // The arm's limits (`arms/cell_arm.toml`): its joint states carry the
    // velocities it moves at, within them.
    let limits = [0.8, 0.8, 1.0, 1.5];
    let (mut states, mut moving) = (0, 0);
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(17) {
        // Drained as they come: a full subscriber queue would hold zenoh up.
        while let Ok(Some(sample)) = joints.try_recv() {
            let js =
                shroud_msg::JointStateMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            assert_eq!(js.velocities.len(), 4, "{js:?}");
            for (v, limit) in js.velocities.iter().zip(limits) {
                assert!(v.abs() <= limit + 1e-9, "{js:?}");
            }
            states += 1;
            moving += usize::from(js.velocities.iter().any(|v| *v != 0.0));
        }
        let Ok(Some(sample)) = verdicts.recv_timeout(Duration::from_millis(200)) else {
            continue;
        };
        let c = collision(&sample);
        match (c.stop, c.speed_scale) {
            (true, s) => {
                assert_eq!(s, 0.0, "{c:?}");
                stops += 1;
            }
            (false, 1.0) => full += 1,
            (false, s) => {
                assert!(s > 0.0 && s < 1.0, "{c:?}");
                scaled += 1;
                limiting.insert(c.limiting_link.clone());
            }
        }
        if !c.stop && stops > 0 {
            resumed += 1;
        }
    }
    assert!(
        full > 0 && scaled > 0 && stops > 0 && resumed > 0,
        "full {full}, scaled {scaled}, stops {stops}, clears after a stop {resumed}"
    );
    // A scale held down by a link's separation names the link.
    assert!(limiting.iter().any(|l| !l.is_empty()), "{limiting:?}");
    assert!(
        states > 0 && moving > 0,
        "{states} joint states, {moving} moving"
    );
    drop(launcher);
}

/// `launch/camera.toml`: the fit node publishes the whole view and its 16
/// sectors, each stating a cone inside the camera's field of view, the
/// guard takes them all as views, and the arm gets `clear` verdicts.
#[test]
fn the_camera_launch_guards_with_the_sectors_of_its_view() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/launch/camera.toml");
    let mut launcher = Proc::start(&["launch", file, "--duration", "15"]);
    let session = client_of(&endpoint_of(&launcher));
    let surrogates = session
        .declare_subscriber("shroud/camera/surrogate/*")
        .wait()
        .unwrap();
    let verdicts = session
        .declare_subscriber("shroud/camera/collision/demo_arm")
        .wait()
        .unwrap();
    let guard_status = session
        .declare_subscriber("shroud/camera/status/guard")
        .wait()
        .unwrap();
    let mut streams = std::collections::BTreeSet::new();
    let (mut clears, mut accepted) = (0, 0);
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(12) {
        while let Ok(Some(sample)) = surrogates.try_recv() {
            let msg = SurrogateMessage::decode(&sample.payload().to_bytes()).unwrap();
            let fov = msg
                .field_of_view
                .expect("the camera states its field of view");
            let key = sample.key_expr().as_str().to_owned();
            if key.contains(".s") {
                assert!(
                    matches!(fov.aperture, shroud_msg::Aperture::Cone { .. }),
                    "{key}: {fov:?}"
                );
            }
            streams.insert(key);
        }
        while let Ok(Some(sample)) = guard_status.try_recv() {
            let status = NodeStatusMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            accepted = accepted.max(status.counter("surrogates"));
        }
        if let Ok(Some(sample)) = verdicts.recv_timeout(Duration::from_millis(100)) {
            clears += usize::from(!collision(&sample).stop);
        }
    }
    // The whole view and at least most sectors (a corner of the view may see
    // too little to fit).
    assert!(
        streams.contains("shroud/camera/surrogate/camera"),
        "{streams:?}"
    );
    assert!(streams.len() >= 12, "{streams:?}");
    assert!(clears > 0, "no clear verdict:\n{}", launcher.output());
    // At 10 clouds a second for about ten seconds, far more than one view each.
    assert!(accepted > 400, "the guard accepted {accepted} surrogates");
    assert!(launcher.wait_exit(LONG).success(), "{}", launcher.output());
}
