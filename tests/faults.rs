//! Fault injection on the running graph, end to end with real processes
//! started by `shroud launch`, real zenoh sessions and a real pseudo-terminal:
//! nodes killed with SIGKILL, a flood of garbage, truncated and wrong-version
//! messages on every topic kind, consumers that stop reading, a lidar
//! unplugged and spewing garbage, and the launcher itself killed. Each test
//! prints what it measured (`faults: ...` lines) and checks what a user needs
//! to stay true. Every wait is bounded; the one comparison of times (the fit
//! latency with and without a stalled consumer) is a ratio of medians
//! measured in the same run.

#[path = "faults/accounting.rs"]
mod accounting;
#[path = "faults/bad_messages.rs"]
mod bad_messages;
mod common;
#[path = "faults/feeder.rs"]
mod feeder;
#[path = "faults/flood.rs"]
mod flood;
#[path = "faults/graphs.rs"]
mod graphs;
#[path = "faults/heard.rs"]
mod heard;
#[path = "faults/outputs.rs"]
mod outputs;
#[path = "faults/shm.rs"]
mod shm;

use common::launched::{pids_of, Launched};
use common::status_board::StatusBoard;
use common::websocket::RawWebSocket;
use common::{alive, assert_all_gone, client_of, inbox, peer_session, unix_ns, wait_moving, Proc};
use feeder::Feeder;
use flood::{Flood, BAD};
use heard::{median, Heard};
use outputs::{Counts, Outputs};
use shroud_msg::{GuardVerdict, NodeStatusMessage};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};
use zenoh::Wait;

const LONG: Duration = Duration::from_secs(60);
/// How long a graph may take to get back to work after a fault.
const RECOVERY: Duration = Duration::from_secs(30);
const ARM_FILE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/launch/arms/demo_arm.toml");

/// One graph at a time: the tests share the machine's cores with the graphs
/// they start, and one test measures latency.
fn one_graph() -> MutexGuard<'static, ()> {
    static ONE: Mutex<()> = Mutex::new(());
    ONE.lock().unwrap_or_else(|p| p.into_inner())
}

fn label<'a>(status: &'a NodeStatusMessage, key: &str) -> &'a str {
    status.labels.get(key).map_or("", String::as_str)
}

/// Polls `done` for up to [`RECOVERY`]; whether it came true.
fn wait_until(done: impl Fn() -> bool) -> bool {
    let deadline = Instant::now() + RECOVERY;
    while !done() {
        if Instant::now() > deadline {
            return false;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    true
}

/// Stops the graph with SIGTERM: it must stop cleanly.
fn stop(mut graph: Launched) {
    graph.launcher.signal(libc::SIGTERM);
    let status = graph.launcher.wait_exit(LONG);
    let output = graph.launcher.output();
    assert!(status.success(), "{output}");
    assert!(output.contains("all nodes stopped cleanly"), "{output}");
    assert!(!output.contains("panicked"), "{output}");
}

/// Waits until the arm moves, within `timeout`; returns how long it took.
fn arm_moves(session: &zenoh::Session, ns: &str, graph: &Launched, timeout: Duration) -> f64 {
    let start = Instant::now();
    let joints = inbox(session, format!("shroud/{ns}/joints/demo_arm"));
    wait_moving(&joints, "the graph at work", &[&graph.launcher], timeout);
    start.elapsed().as_secs_f64()
}

/// The dashboard's address (`127.0.0.1:PORT`), from the launcher's output.
fn dashboard_address(launcher: &Proc) -> String {
    let line = launcher.expect_line("in a browser", LONG);
    let url = line.split("http://").nth(1).expect("a URL");
    url.split('/').next().unwrap().to_string()
}

/// One real message of `key`, as the graph publishes it.
fn one_real(session: &zenoh::Session, key: &str) -> Vec<u8> {
    let sub = session.declare_subscriber(key).wait().unwrap();
    let sample = sub.recv_timeout(LONG).unwrap();
    let sample = sample.unwrap_or_else(|| panic!("nothing on {key}"));
    sample.payload().to_bytes().into_owned()
}

/// SIGKILL of the scanner, the fit and the guard in turn: the launcher
/// restarts each after its backoff and counts it in its status, the arm halts
/// while the guard cannot vouch for it (stale surrogates without a scanner or
/// a fitter, no verdict at all without a guard), and the graph recovers.
#[test]
fn faults_killed_nodes_are_restarted_and_the_arm_waits_for_the_guard() {
    let _one = one_graph();
    let ns = "faults-kill";
    let file = graphs::graph(ns, true, &[], &graphs::demo_chain("0.3"));
    let graph = Launched::start(&file, graphs::write_scene);
    let session = client_of(&graph.endpoint);
    let board = StatusBoard::new(&session, ns);
    arm_moves(&session, ns, &graph, LONG);
    for (victim, cause) in [
        ("scanner", GuardVerdict::Stale),
        ("fit", GuardVerdict::Stale),
        ("guard", GuardVerdict::NoVerdict),
    ] {
        kill_and_recover((&board, &session, &graph, ns), victim, cause);
    }
    let output = graph.launcher.output();
    for victim in ["scanner", "fit", "guard"] {
        let line = format!("[launch] restarting {victim} in 0.50 s");
        assert!(output.contains(&line), "the backoff of {victim}: {output}");
    }
    let launcher = board.published_after("launcher", unix_ns());
    for (node, restarts) in [("scanner", 1), ("fit", 1), ("guard", 1), ("arm", 0)] {
        let counted = launcher.counter(&format!("restarts.{node}"));
        assert_eq!(counted, restarts, "{launcher:?}");
    }
    stop(graph);
}

/// Kills `victim` with SIGKILL; the arm halts for `cause`, the launcher
/// restarts the victim as a new process, and the arm moves again.
fn kill_and_recover(
    (board, session, graph, ns): (&StatusBoard, &zenoh::Session, &Launched, &str),
    victim: &str,
    cause: GuardVerdict,
) {
    let (restarts, pid) = (format!("restarts.{victim}"), format!("pid.{victim}"));
    let launcher = board.published_after("launcher", unix_ns());
    let old_pid: i32 = label(&launcher, &pid).parse().unwrap();
    let halts = cause.halt_counter();
    let halts_before = board.published_after("arm", unix_ns()).counter(halts);
    let killed = Instant::now();
    unsafe {
        libc::kill(old_pid, libc::SIGKILL);
    }
    board.wait_for("arm", halts, RECOVERY, |s| s.counter(halts) > halts_before);
    let halted_after = killed.elapsed().as_secs_f64();
    let restarted = board.wait_for("launcher", "the restart", RECOVERY, |s| {
        s.counter(&restarts) == launcher.counter(&restarts) + 1
            && label(s, &format!("state.{victim}")) == "running"
            && label(s, &pid) != old_pid.to_string()
    });
    let new_pid: i32 = label(&restarted, &pid).parse().unwrap();
    assert!(
        !alive(old_pid) && alive(new_pid),
        "{victim}: {old_pid} -> {new_pid}"
    );
    arm_moves(session, ns, graph, RECOVERY);
    eprintln!(
        "faults: SIGKILL {victim} (pid {old_pid}): arm halted ({halts}) after {halted_after:.2} s; \
         restarted as pid {new_pid} ({restarts} = {}); arm moving again {:.2} s after the kill",
        restarted.counter(&restarts),
        killed.elapsed().as_secs_f64()
    );
}

/// Garbage, truncated and wrong-version messages on every topic kind, sent as
/// fast as zenoh takes them while valid clouds keep coming: every node keeps
/// working, counts each bad message it took exactly once (or dropped it
/// unread with its backlog, counted too), and derives nothing from one.
#[test]
fn faults_a_flood_of_bad_messages_is_counted_once_and_never_used() {
    let _one = one_graph();
    let ns = "faults-flood";
    let graph = Launched::start(&graphs::flood_graph(ns), |_| {});
    let dashboard = dashboard_address(&graph.launcher);
    let session = client_of(&graph.endpoint);
    let board = StatusBoard::new(&session, ns);
    let outputs = Outputs::watch(&session, ns, "s", "demo_arm");
    let feeder = Feeder::start(&session, format!("shroud/{ns}/cloud/s"));
    // A browser that keeps up: the dashboard decodes what it draws.
    let browser = RawWebSocket::connect(&dashboard, None).keep_reading();
    arm_moves(&session, ns, &graph, LONG);
    for node in ["fit", "smooth", "blend"] {
        board.wait_for(node, "a publication", LONG, |s| s.counter("published") > 0);
    }
    board.wait_for("dashboard", "a browser", LONG, |s| {
        s.gauge("browsers") == Some(1.0)
    });
    let flood = Flood::of_graph(&session, ns);

    let nodes = [
        "fit",
        "smooth",
        "blend",
        "guard",
        "arm",
        "dashboard",
        "launcher",
    ];
    feeder.pause();
    let before = accounting::settled(&board, &nodes);
    let valid_before = feeder.sent();
    feeder.resume();
    let rate = flood.send(&session);
    feeder.pause();
    let valid = feeder.sent() - valid_before;
    eprintln!(
        "faults: flood of {} bad messages ({} garbage, truncated and wrong-version each on {} keys) \
         at {rate:.0} messages/s within its bursts; {valid} valid clouds meanwhile",
        flood.messages(),
        flood::N,
        flood.keys.len()
    );

    flood::check_fitter(&board, "fit", &before["fit"], valid);
    flood::check_fitter(&board, "smooth", &before["smooth"], valid);
    flood::check_blend(&board, &before["blend"]);
    flood::check_callback_nodes(&board, &before);
    // The dashboard hears every key but the blend commands.
    let to_dashboard = BAD * (flood.keys.len() as u64 - 1);
    let dash = flood::check_dashboard(&board, &before["dashboard"], to_dashboard);
    outputs.counts.check(BAD);

    // A browser joining now is greeted with the latest of every stream: a bad
    // sample is not decoded (and counted) a second time.
    let second = RawWebSocket::connect(&dashboard, None).keep_reading();
    let joined = unix_ns();
    let greeted = board.wait_for("dashboard", "two browsers", RECOVERY, |s| {
        s.gauge("browsers") == Some(2.0) && s.stamp_ns > joined + 1_000_000_000
    });
    let malformed = |s: &NodeStatusMessage| s.counter("dropped_malformed");
    assert_eq!(malformed(&greeted), malformed(&dash.now));

    // Back to work, every node the process it was.
    feeder.resume();
    let recovered = arm_moves(&session, ns, &graph, RECOVERY);
    let counts = &outputs.counts;
    let (surrogates, fits) = (
        Counts::get(&counts.surrogates),
        Counts::get(&counts.smooth_fits),
    );
    assert!(wait_until(
        || Counts::get(&counts.surrogates) > surrogates && Counts::get(&counts.smooth_fits) > fits
    ));
    let read = browser.bytes();
    assert!(wait_until(|| browser.bytes() > read && second.bytes() > 0));
    let launcher = board.published_after("launcher", unix_ns());
    for node in &nodes[..6] {
        let restarts = launcher.counter(&format!("restarts.{node}"));
        assert_eq!(restarts, 0, "{launcher:?}");
    }
    eprintln!(
        "faults: after the flood the arm moved again within {recovered:.2} s; no node restarted"
    );
    drop((browser, second, feeder));
    stop(graph);
}

/// Lines a `shroud topic echo` printed (one per message).
fn echoed(echo: &Proc) -> usize {
    let seen = echo.seen.lock().unwrap();
    seen.iter().filter(|l| l.starts_with("{\"key\"")).count()
}

/// `shroud topic echo TOPIC` on the graph: a zenoh subscriber in a process of
/// its own, to stop with SIGSTOP.
fn echo(graph: &Launched, ns: &str, topic: &str) -> Proc {
    let wiring = [
        "--namespace",
        ns,
        "--connect",
        &graph.endpoint,
        "--multicast",
        "off",
    ];
    let echo = Proc::start(&[&["topic", "echo", topic][..], &wiring].concat());
    echo.expect_line("{\"key\"", LONG);
    echo
}

/// Consumers that stop reading: two zenoh subscribers in processes of their
/// own (`shroud topic echo` of the clouds and of the surrogates, stopped with
/// SIGSTOP) and a dashboard browser that stops reading its WebSocket. The
/// fit's latency stays flat (median with the stall at most twice the median
/// without, measured before and after it), the dashboard drops the frames the
/// browser cannot take by its policy (the latest per stream: counted as
/// `frames_superseded`), and the stopped subscribers hear the graph again
/// once they read.
#[test]
fn faults_stalled_consumers_leave_the_fit_latency_flat() {
    let _one = one_graph();
    let ns = "faults-stall";
    let graph = Launched::start(&graphs::stall_graph(ns), graphs::write_scene);
    let dashboard = dashboard_address(&graph.launcher);
    let session = client_of(&graph.endpoint);
    let board = StatusBoard::new(&session, ns);
    let latencies = Heard::watch(
        &session,
        format!("shroud/{ns}/surrogate/s"),
        heard::latency_ms,
    );
    let echoes = [echo(&graph, ns, "cloud/s"), echo(&graph, ns, "surrogate/s")];
    board.wait_for("fit", "surrogates", LONG, |s| s.counter("published") >= 10);
    let window = Duration::from_secs(4);
    let before = latencies.over(window);

    for e in &echoes {
        e.signal(libc::SIGSTOP);
    }
    let stalled_browser = RawWebSocket::connect(&dashboard, Some(4096));
    let (dash, scanner) = (
        board.published_after("dashboard", unix_ns()),
        board.published_after("scanner", unix_ns()),
    );
    let heard = echoed(&echoes[0]);
    let superseded = |s: &NodeStatusMessage| s.counter("frames_superseded");
    board.wait_for("dashboard", "frames superseded", RECOVERY, |s| {
        superseded(s) > superseded(&dash)
    });
    let during = latencies.over(window);
    let (dash_stalled, scanner_stalled, fit) = (
        board.published_after("dashboard", unix_ns()),
        board.published_after("scanner", unix_ns()),
        board.published_after("fit", unix_ns()),
    );
    for e in &echoes {
        e.signal(libc::SIGCONT);
    }
    drop(stalled_browser);
    let after = latencies.over(window);
    assert!(
        wait_until(|| echoed(&echoes[0]) > heard && echoed(&echoes[1]) > 0),
        "the stopped subscribers hear the graph again"
    );

    for (when, samples) in [("before", &before), ("during", &during), ("after", &after)] {
        assert!(
            samples.len() >= 5,
            "{when} the stall: {} surrogates",
            samples.len()
        );
    }
    let unstalled: Vec<f64> = before.iter().chain(&after).copied().collect();
    let (p50, p50_stalled) = (median(&unstalled), median(&during));
    eprintln!(
        "faults: fit latency p50 {:.1} ms before, {p50_stalled:.1} ms during, {:.1} ms after the stall \
         ({} / {} / {} surrogates); frames superseded for the stalled browser: {}; clouds published \
         during the stall: {}; the fit's backlog drops so far: {}",
        median(&before),
        median(&after),
        before.len(),
        during.len(),
        after.len(),
        superseded(&dash_stalled) - superseded(&dash),
        scanner_stalled.counter("published") - scanner.counter("published"),
        fit.counter("dropped_backlog")
    );
    assert!(
        p50_stalled <= 2.0 * p50,
        "the fit latency stays flat: p50 {p50_stalled:.1} ms stalled vs {p50:.1} ms"
    );
    drop(echoes);
    stop(graph);
}

/// A lidar unplugged and replugged behind its stable link while it spews
/// garbage: the serial node counts the garbage and reconnects (a disconnect,
/// a second handshake, streaming again), the guard halts the arm while the
/// sensor is away (its surrogates go stale), and certified surrogates of the
/// replugged sensor's sweeps release it. Unplugging alone is in
/// `tests/devices.rs`; this is the whole graph downstream of it.
#[test]
fn faults_an_unplugged_lidar_halts_the_arm_until_certified_surrogates_return() {
    let _one = one_graph();
    let ns = "faults-lidar";
    let graph = Launched::start(&graphs::lidar_graph(ns), |_| {});
    let session = client_of(&graph.endpoint);
    let board = StatusBoard::new(&session, ns);
    let surrogates = Heard::watch(
        &session,
        format!("shroud/{ns}/surrogate/lidar"),
        heard::certified,
    );
    let started = Instant::now();
    let at = || started.elapsed().as_secs_f64();
    let first_move = arm_moves(&session, ns, &graph, LONG);
    // Stale halts while the graph started (a halt counts under every cause
    // that held it) are not the unplug's.
    let stale_before = board
        .published_after("arm", unix_ns())
        .counter("halts_stale");
    let gone = board.wait_for("lidar", "a disconnect", LONG, |s| {
        s.counter("disconnects") >= 1
    });
    let unplugged = at();
    assert_eq!(label(&gone, "device.kind"), "hokuyo", "{gone:?}");
    // After the first move, surrogates are never stale before the unplug: a
    // stale halt (or a stop that turns stale, counted under both causes) is
    // its doing.
    board.wait_for("arm", "a halt for stale surrogates", RECOVERY, |s| {
        s.counter("halts_stale") > stale_before
    });
    let halted = at();
    let back = board.wait_for("lidar", "a second handshake and streaming", RECOVERY, |s| {
        s.counter("handshakes") >= 2 && label(s, "device.state") == "streaming"
    });
    let (replugged, streaming) = (Instant::now(), at());
    let moving = arm_moves(&session, ns, &graph, RECOVERY);
    let (all, after_replug) = (surrogates.since(started), surrogates.since(replugged));
    assert!(all.iter().all(|ok| *ok), "every surrogate is certified");
    assert!(
        !after_replug.is_empty(),
        "surrogates of the replugged sensor"
    );
    let lidar = board.wait_for("lidar", "garbage counted", RECOVERY, |s| {
        s.counter("garbage") > 0
    });
    let arm = board.published_after("arm", unix_ns());
    eprintln!(
        "faults: lidar: arm moving after {first_move:.1} s; disconnect seen at {unplugged:.1} s; arm halted (stale) \
         at {halted:.1} s; streaming again at {streaming:.1} s; arm moving {moving:.1} s later; {} certified surrogates, \
         none uncertified; arm: halts_stale {}, halted {:.1} s of its {:.1} s (its start included); lidar: garbage {}, \
         bad_checksum {}, disconnects {}, handshakes {}, clouds {}",
        all.len(),
        arm.counter("halts_stale"),
        arm.gauge("halted_s").unwrap_or(0.0),
        arm.uptime_s,
        lidar.counter("garbage"),
        lidar.counter("bad_checksum"),
        lidar.counter("disconnects"),
        back.counter("handshakes"),
        lidar.counter("clouds")
    );
    assert_eq!(
        arm.counter("halts_stale") - stale_before,
        1,
        "one stale halt, the unplug's: {arm:?}"
    );
    stop(graph);
}

/// The launcher killed with SIGKILL while its graph moves clouds through
/// shared memory: every node exits (checked by pid) and no shared-memory
/// segment any process of the graph used is left in /dev/shm.
#[test]
fn faults_a_killed_launcher_leaves_no_node_and_no_shared_memory() {
    let _one = one_graph();
    let ns = "faults-orphans";
    // 12000 points: 144 KB clouds, above the nodes' shared-memory threshold.
    let file = graphs::graph(ns, true, &[], &graphs::demo_chain("0.5"));
    let mut graph = Launched::start(&file, |dir| {
        let scene = graphs::SCENE.replace("5000", "12000");
        std::fs::write(dir.join("scene.json"), scene).unwrap()
    });
    let nodes = common::KillOnDrop(pids_of(
        &graph.launcher,
        &["scanner", "fit", "guard", "arm"],
    ));
    // The test's own session takes no shared buffer (it would hold them).
    let session = peer_session(&[
        ("connect/endpoints", format!("[\"{}\"]", graph.endpoint)),
        ("listen/endpoints", "[\"tcp/127.0.0.1:0\"]".to_string()),
        ("transport/shared_memory/enabled", "false".to_string()),
    ]);
    let board = StatusBoard::new(&session, ns);
    board.wait_for("scanner", "clouds through shared memory", LONG, |s| {
        s.counter("sent_shm") > 0
    });
    board.wait_for("fit", "surrogates", LONG, |s| s.counter("published") > 0);
    let everyone: Vec<i32> = [graph.launcher.pid()]
        .iter()
        .chain(&nodes.0)
        .copied()
        .collect();
    let segments = shm::segments_of(&everyone);
    assert!(!segments.is_empty(), "the graph uses shared memory");
    let own = shm::segments_of(&[std::process::id() as i32]);
    assert!(own.is_disjoint(&segments), "the test holds none: {own:?}");

    let killed = Instant::now();
    graph.launcher.signal(libc::SIGKILL);
    graph.launcher.wait_exit(LONG);
    assert_all_gone(&nodes.0, Duration::from_secs(15));
    let exited = killed.elapsed().as_secs_f64();
    let cleaned = wait_until(|| shm::left(&segments).is_empty());
    let left = shm::left(&segments);
    assert!(cleaned, "segments left behind: {left:?} (of {segments:?})");
    eprintln!(
        "faults: launcher SIGKILLed: its {} nodes exited within {exited:.2} s; the {} zenoh segments \
         the graph used are all gone from /dev/shm",
        nodes.0.len(),
        segments.len()
    );
}
