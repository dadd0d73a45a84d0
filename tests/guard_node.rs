//! The path from surrogate to stop, end to end with real processes: a guard
//! killed with SIGKILL halts the arm within its deadline (the arm's deadman),
//! a partition between arm and guard halts it too, a cloud stamped an hour in
//! the future is a counted fault, not a fresh surrogate, a guard frozen while a
//! surrogate arrives says `stale` when it wakes, and two fit nodes on
//! different clouds never clear what one of them saw.

mod common;

use common::{
    alive, free_port, hub, hub_on_free_port, inbox, joint_spread, peer_session, wait_moving,
    wiring, Inbox, Proc,
};
use shroud_msg::{CloudMessage, NodeStatusMessage, SurrogateMessage};
use shroud_surrogate::SurrogateWire;
use shroud_surrogate::{fit_surrogate, FitOptions, Sides};
use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use zenoh::Wait;

const LONG: Duration = Duration::from_secs(60);
const ARM_FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/launch/arms/demo_arm.toml");

/// A certified sandwich of a floor far below the arm and wider than its
/// reach, as the fit node sends it.
fn far_surrogate(sequence: u64) -> Vec<u8> {
    let options = FitOptions {
        cols: 8,
        rows: 8,
        sides: Sides::Sandwich,
        ..FitOptions::default()
    };
    let surrogate = fit_surrogate(&floor(-2.0, 3.0), &options).unwrap();
    SurrogateMessage::from_surrogate(&surrogate, common::unix_ns(), sequence, "test", 1)
        .to_bytes()
        .unwrap()
}

/// The guard args every test uses, with the default policy: space no sensor
/// saw counts as occupied (the floors here are wider than the arm's reach).
fn guard_args(surrogate: &str) -> Vec<String> {
    [
        "node",
        "guard",
        "--arm-file",
        ARM_FILE,
        "--surrogate",
        surrogate,
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}

fn arm_args() -> Vec<String> {
    ["node", "arm", "--arm-file", ARM_FILE, "--rate", "50"]
        .iter()
        .map(|s| s.to_string())
        .collect()
}

/// A hub on a free port and an inbox of the demo arm's verdicts in `ns`.
fn verdict_rig(ns: &str) -> (String, zenoh::Session, Inbox) {
    let (endpoint, session) = hub_on_free_port();
    let verdicts = inbox(&session, format!("shroud/{ns}/collision/demo_arm"));
    (endpoint, session, verdicts)
}

fn start(args: &[String], wiring: &[&str]) -> Proc {
    let mut all: Vec<&str> = args.iter().map(String::as_str).collect();
    all.extend_from_slice(wiring);
    Proc::start(&all)
}

/// The latest status of `node` seen in `inbox` within `window`.
fn status_within(inbox: &Inbox, window: Duration) -> Option<NodeStatusMessage> {
    let start = Instant::now();
    let mut latest = None;
    while start.elapsed() < window {
        if let Ok(Some(s)) = inbox.recv_timeout(Duration::from_millis(50)) {
            latest = NodeStatusMessage::from_bytes(&s.payload().to_bytes()).ok();
        }
    }
    latest
}

/// Publishes a fresh far surrogate every 100 ms until `stop`.
fn keep_fresh(
    session: zenoh::Session,
    key: String,
    stop: Arc<AtomicBool>,
) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        let mut sequence = 0;
        while !stop.load(Ordering::Relaxed) {
            let _ = session.put(&key, far_surrogate(sequence)).wait();
            sequence += 1;
            std::thread::sleep(Duration::from_millis(100));
        }
    })
}

/// How many times the arm has halted for want of a verdict so far (its start,
/// waiting for the first verdict, counts once).
fn no_verdict_halts(status: &Inbox) -> u64 {
    let deadline = Instant::now() + LONG;
    loop {
        if let Some(s) = status_within(status, Duration::from_millis(300)) {
            return s.counter("halts_no_verdict");
        }
        assert!(Instant::now() < deadline, "no status from the arm");
    }
}

/// Waits until the arm's status says it halted for want of a verdict once more
/// than `before`, then checks that it holds still.
fn assert_halts_for_no_verdict(status: &Inbox, joints: &Inbox, arm: &Proc, before: u64) {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let s = status_within(status, Duration::from_millis(300));
        if s.as_ref().is_some_and(|s| {
            s.counter("halts_no_verdict") > before && s.gauge("halted") == Some(1.0)
        }) {
            break;
        }
        assert!(
            Instant::now() < deadline,
            "the arm did not halt for want of a verdict: {s:?}\n{}",
            arm.output()
        );
    }
    assert_eq!(
        joint_spread(joints, Duration::from_millis(500)),
        0.0,
        "the halted arm holds still"
    );
}

#[test]
fn a_killed_guard_halts_the_arm_within_its_deadline() {
    let (endpoint, session) = hub_on_free_port();
    let ns = "e2e-deadman";
    let joints = inbox(&session, format!("shroud/{ns}/joints/demo_arm"));
    let status = inbox(&session, format!("shroud/{ns}/status/arm"));
    let stop = Arc::new(AtomicBool::new(false));
    let feeder = keep_fresh(
        session.clone(),
        format!("shroud/{ns}/surrogate/far"),
        stop.clone(),
    );
    let w = wiring(&endpoint, ns);
    let guard = start(&guard_args("far"), &w);
    let arm = start(&arm_args(), &w);
    wait_moving(&joints, "guard running", &[&guard, &arm], LONG);
    let before = no_verdict_halts(&status);
    guard.signal(libc::SIGKILL);
    assert_halts_for_no_verdict(&status, &joints, &arm, before);
    assert!(alive(arm.pid()), "the arm node itself keeps running");
    stop.store(true, Ordering::Relaxed);
    feeder.join().unwrap();
}

/// Publishes the far floor as a cloud stamped `stamp_ns`.
fn put_sheet(session: &zenoh::Session, ns: &str, stamp_ns: u64, sequence: u64) {
    let cloud = CloudMessage::new(
        stamp_ns,
        sequence,
        "test",
        Default::default(),
        &floor(-2.0, 3.0),
    );
    let key = format!("shroud/{ns}/cloud/future");
    session.put(key, cloud.to_bytes().unwrap()).wait().unwrap();
}

#[test]
fn a_cloud_stamped_an_hour_ahead_is_a_counted_fault_not_a_fresh_surrogate() {
    let ns = "e2e-skew";
    let (endpoint, session, verdicts) = verdict_rig(ns);
    let status = inbox(&session, format!("shroud/{ns}/status/guard"));
    let w = wiring(&endpoint, ns);
    let fit = Proc::start(
        &[
            &[
                "node", "fit", "--input", "future", "--grid", "8x8", "--side", "sandwich",
            ][..],
            &w,
        ]
        .concat(),
    );
    let guard = start(&guard_args("future"), &w);
    let arm = start(&arm_args(), &w);
    let hour_ahead = 3_600_000_000_000u64;
    let deadline = Instant::now() + LONG;
    let mut sequence = 0;
    let faults = loop {
        assert!(
            Instant::now() < deadline,
            "no clock_skew fault counted:\n{}\n{}",
            fit.output(),
            guard.output()
        );
        put_sheet(&session, ns, common::unix_ns() + hour_ahead, sequence);
        sequence += 1;
        if let Some(s) = status_within(&status, Duration::from_millis(150)) {
            if s.counter("clock_skew") >= 3 {
                break s;
            }
        }
    };
    assert_eq!(
        faults.counter("surrogates"),
        0,
        "no skewed surrogate was taken"
    );
    // Every verdict meanwhile says there is nothing to vouch with.
    let seen: Vec<_> = verdicts.drain().collect();
    assert!(!seen.is_empty(), "the guard answers every joint state");
    for s in &seen {
        let v = shroud_msg::CollisionMessage::from_bytes(&s.payload().to_bytes()).unwrap();
        assert!(v.stop, "a skewed surrogate never clears: {v:?}");
    }
    // Honest stamps: the same pipeline now clears the far sheet.
    let deadline = Instant::now() + LONG;
    loop {
        assert!(
            Instant::now() < deadline,
            "honest stamps never cleared:\n{}",
            guard.output()
        );
        put_sheet(&session, ns, common::unix_ns(), sequence);
        sequence += 1;
        if let Ok(Some(s)) = verdicts.recv_timeout(Duration::from_millis(100)) {
            let v = shroud_msg::CollisionMessage::from_bytes(&s.payload().to_bytes()).unwrap();
            if !v.stop {
                assert!(v.surrogate_age_ns < 1_000_000_000, "{v:?}");
                break;
            }
        }
    }
    drop(arm);
}

/// A TCP relay that copies bytes both ways while `forwarding` is set, and
/// swallows them otherwise (the connections stay up: a silent partition).
fn relay(listen: u16, target: u16, forwarding: Arc<AtomicBool>) {
    let listener = TcpListener::bind(("127.0.0.1", listen)).unwrap();
    std::thread::spawn(move || {
        for inbound in listener.incoming().flatten() {
            let Ok(outbound) = TcpStream::connect(("127.0.0.1", target)) else {
                continue;
            };
            for (from, to) in [
                (inbound.try_clone().unwrap(), outbound.try_clone().unwrap()),
                (outbound, inbound),
            ] {
                let forwarding = forwarding.clone();
                std::thread::spawn(move || pump(from, to, &forwarding));
            }
        }
    });
}

fn pump(mut from: TcpStream, mut to: TcpStream, forwarding: &AtomicBool) {
    let mut buf = vec![0u8; 64 * 1024];
    while let Ok(n) = from.read(&mut buf) {
        if n == 0 {
            break;
        }
        if forwarding.load(Ordering::Relaxed) && to.write_all(&buf[..n]).is_err() {
            break;
        }
    }
}

/// A zenoh JSON5 file that turns off gossip scouting, so that peers talk only
/// over the endpoints they are given (the relay), not around it.
fn no_gossip(dir: &std::path::Path) -> String {
    let path = dir.join("no-gossip.json5");
    std::fs::write(&path, "{ scouting: { gossip: { enabled: false } } }").unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn a_partition_between_arm_and_guard_halts_the_arm() {
    let dir = tempfile::tempdir().unwrap();
    let config = no_gossip(dir.path());
    let (hub_port, guard_port, relay_port, arm_port) =
        (free_port(), free_port(), free_port(), free_port());
    let hub_endpoint = format!("tcp/127.0.0.1:{hub_port}");
    let session = hub(&hub_endpoint);
    let ns = "e2e-partition";
    let stop = Arc::new(AtomicBool::new(false));
    let feeder = keep_fresh(
        session.clone(),
        format!("shroud/{ns}/surrogate/far"),
        stop.clone(),
    );
    let forwarding = Arc::new(AtomicBool::new(true));
    relay(relay_port, guard_port, forwarding.clone());
    // The guard hears surrogates from the hub and the arm through the relay
    // only; the test watches the arm from its own side of the partition.
    let guard_listen = format!("tcp/127.0.0.1:{guard_port}");
    let guard_wiring = [
        "--connect",
        &hub_endpoint,
        "--listen",
        &guard_listen,
        "--multicast",
        "off",
        "--zenoh-config",
        &config,
        "--namespace",
        ns,
    ];
    let guard = start(&guard_args("far"), &guard_wiring);
    let (relay_endpoint, arm_listen) = (
        format!("tcp/127.0.0.1:{relay_port}"),
        format!("tcp/127.0.0.1:{arm_port}"),
    );
    let arm_wiring = [
        "--connect",
        &relay_endpoint,
        "--listen",
        &arm_listen,
        "--multicast",
        "off",
        "--zenoh-config",
        &config,
        "--namespace",
        ns,
    ];
    let arm = start(&arm_args(), &arm_wiring);
    let observer = peer_session(&[
        ("connect/endpoints", format!("[\"{arm_listen}\"]")),
        ("listen/endpoints", "[]".to_string()),
        ("scouting/gossip/enabled", "false".to_string()),
        // The arm may not listen yet: keep trying.
        ("connect/exit_on_failure", "false".to_string()),
    ]);
    let joints = inbox(&observer, format!("shroud/{ns}/joints/demo_arm"));
    let status = inbox(&observer, format!("shroud/{ns}/status/arm"));
    wait_moving(&joints, "relay forwarding", &[&guard, &arm], LONG);
    let before = no_verdict_halts(&status);
    forwarding.store(false, Ordering::Relaxed);
    assert_halts_for_no_verdict(&status, &joints, &arm, before);
    assert!(
        alive(guard.pid()),
        "the guard is alive: only the link failed"
    );
    stop.store(true, Ordering::Relaxed);
    feeder.join().unwrap();
}

/// The guard answers joint states it cannot use with a stop that says why
/// (silence would look like a partition), and counts each as malformed.
#[test]
fn unusable_joint_states_are_answered_with_a_stop_and_counted() {
    let ns = "e2e-bad-joints";
    let (endpoint, session, verdicts) = verdict_rig(ns);
    let status = inbox(&session, format!("shroud/{ns}/status/guard"));
    let stop = Arc::new(AtomicBool::new(false));
    let feeder = keep_fresh(
        session.clone(),
        format!("shroud/{ns}/surrogate/far"),
        stop.clone(),
    );
    let guard = start(&guard_args("far"), &wiring(&endpoint, ns));
    let key = format!("shroud/{ns}/joints/demo_arm");
    let wrong_names =
        shroud_msg::JointStateMessage::new(5, 9, "demo_arm", vec!["a".into()], vec![0.0])
            .to_bytes()
            .unwrap();
    // Another arm's joint state, and an encoder glitch past a joint's limits
    // (the shoulder's are [-2, 2]): neither is a pose to judge.
    let names = |file: &shroud_guard::ArmFile| {
        file.arm
            .actuated_joints()
            .map(|j| j.name().to_string())
            .collect::<Vec<_>>()
    };
    let file =
        shroud_guard::ArmFile::from_toml_str(&std::fs::read_to_string(ARM_FILE).unwrap()).unwrap();
    let other_arm =
        shroud_msg::JointStateMessage::new(5, 10, "other_arm", names(&file), vec![0.0; 6])
            .to_bytes()
            .unwrap();
    let glitch = shroud_msg::JointStateMessage::new(
        5,
        11,
        "demo_arm",
        names(&file),
        vec![0.0, 3.0, 0.0, 0.0, 0.0, 0.0],
    )
    .to_bytes()
    .unwrap();
    let deadline = Instant::now() + LONG;
    let (mut undecodable, mut misnamed, mut foreign, mut glitched) = (false, false, false, false);
    while !(undecodable && misnamed && foreign && glitched) {
        assert!(Instant::now() < deadline, "no answers:\n{}", guard.output());
        session
            .put(&key, b"not a joint state".to_vec())
            .wait()
            .unwrap();
        session.put(&key, wrong_names.clone()).wait().unwrap();
        session.put(&key, other_arm.clone()).wait().unwrap();
        session.put(&key, glitch.clone()).wait().unwrap();
        while let Ok(Some(s)) = verdicts.recv_timeout(Duration::from_millis(100)) {
            let v = shroud_msg::CollisionMessage::from_bytes(&s.payload().to_bytes()).unwrap();
            assert!(v.stop, "never clear: {v:?}");
            if v.joints_sequence == u64::MAX {
                assert!(v.reason.contains("undecodable joint state"), "{}", v.reason);
                undecodable = true;
            } else if v.joints_sequence == 9 {
                assert!(v.reason.contains("joint names"), "{}", v.reason);
                misnamed = true;
            } else if v.joints_sequence == 10 {
                assert!(v.reason.contains("other_arm"), "{}", v.reason);
                foreign = true;
            } else if v.joints_sequence == 11 {
                assert!(v.reason.contains("outside its limits"), "{}", v.reason);
                glitched = true;
            }
        }
    }
    let counted = status_within(&status, Duration::from_millis(1500))
        .map_or(0, |s| s.counter("dropped_malformed"));
    assert!(
        counted >= 4,
        "each unusable joint state is counted: {counted}"
    );
    stop.store(true, Ordering::Relaxed);
    feeder.join().unwrap();
}

/// The demo arm's joint state at `q`, as its controller would send it.
fn joint_state(sequence: u64, q: &[f64]) -> Vec<u8> {
    let file =
        shroud_guard::ArmFile::from_toml_str(&std::fs::read_to_string(ARM_FILE).unwrap()).unwrap();
    let names = file
        .arm
        .actuated_joints()
        .map(|j| j.name().to_string())
        .collect();
    shroud_msg::JointStateMessage::new(common::unix_ns(), sequence, "demo_arm", names, q.to_vec())
        .to_bytes()
        .unwrap()
}

/// Sends joint states at `q` every 20 ms for `window` and returns the verdicts
/// that answer them (those for other joint states are skipped).
fn verdicts_for(
    session: &zenoh::Session,
    ns: &str,
    verdicts: &Inbox,
    q: &[f64],
    first: u64,
    window: Duration,
) -> Vec<shroud_msg::CollisionMessage> {
    let key = format!("shroud/{ns}/joints/demo_arm");
    let start = Instant::now();
    let mut sequence = first;
    let mut out = Vec::new();
    while start.elapsed() < window {
        session.put(&key, joint_state(sequence, q)).wait().unwrap();
        sequence += 1;
        while let Ok(Some(s)) = verdicts.recv_timeout(Duration::from_millis(20)) {
            let v = shroud_msg::CollisionMessage::from_bytes(&s.payload().to_bytes()).unwrap();
            if (first..sequence).contains(&v.joints_sequence) {
                out.push(v);
            }
        }
    }
    out
}

/// A floor of points at height `z` (a little rough, as in `common::sheet`) over
/// [-half, half]^2, 5 cm apart: every cell of a coarse grid holds points.
fn floor(z: f32, half: f32) -> Vec<[f32; 3]> {
    let n = (2.0 * half / 0.05) as usize + 1;
    (0..n * n)
        .map(|i| {
            let at = |k: usize| -half + k as f32 * 0.05;
            [at(i % n), at(i / n), z + 0.002 * ((i * 7) % 5) as f32]
        })
        .collect()
}

/// A certified sandwich of a wide floor far below the arm, with the sample's
/// publication time set as a shroud session sets it.
fn put_far_floor(session: &zenoh::Session, key: &str, sequence: u64) {
    session
        .put(key, far_surrogate(sequence))
        .timestamp(session.new_timestamp())
        .wait()
        .unwrap();
}

/// The arm folded up above the floor (clear of it by far).
const FOLDED: [f64; 6] = [0.0, 1.2, 2.2, 1.0, 0.0, 0.0];

/// Issue 23, case 3: a guard frozen (SIGSTOP) while a far surrogate arrives
/// must not take that surrogate as fresh when it wakes: its time in transit
/// and in the guard's own queue counts.
#[test]
fn a_guard_frozen_while_a_surrogate_arrives_says_stale_when_it_wakes() {
    let ns = "e2e-frozen";
    let (endpoint, session, verdicts) = verdict_rig(ns);
    let key = format!("shroud/{ns}/surrogate/far");
    let guard = start(&guard_args("far"), &wiring(&endpoint, ns));
    // Clear while surrogates are fresh.
    let deadline = Instant::now() + LONG;
    let mut sequence = 0;
    loop {
        assert!(
            Instant::now() < deadline,
            "never clear:\n{}",
            guard.output()
        );
        put_far_floor(&session, &key, sequence);
        let got = verdicts_for(
            &session,
            ns,
            &verdicts,
            &FOLDED,
            sequence * 100,
            Duration::from_millis(100),
        );
        sequence += 1;
        if got.iter().any(|v| !v.stop) {
            break;
        }
    }
    guard.signal(libc::SIGSTOP);
    std::thread::sleep(Duration::from_millis(200));
    // A surrogate arrives while the guard is frozen; then nothing for longer
    // than the guard's maximum age (1 s).
    put_far_floor(&session, &key, sequence);
    std::thread::sleep(Duration::from_millis(1500));
    guard.signal(libc::SIGCONT);
    let woken = verdicts_for(
        &session,
        ns,
        &verdicts,
        &FOLDED,
        1_000_000,
        Duration::from_millis(600),
    );
    assert!(
        !woken.is_empty(),
        "answers after waking:\n{}",
        guard.output()
    );
    for v in &woken {
        assert_eq!(
            v.verdict,
            shroud_msg::GuardVerdict::Stale,
            "a surrogate that waited in a frozen guard is not fresh: {v:?}"
        );
    }
}

/// Issue 23, case 1, with real fit nodes: a top view of a newer cloud sees an
/// obstacle at the arm's fingertips; a side view of another cloud, which
/// ends below the fingertips, did not see that space at all. Together: stop.
#[test]
fn two_fit_nodes_on_different_clouds_stop_for_an_obstacle_one_of_them_saw() {
    let ns = "e2e-two-clouds";
    let (endpoint, session, verdicts) = verdict_rig(ns);
    let w = wiring(&endpoint, ns);
    let fit = |input: &str, dir: &str| {
        Proc::start(
            &[
                &[
                    "node", "fit", "--input", input, "--grid", "16x16", "--side", "sandwich",
                    "--dir", dir,
                ][..],
                &w,
            ]
            .concat(),
        )
    };
    let (top_fit, side_fit) = (fit("top", "0,0,-1"), fit("side", "0,-1,0"));
    let mut args = guard_args("top");
    args.extend(["--surrogate".into(), "side".into()]);
    let guard = start(&args, &w);
    // At q = 0 the arm hangs straight down; its fingertips are near z = 0.25
    // over the origin. The top sensor's cloud: a floor and a box there.
    let mut top = floor(0.0, 2.0);
    top.extend((0..400).map(|i| {
        let (a, b, c) = ((i % 8) as f32, ((i / 8) % 8) as f32, (i / 64) as f32);
        [-0.1 + 0.028 * a, -0.1 + 0.028 * b, 0.15 + 0.03 * c]
    }));
    // The side sensor's older cloud: the floor and a low step, nothing above
    // z = 0.1, so its domain ends below the fingertips.
    let mut side = floor(0.0, 2.0);
    side.extend(floor(0.1, 0.5));
    let hanging = [0.0; 6];
    let put = |stream: &str, points: &[[f32; 3]], sequence: u64| {
        let cloud = CloudMessage::new(
            common::unix_ns(),
            sequence,
            stream,
            Default::default(),
            points,
        );
        session
            .put(
                format!("shroud/{ns}/cloud/{stream}"),
                cloud.to_bytes().unwrap(),
            )
            .wait()
            .unwrap();
    };
    let deadline = Instant::now() + LONG;
    let mut sequence = 0;
    let seen = loop {
        assert!(
            Instant::now() < deadline,
            "no verdict from two views:\n{}\n{}\n{}",
            guard.output(),
            top_fit.output(),
            side_fit.output()
        );
        put("top", &top, sequence);
        put("side", &side, sequence);
        let got = verdicts_for(
            &session,
            ns,
            &verdicts,
            &hanging,
            sequence * 100,
            Duration::from_millis(150),
        );
        sequence += 1;
        if let Some(v) = got.into_iter().find(|v| v.views == 2) {
            break v;
        }
    };
    assert_eq!(seen.verdict, shroud_msg::GuardVerdict::Stop, "{seen:?}");
    assert!(seen.min_clearance < seen.stop_distance, "{seen:?}");
}

/// A floor 2 m below a sensor looking down through a cone of 0.5 rad: the
/// points its rays return, and the field of view its cloud states.
fn perspective_floor() -> (Vec<[f32; 3]>, shroud_msg::FieldOfView) {
    let fov = shroud_msg::FieldOfView {
        apex: [0.0, 0.0, 2.0],
        axis: [0.0, 0.0, -1.0],
        aperture: shroud_msg::Aperture::Cone { half_angle: 0.5 },
        max_range: 4.0,
    };
    let reach = 2.0 * 0.5f32.tan();
    let points = floor(0.0, 1.2)
        .into_iter()
        .filter(|p| p[0].hypot(p[1]) < reach)
        .collect();
    (points, fov)
}

/// A fit node with `--sectors 2` publishes the whole view and its four
/// sectors, each looking along its own axis and stating its cone; a guard
/// with `--sectors 2` takes all five as views. A cloud that states no field
/// of view still gets its whole view, and its sectors are a counted miss.
#[test]
fn a_fit_node_publishes_the_sectors_of_a_perspective_cloud_and_the_guard_reads_them() {
    let ns = "e2e-sectors";
    let (endpoint, session) = common::hub_on_free_port();
    let w = wiring(&endpoint, ns);
    let surrogates = inbox(&session, format!("shroud/{ns}/surrogate/*"));
    let fit_status = inbox(&session, format!("shroud/{ns}/status/fit"));
    let guard_status = inbox(&session, format!("shroud/{ns}/status/guard"));
    let fit = Proc::start(
        &[
            &[
                "node",
                "fit",
                "--input",
                "cam",
                "--grid",
                "12x12",
                "--side",
                "upper",
                "--sectors",
                "2",
            ][..],
            &w,
        ]
        .concat(),
    );
    let mut args = guard_args("cam");
    args.extend(["--sectors".into(), "2".into()]);
    let guard = start(&args, &w);
    let (points, fov) = perspective_floor();
    let put = |sequence: u64, stated: bool| {
        let mut cloud = shroud_msg::CloudView::new(
            common::unix_ns(),
            sequence,
            "cam",
            Default::default(),
            &points,
        );
        if stated {
            cloud = cloud.with_field_of_view(fov).unwrap();
        }
        session
            .put(format!("shroud/{ns}/cloud/cam"), cloud.to_bytes().unwrap())
            .timestamp(session.new_timestamp())
            .wait()
            .unwrap();
    };
    let mut keys = std::collections::BTreeMap::new();
    let deadline = Instant::now() + LONG;
    let mut sequence = 0;
    while keys.len() < 5 {
        assert!(
            Instant::now() < deadline,
            "surrogates seen on {:?}:\n{}\n{}",
            keys.keys().collect::<Vec<_>>(),
            fit.output(),
            guard.output()
        );
        put(sequence, true);
        sequence += 1;
        let start = Instant::now();
        while start.elapsed() < Duration::from_millis(200) {
            let Ok(Some(sample)) = surrogates.recv_timeout(Duration::from_millis(50)) else {
                continue;
            };
            let (msg, surrogate) =
                SurrogateMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            keys.insert(sample.key_expr().to_string(), (msg, surrogate));
        }
    }
    let prefix = format!("shroud/{ns}/surrogate/");
    let names: Vec<&str> = keys.keys().map(|k| &k[prefix.len()..]).collect();
    assert_eq!(names, ["cam", "cam.s0", "cam.s1", "cam.s2", "cam.s3"]);
    let whole_points = keys[&format!("{prefix}cam")].1.stats.points;
    for (key, (msg, surrogate)) in &keys {
        let stated = msg
            .field_of_view
            .expect("every view states its field of view");
        assert_eq!(stated.apex, fov.apex, "{key}");
        if key.ends_with("/cam") {
            assert_eq!(stated, fov, "the whole view states the cloud's");
            continue;
        }
        let shroud_msg::Aperture::Cone { half_angle } = stated.aperture else {
            panic!("{key}: a sector is a cone")
        };
        assert!(half_angle < 0.5, "{key}: {half_angle}");
        let axis = glam::DVec3::from_array(stated.axis);
        assert!(
            (surrogate.frame.direction - axis).length() < 1e-9,
            "{key} looks along its axis"
        );
        let points = surrogate.stats.points;
        assert!(
            points > 20 && points < whole_points,
            "{key}: {points} of {whole_points}"
        );
        assert!(surrogate.upper.as_ref().unwrap().certificate.violations == 0);
    }
    // A cloud without a field of view: the whole view only, and a count.
    for _ in 0..3 {
        put(sequence, false);
        sequence += 1;
        std::thread::sleep(Duration::from_millis(100));
    }
    let deadline = Instant::now() + LONG;
    loop {
        assert!(Instant::now() < deadline, "counts:\n{}", fit.output());
        let (Some(f), Some(g)) = (
            status_within(&fit_status, Duration::from_millis(1100)),
            status_within(&guard_status, Duration::from_millis(1100)),
        ) else {
            continue;
        };
        let published = f.counter("sectors_published");
        // The guard took more surrogates than there were clouds: the
        // sectors' views besides the whole ones.
        if f.counter("sectors_unstated") >= 3 && g.counter("surrogates") > sequence {
            assert!(published >= 4, "{published}");
            assert_eq!(f.counter("sector_errors"), 0);
            break;
        }
    }
}
