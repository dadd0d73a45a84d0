//! Issue 26's acceptance test: the demo over hosts made of network namespaces
//! on one machine, linked by mutual TLS through veths on a bridge: a router
//! host (`shroud router`), a sensor host (the scanner), a fit host (the
//! fitter and the guard) and an arm host (the simulated arm, listening for
//! other hosts too), each started with `shroud launch --host` and a shared
//! memory of its own. The test process watches from the root namespace with
//! an `observer` certificate. It checks that:
//!
//! 1. the guard's verdicts rest on certified surrogates of clouds that
//!    crossed two hops, their sequence advancing;
//! 2. the arm moves, and the guard stops it when a sphere of the scene
//!    sweeps through it;
//! 3. a link taken down halts the arm (the arm host's: its deadman; the
//!    sensor host's: `stale` verdicts; the fit host's: no verdict) and
//!    bringing it back up recovers without restarting anything;
//! 4. rogue peers in namespaces of their own cannot steer the arm: one
//!    without a certificate cannot even connect, one holding the sensor
//!    host's certificate forges clear verdicts for each live joint state,
//!    joint states and surrogates, through the router host and straight to
//!    the arm host, and none reaches the observer or moves the halted arm;
//!    the same forgeries from the fit host's certificate (whose guard may
//!    publish verdicts) do move it, which shows that the refused ones would
//!    have.
//!
//! Needs root and `ip netns`: without them the test says why and passes,
//! under `CI=true` it fails. Links stay down for [`OUTAGE`], within zenoh's
//! 10 s lease, so that they recover without zenoh opening a new session; the
//! ignored test takes the arm host's link down for longer, which zenoh 1.10.2
//! does not always recover from (see its `ignore` reason).

mod common;

use common::impair::Impairment;
use common::netns::{self, Lan};
use common::status_board::StatusBoard;
use common::{inbox, joint_spread_if_any, unix_ns, Proc};
use shroud_graph::metrics::Percentiles;
use shroud_msg::{CollisionMessage, GuardVerdict, SurrogateMessage};
use shroud_surrogate::SurrogateWire;
use std::collections::BTreeMap;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};
use zenoh::Wait;

/// The graph's namespace (the hosts have a network of their own).
const NS: &str = "lan";
const PORT: u16 = 7447;
const LONG: Duration = Duration::from_secs(60);
/// How long the graph may take to get back to work after a fault.
const RECOVERY: Duration = Duration::from_secs(30);
/// How long a link stays down.
const OUTAGE: Duration = Duration::from_secs(4);
/// The namespaces, in address order (`.1` the router host).
const HOSTS: [&str; 6] = ["hub", "sensor", "fit", "arm", "rogue1", "rogue2"];
/// A forged joint state's sequence is the real one's plus this.
const FORGED_SEQUENCE: u64 = 1_000_000_000;

/// Two spheres (4000 points in all for the faults, light enough for a debug
/// build at 10 Hz): one beside the arm, one sweeping through it every 5 s
/// (the guard stops the arm then, for a second or so).
const SCENE: &str = r#"{"kind": "moving-spheres", "points": {points}, "radii": [0.5, 0.45],
 "paths": [{"centre": [-0.6, -2.6, 0.3], "amplitude": [0.2, 0.1, 0.1], "angular_speed": [0.5, 0.5, 1.0], "phase": [0.0, 0.0, 0.0]},
           {"centre": [0.0, 0.0, 1.0], "amplitude": [2.5, 0.2, 0.1], "angular_speed": [0.6, 0.5, 1.0], "phase": [1.5707963267948966, 0.0, 0.0]}],
 "seed": 7}"#;

/// Two spheres beside the arm, which never reach it: the link conditions'
/// scene, where every halt is the link's doing.
const STILL: &str = r#"{"kind": "moving-spheres", "points": {points}, "radii": [0.5, 0.45],
 "paths": [{"centre": [-0.6, -2.6, 0.3], "amplitude": [0.2, 0.1, 0.1], "angular_speed": [0.5, 0.5, 1.0], "phase": [0.0, 0.0, 0.0]},
           {"centre": [0.6, 2.6, 0.3], "amplitude": [0.2, 0.1, 0.1], "angular_speed": [0.6, 0.5, 1.0], "phase": [1.0, 0.0, 0.0]}],
 "seed": 7}"#;

/// `launch/hosts.toml` with a fit host between the sensor and the arm, the
/// hosts' addresses on the LAN, and the arm host listening for other hosts;
/// the guard trusts a surrogate for a second (a debug build's fit takes tens
/// of milliseconds) and judges by what it saw; the hosts share one clock.
const GRAPH: &str = r#"
namespace = "{ns}"
shutdown_grace_s = 3

[summary]
period_s = 2.0

[hosts.hub]
router = true
listen = ["tls/{hub}:{port}"]
tls = { root_ca = "{dir}/ca.pem", certificate = "{dir}/hub.pem", private_key = "{dir}/hub.key" }

[hosts.sensor]
connect = ["tls/{hub}:{port}"]
tls = { root_ca = "{dir}/ca.pem", certificate = "{dir}/sensor.pem", private_key = "{dir}/sensor.key" }

[hosts.fit]
connect = ["tls/{hub}:{port}"]
tls = { root_ca = "{dir}/ca.pem", certificate = "{dir}/fit.pem", private_key = "{dir}/fit.key" }

[hosts.arm]
listen = ["tls/{arm}:{port}"]
connect = ["tls/{hub}:{port}"]
tls = { root_ca = "{dir}/ca.pem", certificate = "{dir}/arm.pem", private_key = "{dir}/arm.key" }

[[node]]
name = "scanner"
kind = "scanner"
host = "sensor"
outputs = { cloud = "spheres" }
restart = "always"
[node.settings]
config = "{dir}/scene.json"
rate = 10

[[node]]
name = "fit"
kind = "fit"
host = "fit"
inputs = { cloud = "spheres" }
outputs = { surrogate = "spheres" }
[node.settings]
grid = "10x10"
side = "sandwich"
dir = "0,0,-1"
max_clock_offset = 0.001

[[node]]
name = "guard"
kind = "guard"
host = "fit"
inputs = { surrogate = "spheres", joints = "demo_arm" }
outputs = { collision = "demo_arm" }
[node.settings]
arm_file = "{root}/launch/arms/demo_arm.toml"
stop_distance = 0.05
max_age = 1.0
unobserved = "ignore"
max_clock_offset = 0.001

[[node]]
name = "arm"
kind = "arm"
host = "arm"
inputs = { collision = "demo_arm" }
outputs = { joints = "demo_arm" }
[node.settings]
arm_file = "{root}/launch/arms/demo_arm.toml"
rate = 50
"#;

/// The test's processes by name; all their outputs are printed if it fails.
#[derive(Default)]
struct Procs(Vec<(String, Proc)>);

impl Procs {
    fn start(&mut self, name: &str, command: &mut std::process::Command) {
        self.0.push((name.to_string(), Proc::spawn(command)));
    }

    fn get(&self, name: &str) -> &Proc {
        let found = self.0.iter().find(|(n, _)| n == name);
        &found.unwrap_or_else(|| panic!("no process {name}")).1
    }
}

impl Drop for Procs {
    fn drop(&mut self) {
        if std::thread::panicking() {
            for (name, proc) in &self.0 {
                eprintln!("===== {name} (pid {}) =====\n{}", proc.pid(), proc.output());
            }
        }
    }
}

/// What the observer heard: every verdict, and every forged sample.
#[derive(Default)]
struct Heard {
    verdicts: Vec<(Instant, CollisionMessage)>,
    /// Each verdict's time from the joint state it answers (stamped on the
    /// arm host) to the observer, in ms: the hosts share the kernel's clock.
    loops_ms: Vec<(Instant, f64)>,
    /// Each surrogate's time from its cloud's stamp (on the sensor host) to
    /// the observer, in ms.
    surrogate_ms: Vec<(Instant, f64)>,
    /// The sequence of every joint state heard.
    joints: Vec<(Instant, u64)>,
    /// Samples with a rogue's attachment, by `<attachment> on <key>`.
    forged: BTreeMap<String, u64>,
    /// Verdicts that answer a forged joint state.
    judged_forged_joints: u64,
}

fn lock(heard: &Mutex<Heard>) -> MutexGuard<'_, Heard> {
    heard.lock().unwrap_or_else(|p| p.into_inner())
}

/// Subscribes the observer to each of `keys` (with the graph's namespace).
fn listen(
    observer: &zenoh::Session,
    keys: &[&str],
) -> (Arc<Mutex<Heard>>, Vec<zenoh::pubsub::Subscriber<()>>) {
    let heard = Arc::new(Mutex::new(Heard::default()));
    let subscribers = (keys.iter())
        .map(|key| {
            let sink = heard.clone();
            observer
                .declare_subscriber(format!("shroud/{NS}/{key}"))
                .callback(move |sample| hear(&mut lock(&sink), &sample))
                .wait()
                .expect("the observer subscribes")
        })
        .collect();
    (heard, subscribers)
}

/// Notes what `sample` tells: a forgery, a verdict, a surrogate, a joint
/// state.
fn hear(heard: &mut Heard, sample: &zenoh::sample::Sample) {
    let key = sample.key_expr().to_string();
    let now = (Instant::now(), unix_ns());
    let since = |stamp_ns: u64| now.1.saturating_sub(stamp_ns) as f64 * 1e-6;
    if let Some(attachment) = sample.attachment() {
        let who = String::from_utf8_lossy(&attachment.to_bytes()).into_owned();
        *heard.forged.entry(format!("{who} on {key}")).or_default() += 1;
    }
    let bytes = sample.payload().to_bytes();
    if key == format!("shroud/{NS}/surrogate/spheres") {
        if let Ok((surrogate, _)) = SurrogateMessage::from_bytes(&bytes) {
            let ms = since(surrogate.source_stamp_ns);
            heard.surrogate_ms.push((now.0, ms));
        }
        return;
    }
    if key == format!("shroud/{NS}/joints/demo_arm") {
        if let Ok(joints) = shroud_msg::JointStateMessage::from_bytes(&bytes) {
            heard.joints.push((now.0, joints.sequence));
        }
        return;
    }
    if key != format!("shroud/{NS}/collision/demo_arm") {
        return;
    }
    match CollisionMessage::from_bytes(&bytes) {
        Ok(v) => {
            if v.joints_sequence >= FORGED_SEQUENCE && v.joints_sequence != u64::MAX {
                heard.judged_forged_joints += 1;
            }
            if v.reason == "forged" && sample.attachment().is_none() {
                *heard
                    .forged
                    .entry(format!("unmarked on {key}"))
                    .or_default() += 1;
            }
            // A verdict for no joint state (the guard's start) has none.
            if v.joints_sequence != u64::MAX {
                heard.loops_ms.push((now.0, since(v.joints_stamp_ns)));
            }
            heard.verdicts.push((now.0, v));
        }
        Err(e) => {
            *heard
                .forged
                .entry(format!("undecodable on {key}: {e}"))
                .or_default() += 1
        }
    }
}

/// The first verdict heard at or after `since` that satisfies `wanted`.
fn wait_verdict(
    heard: &Mutex<Heard>,
    since: Instant,
    timeout: Duration,
    what: &str,
    wanted: impl Fn(&CollisionMessage) -> bool,
) -> CollisionMessage {
    let deadline = Instant::now() + timeout;
    loop {
        {
            let heard = lock(heard);
            let mut fresh = heard.verdicts.iter().filter(|(t, _)| *t >= since);
            if let Some((_, v)) = fresh.clone().find(|(_, v)| wanted(v)) {
                return v.clone();
            }
            if Instant::now() > deadline {
                let last = fresh
                    .next_back()
                    .map(|(_, v)| (v.verdict, v.views, v.reason.clone()));
                panic!("no verdict with {what} within {timeout:?}; the last: {last:?}");
            }
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Whether the arm moves within `timeout`, as its joint states tell the
/// observer.
fn moves_within(observer: &zenoh::Session, timeout: Duration) -> bool {
    let joints = inbox(observer, format!("shroud/{NS}/joints/demo_arm"));
    let deadline = Instant::now() + timeout;
    while Instant::now() < deadline {
        let spread = joint_spread_if_any(&joints, Duration::from_millis(300));
        if spread.is_some_and(|s| s > 1e-6) {
            return true;
        }
    }
    false
}

fn moving(observer: &zenoh::Session, what: &str, timeout: Duration) {
    assert!(
        moves_within(observer, timeout),
        "{what}: the arm does not move within {timeout:?}"
    );
}

/// The largest joint step over `window`, as the observer hears the arm.
fn spread(observer: &zenoh::Session, window: Duration) -> Option<f64> {
    joint_spread_if_any(
        &inbox(observer, format!("shroud/{NS}/joints/demo_arm")),
        window,
    )
}

/// How many lines `proc` has written so far.
fn mark(proc: &Proc) -> usize {
    proc.seen.lock().unwrap().len()
}

fn lines_since(proc: &Proc, mark: usize) -> Vec<String> {
    proc.seen.lock().unwrap()[mark..].to_vec()
}

/// A halt or a resumption the arm node logs (through its host's launcher).
fn arm_event(line: &str) -> Option<&str> {
    let text = line.split("shroud_nodes::node::arm: ").nth(1)?;
    (text.starts_with("halted: ")
        || text.starts_with("still halted")
        || text.starts_with("resumed after"))
    .then_some(text)
}

/// The first line after `mark` that satisfies `wanted`, waiting up to
/// `timeout`.
fn wait_line(
    proc: &Proc,
    mark: usize,
    timeout: Duration,
    wanted: impl Fn(&str) -> bool,
) -> Option<String> {
    let deadline = Instant::now() + timeout;
    loop {
        if let Some(line) = lines_since(proc, mark).into_iter().find(|l| wanted(l)) {
            return Some(line);
        }
        if Instant::now() > deadline {
            return None;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The arm halts after `mark` (it was moving then: its deadman halts it
/// within a few joint periods, and it says so), or it was already halted (a
/// stop came just before): what it said. Waits briefly, so that the link
/// stays down well within zenoh's lease.
fn arm_halts(arm_host: &Proc, mark: usize, why: &str) -> String {
    let halted = |l: &str| arm_event(l).is_some_and(|e| !e.starts_with("resumed"));
    if let Some(line) = wait_line(arm_host, mark, Duration::from_secs(2), halted) {
        return arm_event(&line).unwrap_or_default().to_string();
    }
    let lines = arm_host.seen.lock().unwrap();
    let last = lines[..mark].iter().rev().find_map(|l| arm_event(l));
    match last {
        Some(event) if !event.starts_with("resumed") => format!("was halted already ({event})"),
        _ => panic!("{why}: the arm does not halt (its last word: {last:?})"),
    }
}

/// Asserts that the arm logged no resumption after `mark`.
fn arm_stayed_halted(arm_host: &Proc, mark: usize, why: &str) {
    let resumed: Vec<String> = lines_since(arm_host, mark)
        .into_iter()
        .filter(|l| arm_event(l).is_some_and(|e| e.starts_with("resumed")))
        .collect();
    assert!(resumed.is_empty(), "{why}: the arm resumed: {resumed:?}");
}

/// The JSON lines a rogue printed.
fn rogue_lines(rogue: &Proc) -> Vec<serde_json::Value> {
    let lines = rogue.seen.lock().unwrap();
    (lines.iter())
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .collect()
}

/// A rogue's last `stats` line for `endpoint`.
fn rogue_stats(rogue: &Proc, endpoint: &str) -> serde_json::Value {
    let lines = rogue_lines(rogue);
    let last = (lines.into_iter()).rfind(|l| l["event"] == "stats" && l["endpoint"] == endpoint);
    last.unwrap_or_else(|| panic!("no stats for {endpoint} yet:\n{}", rogue.output()))
}

/// A rogue's `open` line for `endpoint`, waiting for it.
fn rogue_open(rogue: &Proc, endpoint: &str) -> serde_json::Value {
    let deadline = Instant::now() + LONG;
    loop {
        let opened = (rogue_lines(rogue).into_iter())
            .find(|l| l["event"] == "open" && l["endpoint"] == endpoint);
        if let Some(line) = opened {
            return line;
        }
        assert!(
            Instant::now() < deadline,
            "the rogue says nothing of {endpoint}:\n{}",
            rogue.output()
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn count(stats: &serde_json::Value, field: &str) -> u64 {
    stats[field].as_u64().unwrap_or(0)
}

/// A clear verdict for the demo arm, MessagePack, as a hex string: what the
/// rogues send with each joint state's sequence and stamp.
fn clear_template() -> String {
    let mut verdict = shroud_msg::sample_collision(GuardVerdict::Clear);
    verdict.arm = "demo_arm".into();
    verdict.reason = "forged".into();
    let bytes = verdict.to_bytes().unwrap();
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The demo on its hosts, watched by the observer. Dropped in field order:
/// the processes (their outputs printed if the test failed), the sessions,
/// the files, the namespaces.
struct Demo {
    procs: Procs,
    _watching: Vec<zenoh::pubsub::Subscriber<()>>,
    board: StatusBoard,
    heard: Arc<Mutex<Heard>>,
    observer: zenoh::Session,
    /// The router host's endpoint and the arm host's.
    hub: String,
    arm_router: String,
    dir: tempfile::TempDir,
    lan: Lan,
    /// This test binary's tests run in parallel threads of one process, and
    /// a [`Lan`]'s names and addresses come from the process: one demo at a
    /// time (held until the namespaces are gone).
    _turn: MutexGuard<'static, ()>,
}

/// Whose turn it is to have the LAN.
static LAN_TURN: Mutex<()> = Mutex::new(());

/// How a run of the demo is set up.
struct Setup {
    /// The scanner's scene, with `{points}` for its number of points.
    scene: &'static str,
    /// Points of a cloud, in all.
    points: usize,
    /// Hosts whose link passes through a relay that can delay and drop.
    relayed: &'static [&'static str],
    /// What the observer subscribes to, under the graph's namespace.
    watch: &'static [&'static str],
}

/// The faults and rogues: light clouds, plain links, the observer hears
/// everything (forgeries on any key).
const FAULTS: Setup = Setup {
    scene: SCENE,
    points: 4000,
    relayed: &[],
    watch: &["**"],
};

impl Demo {
    /// Certificates, the graph, the router host and each host's launcher in
    /// their namespaces, and the observer; `None` (the test skipped) without
    /// root or `ip netns`.
    fn start(setup: &Setup) -> Option<Demo> {
        if let Some(reason) = netns::unusable() {
            netns::skip(&reason);
            return None;
        }
        let turn = LAN_TURN.lock().unwrap_or_else(|p| p.into_inner());
        let lan = match Lan::with_relayed(&HOSTS, setup.relayed) {
            Ok(lan) => lan,
            Err(e) => {
                netns::skip(&format!("cannot make network namespaces: {e}"));
                return None;
            }
        };
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let certs = d.display().to_string();
        let scene = (setup.scene).replace("{points}", &setup.points.to_string());
        std::fs::write(d.join("scene.json"), scene).unwrap();
        let graph = d.join("hosts.toml").display().to_string();
        let text = GRAPH
            .replace("{ns}", NS)
            .replace("{port}", &PORT.to_string())
            .replace("{hub}", &lan.addr("hub"))
            .replace("{arm}", &lan.addr("arm"))
            .replace("{root}", env!("CARGO_MANIFEST_DIR"))
            .replace("{dir}", &certs);
        std::fs::write(&graph, text).unwrap();
        let done = std::process::Command::new(env!("CARGO_BIN_EXE_shroud"))
            .args(["certs", "--graph", &graph, "--out", &certs])
            .args(["--host", "observer"])
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&done.stderr);
        assert!(done.status.success(), "shroud certs: {said}");

        // The router host, then each host's launcher, each in its namespace.
        let shroud = env!("CARGO_BIN_EXE_shroud");
        let mut procs = Procs::default();
        procs.start(
            "router",
            lan.command("hub", shroud)
                .args(["--log", "info", "router", "--graph", &graph])
                .args(["--host", "hub"]),
        );
        procs.get("router").expect_line("listening on", LONG);
        for host in ["sensor", "fit", "arm"] {
            procs.start(
                host,
                lan.command(host, shroud)
                    .args(["launch", &graph, "--host", host]),
            );
        }
        let hub = format!("tls/{}:{PORT}", lan.addr("hub"));
        let arm_router = format!("tls/{}:{PORT}", lan.addr("arm"));
        let observer = netns::lan_client(d, &hub, "observer")
            .expect("the observer reaches the router host from the root namespace");
        let (heard, watching) = listen(&observer, setup.watch);
        let board = StatusBoard::new(&observer, NS);
        Some(Demo {
            procs,
            _watching: watching,
            board,
            heard,
            observer,
            hub,
            arm_router,
            dir,
            lan,
            _turn: turn,
        })
    }

    /// Takes the arm host's link down for `outage`, and waits for the arm to
    /// move again (after `timeout`: false).
    fn arm_link_outage(&self, outage: Duration, timeout: Duration) -> bool {
        let arm_host = self.procs.get("arm");
        moving(&self.observer, "before the arm host's link goes down", LONG);
        let at = mark(arm_host);
        let down = Instant::now();
        self.lan.link_down("arm");
        let why = arm_halts(arm_host, at, "the arm host's link down");
        std::thread::sleep(outage.saturating_sub(down.elapsed()));
        arm_stayed_halted(arm_host, at, "while the arm host's link is down");
        self.lan.link_up("arm");
        let up = Instant::now();
        if !moves_within(&self.observer, timeout) {
            return false;
        }
        wait_verdict(
            &self.heard,
            up,
            timeout,
            "a clear after the arm link",
            |v| v.verdict == GuardVerdict::Clear && v.views > 0,
        );
        eprintln!(
            "multihost_netns: arm host link down {:.1} s: the arm {why}; moving again {:.1} s after the link came back",
            (up - down).as_secs_f64(),
            up.elapsed().as_secs_f64()
        );
        true
    }
}

/// A rogue's forgeries and what it heard, in short.
fn rogue_summary(stats: &serde_json::Value) -> String {
    format!(
        "{} verdicts, {} joint states, {} surrogates forged; {} joint states, {} surrogates heard",
        count(stats, "collision"),
        count(stats, "joints"),
        count(stats, "surrogate"),
        count(stats, "joints_heard"),
        count(stats, "surrogates_heard")
    )
}

#[test]
fn the_demo_across_network_namespaces_halts_on_lost_links_and_refuses_rogues() {
    if let Some(reason) = netns::unusable() {
        return netns::skip(&reason);
    }
    let started = Instant::now();
    let python =
        common::python::python_with("zenoh-rogue", &["eclipse-zenoh==1.10.2", "msgpack==1.1.2"]);
    let Some(mut demo) = Demo::start(&FAULTS) else {
        return;
    };

    // The rogues, forging from the start: without a certificate (as a
    // client, which must fail to connect, and as a peer, which retries), with
    // the sensor host's, and the control with the fit host's, idle until the
    // file `armed` exists.
    let d = demo.dir.path().to_path_buf();
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/multihost/rogue.py");
    let armed = d.join("armed");
    let armed_arg = armed.display().to_string();
    let template = clear_template();
    let ca = d.join("ca.pem").display().to_string();
    let (hub, arm_router) = (demo.hub.clone(), demo.arm_router.clone());
    let both = [
        "--endpoint",
        hub.as_str(),
        "--endpoint",
        arm_router.as_str(),
    ];
    let control = [
        &["--endpoint", hub.as_str(), "--forge", "collision"][..],
        &["--armed", armed_arg.as_str()],
    ]
    .concat();
    let rogues = [
        (
            "nocert",
            "rogue1",
            None,
            [&both[..], &["--seconds", "3"]].concat(),
        ),
        (
            "nocert-peer",
            "rogue1",
            None,
            [&both[..], &["--mode", "peer"]].concat(),
        ),
        ("sensor-rogue", "rogue2", Some("sensor"), both.to_vec()),
        ("control", "rogue2", Some("fit"), control),
    ];
    for (name, host, identity, extra) in rogues {
        let mut command = demo.lan.command(host, &python);
        command
            .arg(script)
            .args(["--name", name, "--ns", NS, "--ca", &ca]);
        command.args(["--arm", "demo_arm", "--surrogate", "spheres"]);
        command.args(["--template", &template, "--seconds", "600"]);
        if let Some(identity) = identity {
            let file = |ext: &str| d.join(format!("{identity}.{ext}")).display().to_string();
            command.args(["--cert", &file("pem"), "--key", &file("key")]);
        }
        // The last --seconds counts.
        command.args(extra);
        demo.procs.start(name, &mut command);
    }
    let Demo {
        procs,
        heard,
        observer,
        board,
        lan,
        ..
    } = &demo;

    // 1. Verdicts on certified surrogates of clouds from two hops away.
    let first = wait_verdict(heard, started, LONG, "views", |v| {
        v.views > 0 && v.surrogate_sequence > 0
    });
    let later = wait_verdict(heard, Instant::now(), LONG, "a newer cloud", |v| {
        v.views > 0 && v.surrogate_sequence > first.surrogate_sequence
    });
    let surrogates = observer
        .declare_subscriber(format!("shroud/{NS}/surrogate/spheres"))
        .wait()
        .unwrap();
    let sample = surrogates.recv_timeout(LONG).unwrap();
    let sample = sample.expect("a surrogate reaches the observer");
    let (surrogate, _) = SurrogateMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
    assert!(
        surrogate
            .surfaces
            .iter()
            .all(|s| s.certificate.violations == 0),
        "certified surrogates"
    );
    drop(surrogates);
    eprintln!(
        "multihost_netns: verdicts on clouds {} .. {} ({} views), after {:.1} s",
        first.surrogate_sequence,
        later.surrogate_sequence,
        later.views,
        started.elapsed().as_secs_f64()
    );

    // Each host's shared memory is its own.
    let ours = netns::mount_ns_of(std::process::id() as i32);
    let mut segments: Vec<(String, Vec<String>)> = Vec::new();
    for host in ["sensor", "fit", "arm"] {
        let pid = procs.get(host).pid();
        let mount = netns::mount_ns_of(pid);
        assert!(!mount.is_empty() && mount != ours, "{host}: {mount}");
        let names = netns::shm_of(pid);
        for (other, theirs) in &segments {
            let shared: Vec<&String> = names.iter().filter(|n| theirs.contains(n)).collect();
            assert!(shared.is_empty(), "{host} and {other} share {shared:?}");
        }
        segments.push((host.to_string(), names));
    }
    let root_shm = netns::shm_of(std::process::id() as i32);
    for (host, names) in &segments {
        let leaked: Vec<&String> = names.iter().filter(|n| root_shm.contains(n)).collect();
        assert!(
            leaked.is_empty(),
            "{host}'s segments in /dev/shm: {leaked:?}"
        );
    }
    assert!(
        !segments[0].1.is_empty(),
        "the sensor host's scanner uses its shared memory"
    );
    eprintln!(
        "multihost_netns: /dev/shm segments per host: {:?}",
        (segments.iter())
            .map(|(h, n)| (h.as_str(), n.len()))
            .collect::<Vec<_>>()
    );

    // 2. The arm moves, and the guard stops it when the sphere comes.
    let arm_host = procs.get("arm");
    moving(observer, "the demo at work", LONG);
    let at = mark(arm_host);
    let since = Instant::now();
    let stop = wait_verdict(heard, since, LONG, "a stop", |v| {
        v.verdict == GuardVerdict::Stop && v.views > 0
    });
    let halt = wait_line(arm_host, at, LONG, |l| {
        arm_event(l).is_some_and(|e| e.contains("halted") && e.contains("stop: link"))
    });
    let halt = halt.expect("the arm halts on the guard's stop");
    eprintln!(
        "multihost_netns: stop after {:.1} s ({}); the arm: {}",
        since.elapsed().as_secs_f64(),
        stop.reason,
        arm_event(&halt).unwrap_or_default()
    );

    // 3. Links down. The arm host's: nothing reaches it, its deadman halts it
    // (the observer cannot hear it then: its log says).
    assert!(
        demo.arm_link_outage(OUTAGE, RECOVERY),
        "the arm does not move within {RECOVERY:?} after its host's link came back"
    );

    // The sensor host's: no cloud, the guard answers stale and says why; the
    // arm halts.
    moving(observer, "before the sensor host's link goes down", LONG);
    lan.link_down("sensor");
    let down = Instant::now();
    let stale = wait_verdict(heard, down, Duration::from_secs(6), "stale", |v| {
        v.verdict == GuardVerdict::Stale
    });
    let stale_after = down.elapsed();
    assert!(!stale.reason.is_empty(), "a stale verdict says why");
    std::thread::sleep(Duration::from_millis(300));
    let held = spread(observer, Duration::from_secs(1));
    assert!(
        held.is_some_and(|s| s <= 1e-6),
        "the arm is halted on stale verdicts: largest joint step {held:?}"
    );
    std::thread::sleep(OUTAGE.saturating_sub(down.elapsed()));
    lan.link_up("sensor");
    let up = Instant::now();
    moving(observer, "after the sensor host's link came back", RECOVERY);
    wait_verdict(heard, up, RECOVERY, "a clear after the sensor link", |v| {
        v.verdict == GuardVerdict::Clear && v.views > 0
    });
    eprintln!(
        "multihost_netns: sensor host link down {:.1} s: stale after {:.1} s ({}); moving again {:.1} s after the link came back",
        (up - down).as_secs_f64(),
        stale_after.as_secs_f64(),
        stale.reason,
        up.elapsed().as_secs_f64()
    );

    // 4. The rogues. No certificate: refused (as a client; a peer keeps
    // retrying, linked to no one).
    let nocert = procs.get("nocert");
    for endpoint in [&hub, &arm_router] {
        let open = rogue_open(nocert, endpoint);
        assert_eq!(
            open["ok"], false,
            "a client without a certificate connects to {endpoint}"
        );
        eprintln!("multihost_netns: no certificate, client of {endpoint}: {open}");
    }
    for (name, what) in [("router", "router host"), ("arm", "arm host's launcher")] {
        let output = procs.get(name).output();
        let refused: Vec<&str> = (output.lines())
            .filter(|l| l.contains("sent no certificates"))
            .collect();
        assert!(!refused.is_empty(), "the {what} logs no refused handshake");
        eprintln!(
            "multihost_netns: the {what} refused {} TLS handshakes without a certificate: {:?}",
            refused.len(),
            refused.first()
        );
    }
    let nocert_peer = procs.get("nocert-peer");
    for endpoint in [&hub, &arm_router] {
        eprintln!(
            "multihost_netns: no certificate, peer of {endpoint}: {}",
            rogue_open(nocert_peer, endpoint)
        );
    }
    let sensor_rogue = procs.get("sensor-rogue");
    for endpoint in [&hub, &arm_router] {
        let open = rogue_open(sensor_rogue, endpoint);
        assert_eq!(open["ok"], true, "the sensor's certificate connects");
    }

    // The fit host's link down: the guard is cut off, the arm halts with no
    // verdict, and only forgeries could move it now.
    moving(observer, "before the fit host's link goes down", LONG);
    let at = mark(arm_host);
    lan.link_down("fit");
    let down = Instant::now();
    let why = arm_halts(arm_host, at, "the fit host's link down");
    let before: Vec<serde_json::Value> = [&hub, &arm_router]
        .iter()
        .map(|e| rogue_stats(sensor_rogue, e))
        .collect();
    let held = spread(observer, Duration::from_secs(2));
    let after: Vec<serde_json::Value> = [&hub, &arm_router]
        .iter()
        .map(|e| rogue_stats(sensor_rogue, e))
        .collect();
    assert!(
        held.is_some_and(|s| s <= 1e-6),
        "forged clears from the sensor's certificate moved the arm: largest joint step {held:?}"
    );
    arm_stayed_halted(arm_host, at, "forged clears from the sensor's certificate");
    for (b, a) in before.iter().zip(&after) {
        assert!(
            count(a, "collision") > count(b, "collision")
                && count(a, "joints_heard") > count(b, "joints_heard"),
            "the sensor rogue forged verdicts for live joint states meanwhile: {b} -> {a}"
        );
    }
    // The control: the same forgeries under the fit host's name move it.
    std::fs::write(&armed, "").unwrap();
    let control = moves_within(observer, Duration::from_secs(4));
    std::fs::remove_file(&armed).unwrap();
    let control_stats = rogue_stats(procs.get("control"), &hub);
    assert!(
        control,
        "the control: clears forged with the fit host's certificate do not move the arm either, \
         so the refused ones prove nothing: {control_stats}"
    );
    lan.link_up("fit");
    let up = Instant::now();
    moving(observer, "after the fit host's link came back", RECOVERY);
    wait_verdict(heard, up, RECOVERY, "a clear after the fit link", |v| {
        v.verdict == GuardVerdict::Clear && v.views > 0
    });
    eprintln!(
        "multihost_netns: fit host link down {:.1} s: the arm {why}; the sensor rogue forged {} verdicts through the router and {} to the arm host meanwhile, none moved it; the control's did; moving again {:.1} s after the link came back",
        (up - down).as_secs_f64(),
        count(&after[0], "collision") - count(&before[0], "collision"),
        count(&after[1], "collision") - count(&before[1], "collision"),
        up.elapsed().as_secs_f64()
    );

    // Nothing forged reached the observer but the control's verdicts, and
    // the guard judged no forged joint state.
    let sensor_total: Vec<serde_json::Value> = [&hub, &arm_router]
        .iter()
        .map(|e| rogue_stats(sensor_rogue, e))
        .collect();
    let peer_total: Vec<serde_json::Value> = [&hub, &arm_router]
        .iter()
        .map(|e| rogue_stats(nocert_peer, e))
        .collect();
    {
        let heard = lock(heard);
        let control_key = format!("rogue:control on shroud/{NS}/collision/demo_arm");
        let leaked: Vec<(&String, &u64)> = heard
            .forged
            .iter()
            .filter(|(k, _)| **k != control_key)
            .collect();
        assert!(
            leaked.is_empty(),
            "forged samples reached the observer: {leaked:?}; the sensor rogue sent {sensor_total:?}"
        );
        assert!(
            heard.forged.get(&control_key).is_some_and(|&n| n > 0),
            "the control's verdicts reach the observer: {:?}",
            heard.forged
        );
        assert_eq!(
            heard.judged_forged_joints, 0,
            "the guard judged forged joint states"
        );
    }
    for stats in &peer_total {
        assert_eq!(
            count(stats, "joints_heard") + count(stats, "surrogates_heard"),
            0,
            "a peer without a certificate hears the graph: {stats}"
        );
    }
    for (who, totals) in [
        ("with the sensor's certificate", &sensor_total),
        ("without a certificate (a peer)", &peer_total),
    ] {
        for (endpoint, stats) in [&hub, &arm_router].iter().zip(totals) {
            eprintln!(
                "multihost_netns: rogue {who}, to {endpoint}: {}",
                rogue_summary(stats)
            );
        }
    }

    // 5. Nothing was restarted: every launcher still runs its first nodes.
    let now = unix_ns();
    for (host, nodes) in [
        ("sensor", &["scanner"][..]),
        ("fit", &["fit", "guard"]),
        ("arm", &["arm"]),
    ] {
        let launcher = procs.get(host);
        let output = launcher.output();
        assert!(!output.contains("[launch] restarting"), "{host}: a restart");
        assert_eq!(
            output.matches("[launch] started ").count(),
            nodes.len(),
            "{host}: started more than its nodes"
        );
        let status = board.published_after(&format!("launcher.{host}"), now);
        for node in nodes {
            assert_eq!(status.counter(&format!("restarts.{node}")), 0, "{status:?}");
            assert_eq!(status.counter(&format!("starts.{node}")), 1, "{status:?}");
        }
        let pid = launcher.pid();
        assert!(
            common::alive(pid) && lan.pids(host).contains(&pid),
            "{host}'s launcher runs"
        );
    }
    eprintln!(
        "multihost_netns: passed in {:.1} s",
        started.elapsed().as_secs_f64()
    );
}

/// The arm host's link down past zenoh's 10 s lease, three times: the
/// sessions between the arm host's router and the router host expire, the
/// arm host's router connects again, and the arm must move again each time,
/// and still after the old session's lease has run out too.
#[test]
#[ignore = "fails with zenoh 1.10.2: about 10 s after the arm host's router reconnects from an \
            outage past the lease, the router host stops routing to it for good ('Could not find \
            corresponding link in routers network'), and the arm stays halted; --ignored runs it"]
fn the_arm_recovers_from_link_outages_past_the_lease() {
    let Some(demo) = Demo::start(&FAULTS) else {
        return;
    };
    let router = demo.procs.get("router");
    let lost = |line: &String| line.contains("Could not find corresponding link");
    for round in 1..=3 {
        let at = mark(router);
        let recovered = demo.arm_link_outage(Duration::from_secs(15), RECOVERY);
        // The first session closes for good about 10 s after the new one
        // opened: what routes through the router host after that?
        std::thread::sleep(Duration::from_secs(15));
        let still = recovered && moves_within(&demo.observer, RECOVERY);
        let errors = lines_since(router, at);
        let errors: Vec<&String> = errors.iter().filter(|l| lost(l)).collect();
        assert!(
            still,
            "round {round}: the arm {} after its host's link came back; the router host \
             logged {} lost-link errors, the first: {:?}",
            match recovered {
                true => "moved again, then stopped for good",
                false => "does not move again",
            },
            errors.len(),
            errors.first()
        );
        eprintln!(
            "multihost_netns: round {round}: still moving 15 s later ({} lost-link errors)",
            errors.len()
        );
    }
}

/// The link conditions: the sensor host's clouds cross the fit host's link
/// with the arm's joint states (in) and the guard's verdicts (out). The
/// observer hears verdicts, surrogates and joint states only (a cloud to it
/// would load the router host twice).
fn conditions_setup(points: usize) -> Setup {
    Setup {
        scene: STILL,
        points,
        relayed: &["fit"],
        watch: &["collision/demo_arm", "surrogate/spheres", "joints/demo_arm"],
    }
}

/// A condition of the fit host's link: delay and loss each way, a bandwidth
/// limit each way.
#[derive(Clone, Copy)]
struct Condition {
    name: &'static str,
    impairment: Impairment,
    mbit_s: Option<f64>,
}

const fn condition(name: &'static str, delay_ms: u64, loss: f64, mbit_s: Option<f64>) -> Condition {
    Condition {
        name,
        impairment: Impairment {
            delay: Duration::from_millis(delay_ms),
            loss,
        },
        mbit_s,
    }
}

/// The nodes whose counters a condition reads: the graph's, and the zenoh
/// routers of each host (where a congested link drops).
const COUNTED: [&str; 8] = [
    "scanner",
    "fit",
    "guard",
    "arm",
    "router.hub",
    "launcher.sensor",
    "launcher.fit",
    "launcher.arm",
];

/// What a condition did over a measurement window.
#[derive(Debug)]
struct Measured {
    /// Joint state to verdict at the observer (the fit host's link crossed
    /// both ways), median and 99th percentile, ms.
    loop_ms: Option<(f64, f64)>,
    /// Joint states heard in the window that a verdict heard by its end
    /// answers (the last second's are not asked about).
    answered: (usize, usize),
    /// Cloud stamp to surrogate at the observer, median and 99th percentile.
    surrogate_ms: Option<(f64, f64)>,
    /// Counter changes over the window, by `node/counter`.
    counted: BTreeMap<String, i64>,
    /// Verdicts heard, by kind.
    verdicts: BTreeMap<String, usize>,
    /// Seconds the arm was halted, from its status (`halted_s`) at the
    /// window's start and end, over the window: statuses up to a second off
    /// the window's ends may take it a little over 100 % (NaN without them).
    halted: f64,
    /// Frames the relay dropped for the loss probability.
    frames_lost: u64,
    /// Nodes whose status did not reach the observer within 5 s, at the
    /// window's start or end (their counters are left out).
    silent: Vec<&'static str>,
}

impl Measured {
    fn count(&self, node: &str, counter: &str) -> i64 {
        self.counted
            .get(&format!("{node}/{counter}"))
            .copied()
            .unwrap_or(0)
    }

    /// zenoh's congestion drops, every process together.
    fn congestion_drops(&self) -> i64 {
        (COUNTED.iter())
            .map(|node| self.count(node, "zenoh_dropped_congestion"))
            .sum()
    }

    fn row(&self, condition: &Condition) -> String {
        let ms =
            |p: Option<(f64, f64)>| p.map_or("none".into(), |(a, b)| format!("{a:.1} / {b:.1}"));
        let mut verdicts: Vec<String> = (self.verdicts.iter())
            .map(|(kind, n)| format!("{kind} {n}"))
            .collect();
        if !self.silent.is_empty() {
            verdicts.push(format!("(no status from {})", self.silent.join(", ")));
        }
        format!(
            "| {} | {} | {:.1} % | {} | {} / {} | {} | {} | {} | {:.0} % |",
            condition.name,
            ms(self.loop_ms),
            100.0 * self.answered.0 as f64 / self.answered.1.max(1) as f64,
            ms(self.surrogate_ms),
            self.count("fit", "received"),
            self.count("scanner", "published"),
            self.count("fit", "sequence_gaps"),
            self.congestion_drops(),
            verdicts.join(", "),
            100.0 * self.halted,
        )
    }
}

/// The median and 99th percentile of `values` (nearest rank, as the nodes'
/// latency gauges; none when empty).
fn percentiles(values: Vec<f64>) -> Option<(f64, f64)> {
    let mut window = Percentiles::new(values.len());
    values.into_iter().for_each(|v| window.push(v));
    window.summary().map(|s| (s.p50, s.p99))
}

impl Demo {
    /// Every counted node's status published after `after_ns`, of those
    /// whose status comes within 5 s (a silent node is left out).
    fn statuses(&self, after_ns: u64) -> BTreeMap<&'static str, shroud_msg::NodeStatusMessage> {
        let within = Duration::from_secs(5);
        (COUNTED.iter())
            .filter_map(|node| {
                let status = (self.board).try_wait_for(node, within, |s| s.stamp_ns >= after_ns);
                status.map(|s| (*node, s))
            })
            .collect()
    }

    /// Puts the fit host's link in `condition`, lets it settle, and measures
    /// what it does over `window`.
    fn measure(&self, condition: &Condition, settle: Duration, window: Duration) -> Measured {
        self.lan.impair("fit", condition.impairment);
        self.lan.limit_rate("fit", condition.mbit_s);
        std::thread::sleep(settle);
        let (start, start_ns) = (Instant::now(), unix_ns());
        let before = self.statuses(start_ns);
        let lost_before = self.lan.relay_counts("fit").lost;
        std::thread::sleep(window);
        let end = Instant::now();
        let after = self.statuses(unix_ns());
        let mut counted = BTreeMap::new();
        let mut silent = Vec::new();
        for node in COUNTED {
            let (Some(was), Some(now)) = (before.get(node), after.get(node)) else {
                silent.push(node);
                continue;
            };
            for (name, value) in &now.counters {
                let change = *value as i64 - was.counter(name) as i64;
                counted.insert(format!("{node}/{name}"), change);
            }
        }
        let seconds = |s: Option<&shroud_msg::NodeStatusMessage>| {
            s.and_then(|s| s.gauge("halted_s")).unwrap_or(f64::NAN)
        };
        let halted =
            (seconds(after.get("arm")) - seconds(before.get("arm"))) / (end - start).as_secs_f64();
        let heard = lock(&self.heard);
        let within = |t: &Instant| *t >= start && *t <= end;
        let answered: std::collections::BTreeSet<u64> = (heard.verdicts.iter())
            .filter(|(t, _)| within(t))
            .map(|(_, v)| v.joints_sequence)
            .collect();
        let asked: Vec<u64> = (heard.joints.iter())
            .filter(|(t, _)| within(t) && *t + Duration::from_secs(1) <= end)
            .map(|(_, sequence)| *sequence)
            .collect();
        let mut verdicts = BTreeMap::new();
        for (_, v) in heard.verdicts.iter().filter(|(t, _)| within(t)) {
            *verdicts
                .entry(format!("{:?}", v.verdict).to_lowercase())
                .or_default() += 1;
        }
        let in_window = |values: &[(Instant, f64)]| {
            (values.iter())
                .filter(|(t, _)| within(t))
                .map(|(_, ms)| *ms)
                .collect()
        };
        Measured {
            loop_ms: percentiles(in_window(&heard.loops_ms)),
            answered: (
                asked.iter().filter(|s| answered.contains(s)).count(),
                asked.len(),
            ),
            surrogate_ms: percentiles(in_window(&heard.surrogate_ms)),
            counted,
            verdicts,
            halted,
            frames_lost: self.lan.relay_counts("fit").lost - lost_before,
            silent,
        }
    }
}

/// The header of the link conditions table.
const TABLE_HEADER: &str = "| fit host's link (each way) | joint state → verdict, p50 / p99 ms | joint states answered | cloud → surrogate, p50 / p99 ms | clouds fitted / published | clouds lost (counted by the fit node) | zenoh congestion drops | verdicts | arm halted |
|---|---|---|---|---|---|---|---|---|";

/// Issue 26's link conditions, checked (not timed): with loss and a
/// bandwidth a third of the clouds' rate on the link that carries clouds in,
/// joint states in and verdicts out, verdicts keep answering joint states
/// (clouds do not starve them), every cloud the scanner published is fitted
/// or counted lost, and the graph recovers when the link does, restarting
/// nothing. (Whether the arm moves meanwhile depends on the link's latency
/// against its deadman: the table of `docs/multi-host.md` measures it.)
#[test]
fn a_slow_lossy_link_keeps_verdicts_flowing_and_counts_every_lost_cloud() {
    // A second round, on a fresh graph, only when the first one's failure
    // may be the stall of docs/multi-host.md's known gaps (zenoh 1.10.2: a
    // priority's droppable messages stop for good on a starved link); a
    // regression fails both.
    let mut failures = Vec::new();
    for round in 1..=2 {
        match slow_link_round() {
            Ok(()) => return,
            Err(why) => {
                eprintln!("multihost_netns: slow link, round {round}: {why}");
                failures.push(why);
            }
        }
    }
    panic!("the slow link failed twice, on fresh graphs: {failures:#?}");
}

/// Every counted node's status from now on, or which nodes were silent.
fn every_status(
    demo: &Demo,
) -> Result<BTreeMap<&'static str, shroud_msg::NodeStatusMessage>, String> {
    let heard = demo.statuses(unix_ns());
    let silent: Vec<&&str> = COUNTED
        .iter()
        .filter(|n| !heard.contains_key(**n))
        .collect();
    match silent.is_empty() {
        true => Ok(heard),
        false => Err(format!("no status within 5 s from {silent:?}")),
    }
}

/// One round of the slow link test: `Err` says what failed (a skip is
/// `Ok`).
fn slow_link_round() -> Result<(), String> {
    let Some(demo) = Demo::start(&conditions_setup(15_000)) else {
        return Ok(());
    };
    let check = |ok: bool, why: String| if ok { Ok(()) } else { Err(why) };
    check(
        moves_within(&demo.observer, LONG),
        "the arm does not move on a plain link".into(),
    )?;
    let calm = every_status(&demo)?;
    // 15 000 points at 10 Hz are 14 Mbit/s: a third can cross.
    let slow = condition("0.2 %, 5 Mbit/s", 0, 0.002, Some(5.0));
    let measured = demo.measure(&slow, Duration::from_secs(4), Duration::from_secs(12));
    eprintln!("multihost_netns: {TABLE_HEADER}\n{}", measured.row(&slow));
    check(
        measured.frames_lost > 0,
        "the relay dropped no frame".into(),
    )?;
    let (answered, asked) = measured.answered;
    check(
        asked > 0 && answered * 2 > asked,
        format!("verdicts answered {answered} of {asked} joint states across the slow link"),
    )?;
    // A lost cloud shows in the fit node's gaps only when a later one
    // arrives: counted below, once the link is plain again.
    let lost = measured.count("scanner", "published") - measured.count("fit", "received");
    check(
        lost > 0 && measured.congestion_drops() > 0,
        format!("clouds at three times the link's rate, yet none lost or zenoh counted no drop: {measured:?}"),
    )?;
    // Back to a plain link: the arm moves again, and every cloud published
    // since the calm before is fitted or counted lost.
    demo.lan.impair("fit", Impairment::default());
    demo.lan.limit_rate("fit", None);
    check(
        moves_within(&demo.observer, RECOVERY),
        format!("the arm does not move within {RECOVERY:?} once the link is plain again"),
    )?;
    let settled = every_status(&demo)?;
    let change = |node: &str, counter: &str| {
        settled[node].counter(counter) as i64 - calm[node].counter(counter) as i64
    };
    // The fit node's sequence gaps count every cloud it did not decode,
    // those it dropped from its queue too (`dropped_backlog`).
    let published = change("scanner", "published");
    let accounted = change("fit", "received") + change("fit", "sequence_gaps");
    // Each counter is as of its node's status: at 10 Hz, one cloud for every
    // 0.1 s between the scanner's and the fit node's, at either end, and a
    // few in flight.
    let skew = |node_a: &str, node_b: &str, at: &BTreeMap<&str, shroud_msg::NodeStatusMessage>| {
        at[node_a].stamp_ns.abs_diff(at[node_b].stamp_ns) as f64 * 1e-9
    };
    let lag = skew("scanner", "fit", &calm) + skew("scanner", "fit", &settled);
    let tolerance = (10.0 * lag).ceil() as i64 + 3;
    assert!(
        (published - accounted).abs() <= tolerance,
        "every cloud published is fitted or counted lost: {published} published, \
         {accounted} accounted for (tolerance {tolerance})"
    );
    for host in ["sensor", "fit", "arm"] {
        let launcher = &settled[format!("launcher.{host}").as_str()];
        let restarts: u64 = (launcher.counters.iter())
            .filter(|(name, _)| name.starts_with("restarts."))
            .map(|(_, n)| *n)
            .sum();
        assert_eq!(restarts, 0, "{host}: nodes restarted");
    }
    eprintln!(
        "multihost_netns: slow link: {answered} of {asked} joint states answered; \
         {published} clouds published, {accounted} fitted or counted lost"
    );
    Ok(())
}

/// The tables of `docs/multi-host.md`: the demo with clouds of
/// `SHROUD_LINK_POINTS` points (300 000 unless set) at 10 Hz, the fit host's
/// link in each condition (`SHROUD_LINK_CONDITIONS`, names separated by
/// `;`; all unless set), a fresh graph for each, and what each does to
/// latency and drops. A measurement, not a test: `cargo test -p shroud
/// --test multihost_netns -- --ignored --nocapture link_conditions_table`
/// (root and `ip netns`).
#[test]
#[ignore = "a measurement: prints the link conditions table of docs/multi-host.md"]
fn link_conditions_table() {
    let points: usize = std::env::var("SHROUD_LINK_POINTS")
        .ok()
        .and_then(|p| p.parse().ok())
        .unwrap_or(300_000);
    let conditions = [
        condition("as is", 0, 0.0, None),
        condition("10 ms", 10, 0.0, None),
        condition("50 ms", 50, 0.0, None),
        condition("1 % loss", 0, 0.01, None),
        condition("5 % loss", 0, 0.05, None),
        condition("100 Mbit/s", 0, 0.0, Some(100.0)),
        condition("20 Mbit/s", 0, 0.0, Some(20.0)),
        condition("20 ms, 1 %, 50 Mbit/s", 20, 0.01, Some(50.0)),
    ];
    let only = std::env::var("SHROUD_LINK_CONDITIONS").unwrap_or_default();
    let chosen = (conditions.iter())
        .filter(|c| only.is_empty() || only.split(';').any(|n| n.trim() == c.name));
    let mut rows = Vec::new();
    // A graph of its own for each condition: after a condition that starved
    // the fit host's link, zenoh 1.10.2 did not always deliver to that host
    // again (docs/multi-host.md, known gaps), which would leak into the next
    // row.
    for c in chosen {
        let Some(demo) = Demo::start(&conditions_setup(points)) else {
            return;
        };
        moving(&demo.observer, "on a plain link", LONG);
        let measured = demo.measure(c, Duration::from_secs(5), Duration::from_secs(20));
        eprintln!("{}", measured.row(c));
        eprintln!("  {measured:?}");
        rows.push(measured.row(c));
    }
    println!(
        "{points} points a cloud at 10 Hz ({:.0} Mbit/s)\n{TABLE_HEADER}\n{}",
        points as f64 * 12.0 * 8.0 * 10.0 / 1e6,
        rows.join("\n")
    );
}
