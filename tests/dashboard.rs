//! The dashboard end to end: a real graph (scanner, fit, guard, arm, blend),
//! the `dashboard` node, and the page in a real headless Chromium driven by
//! playwright-core (tests/browser/). The page loads without console errors,
//! draws the cloud and the surfaces, its plots advance, a killed node's row
//! turns red, a part dragged onto the cloud makes the blend node publish a
//! composed cloud with transition points, a stop verdict shows the STOP
//! banner, and a scaled clear verdict moves the speed gauge below 100 %.
//! Screenshots go to target/tmp/dashboard/<test>/.

mod common;

use common::browser::{browser_available, check, node_dies, out_dir};
use common::{hub_on_free_port, wait_sources, wiring, Proc};
use shroud_msg::{sample_collision, GuardVerdict};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;
use zenoh::Wait;

const START: Duration = Duration::from_secs(60);
const ARM_FILE: &str = "launch/arms/demo_arm.toml";

/// `shroud node <args...>` on the test's hub.
fn node(args: &[&str], w: &[&str]) -> Proc {
    Proc::start(&[args, w].concat())
}

/// The guard over `stream` (with `extra` options) and the simulated arm at
/// `rate` joint states a second, both with the demo's arm file.
fn guard_and_arm(stream: &str, extra: &[&str], rate: &str, w: &[&str]) -> (Proc, Proc) {
    let guard = [
        "node",
        "guard",
        "--arm-file",
        ARM_FILE,
        "--surrogate",
        stream,
        "--unobserved",
        "ignore",
    ];
    let arm = ["node", "arm", "--arm-file", ARM_FILE, "--rate", rate];
    (node(&[&guard[..], extra].concat(), w), node(&arm, w))
}

/// Starts the dashboard on a free port and returns it with its URL.
fn dashboard(w: &[&str]) -> (Proc, String) {
    let node = Proc::start(
        &[
            &[
                "node",
                "dashboard",
                "--listen",
                "127.0.0.1:0",
                "--arm-file",
                ARM_FILE,
                "--log",
                "info",
            ][..],
            w,
        ]
        .concat(),
    );
    let line = node.expect_line("serving the dashboard at ", START);
    let url = line
        .split("serving the dashboard at ")
        .nth(1)
        .expect("a URL after the words")
        .trim()
        .to_string();
    (node, url)
}

/// The demo's graph (moving spheres, a sandwich fit, the guard watching the
/// arm) with the dashboard: the page shows it all, and a killed fit node
/// turns red within two seconds.
#[test]
fn the_page_shows_the_demo_and_a_killed_node() {
    if !browser_available() {
        return;
    }
    let (endpoint, _hub) = hub_on_free_port();
    let w = wiring(&endpoint, "e2e-dash");
    let scene = "launch/scenes/demo_spheres.json";
    let _scanner = node(
        &[
            "node", "scanner", "--config", scene, "--rate", "10", "--stream", "spheres",
        ],
        &w,
    );
    let fit = node(
        &[
            "node", "fit", "--name", "fit", "--input", "spheres", "--grid", "16x16",
        ],
        &w,
    );
    let speed = ["--max-obstacle-speed", "1.3", "--max-age", "0.5"];
    let _guard_and_arm = guard_and_arm("spheres", &speed, "50", &w);
    let (_dashboard, url) = dashboard(&w);
    let out = out_dir("demo");
    check(&url, &out, "loads", &[]);
    let scene = check(&url, &out, "scene", &[]);
    eprintln!("scene: {scene}");
    let plots = check(
        &url,
        &out,
        "plots",
        &["--plots", "fit,latency,clearance,rates,drops"],
    );
    eprintln!("plots: {plots}");
    check(&url, &out, "screenshot", &[]);
    let died = node_dies(&url, &out, "fit", || fit.signal(libc::SIGKILL));
    let elapsed = died["elapsed_ms"].as_f64().expect("the time it took");
    assert!(
        elapsed < 2000.0,
        "the fit row turned red after {elapsed} ms: {died}"
    );
}

/// A blend node over the table top and a guard whose stop distance no arm
/// pose can clear: a part dragged from the palette onto the cloud comes back
/// composed with transition points, and the STOP banner shows the stop.
#[test]
fn a_dragged_part_is_blended_and_a_stop_shows_the_banner() {
    if !browser_available() {
        return;
    }
    let (endpoint, hub) = hub_on_free_port();
    let ns = "e2e-dash-blend";
    let w = wiring(&endpoint, ns);
    let models = hub
        .declare_subscriber(format!("shroud/{ns}/cloud/blend"))
        .wait()
        .unwrap();
    let table = [
        "--scene",
        "table-top",
        "--points",
        "20000",
        "--rate",
        "2",
        "--time-scale",
        "0",
    ];
    let _scanner = node(
        &[&["node", "scanner", "--stream", "table"][..], &table].concat(),
        &w,
    );
    let parts = [
        "--child-part",
        "hemisphere",
        "--child-part",
        "half-cylinder",
        "--part-size",
        "0.3",
    ];
    let blend = [
        "node",
        "blend",
        "--parent-stream",
        "table",
        "--stream",
        "blend",
        "--centres",
        "400",
    ];
    let _blend = node(&[&blend[..], &parts].concat(), &w);
    let _fit = node(&["node", "fit", "--input", "table", "--grid", "16x16"], &w);
    let _guard_and_arm = guard_and_arm("table", &["--stop-distance", "5"], "20", &w);
    let (_dashboard, url) = dashboard(&w);
    let out = out_dir("blend");
    let dragged = check(&url, &out, "drag_part", &[]);
    eprintln!("drag: {dragged}");
    // What the blend node published, seen on zenoh: the composed cloud.
    let counts = wait_sources(&models, START, |[_, _, transition]| transition > 0)
        .expect("no composed cloud with transition points");
    eprintln!("sources (parent, part, transition): {counts:?}");
    let banner = check(
        &url,
        &out,
        "stop_banner",
        &["--expect", "within the stop distance"],
    );
    let text = banner["text"].as_str().unwrap_or("").to_lowercase();
    assert!(text.contains("stop distance"), "{banner}");
}

/// The dashboard alone, fed on zenoh the verdict a guard with speed
/// monitoring publishes when a link's separation slows the arm (a `clear` at
/// 42 % of the velocity limits, limited by `forearm` at S_p 0.84 m), 20 times
/// a second: the speed gauge beside the banner shows 42 %, the limiting link
/// and S_p, with the bar filled to 42 %. (A real guard's scale follows the
/// arm's motion and the obstacle's: the verdict is published directly so
/// that the numbers the page must show are known.)
#[test]
fn a_scaled_clear_shows_the_speed_gauge_below_full_speed() {
    if !browser_available() {
        return;
    }
    let (endpoint, hub) = hub_on_free_port();
    let ns = "e2e-dash-speed";
    let w = wiring(&endpoint, ns);
    let (_dashboard, url) = dashboard(&w);
    let mut verdict = sample_collision(GuardVerdict::Clear);
    verdict.arm = "demo_arm".into();
    (
        verdict.speed_scale,
        verdict.limiting_link,
        verdict.protective_distance,
    ) = (0.42, "forearm".into(), 0.84);
    let done = Arc::new(AtomicBool::new(false));
    let stop_publishing = StopOnDrop(done.clone());
    let guard = {
        let done = done.clone();
        let key = format!("shroud/{ns}/collision/demo_arm");
        std::thread::spawn(move || {
            while !done.load(Ordering::Relaxed) {
                verdict.joints_sequence += 1;
                hub.put(&key, verdict.to_bytes().unwrap()).wait().unwrap();
                std::thread::sleep(Duration::from_millis(50));
            }
        })
    };
    let out = out_dir("speed");
    let gauge = check(
        &url,
        &out,
        "speed_gauge",
        &["--expect", "limited by forearm (S_p 0.840 m)"],
    );
    drop(stop_publishing);
    guard.join().unwrap();
    eprintln!("gauge: {gauge}");
    assert_eq!(gauge["arm"], "demo_arm", "{gauge}");
    assert_eq!(gauge["scale"].as_f64(), Some(0.42), "{gauge}");
    let text = gauge["text"].as_str().unwrap_or("");
    assert!(text.contains("42 % speed"), "{gauge}");
    let filled = gauge["filled"].as_f64().unwrap_or(-1.0);
    assert!(
        (filled - 0.42).abs() < 0.02,
        "the bar is {filled} full: {gauge}"
    );
    // A scaled clear is still a clear: the banner is green.
    assert_eq!(gauge["banner"], "clear", "{gauge}");
}

/// Sets its flag when dropped: a publishing thread stops even when the test
/// fails before it says so.
struct StopOnDrop(Arc<AtomicBool>);

impl Drop for StopOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}
