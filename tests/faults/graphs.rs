//! The launch files of the fault tests: the demo's chain on a scene beside the
//! arm, the flood's graph of every subscribing node kind, and the lidar chain
//! of `launch/lidar.toml` on a faulty emulated URG.

use crate::common::device_rig::TILTING;
use crate::ARM_FILE;

/// The paper's two moving spheres, 5000 points, beside the demo arm (around
/// y = -2.6; the arm reaches about 1.4 m from its mount over the origin): the
/// guard clears the arm, so that every halt has a fault as its cause.
pub const SCENE: &str = r#"{"kind": "moving-spheres", "points": 5000, "radii": [0.5, 0.4],
 "paths": [{"centre": [-0.6, -2.6, 0.3], "amplitude": [0.2, 0.1, 0.1], "angular_speed": [0.5, 0.5, 1.0], "phase": [0.0, 0.0, 0.0]},
           {"centre": [0.6, -2.6, 0.3], "amplitude": [0.2, 0.1, 0.1], "angular_speed": [0.5, 0.5, 1.0], "phase": [1.0, 0.0, 0.0]}],
 "seed": 7}"#;

/// Writes [`SCENE`] as `scene.json` in the graph's dir.
pub fn write_scene(dir: &std::path::Path) {
    std::fs::write(dir.join("scene.json"), SCENE).unwrap();
}

/// A `[[node]]` table of `kind` with its ports (TOML lines such as
/// `inputs = { cloud = "s" }`) and its settings given as options
/// (`["--grid", "10x10"]` is `grid = "10x10"`, a repeated option an array,
/// an option without a value a switch): restarted on failure after 0.5 s
/// (doubling after each quick failure), its status every 0.2 s.
pub fn node(name: &str, kind: &str, ports: &str, options: &[&str]) -> String {
    let mut values: Vec<(String, Vec<String>)> = Vec::new();
    let mut rest = options.iter().peekable();
    while let Some(option) = rest.next() {
        let key = option.trim_start_matches("--").replace('-', "_");
        let value = match rest.next_if(|v| !v.starts_with("--")) {
            Some(value) => format!("{value:?}"),
            None => "true".to_string(),
        };
        match values.iter_mut().find(|(k, _)| *k == key) {
            Some((_, list)) => list.push(value),
            None => values.push((key, vec![value])),
        }
    }
    let mut settings = vec!["status_period = 0.2".to_string()];
    settings.extend(values.into_iter().map(|(key, list)| match list.len() {
        1 => format!("{key} = {}", list[0]),
        _ => format!("{key} = [{}]", list.join(", ")),
    }));
    format!(
        "[[node]]\nname = \"{name}\"\nkind = \"{kind}\"\n{ports}\nrestart = \"on-failure\"\nbackoff_ms = 500\n[node.settings]\n{}\n",
        settings.join("\n")
    )
}

/// A launch file: namespace, shared memory on or off, the streams the test
/// itself publishes (`kind/name`), the nodes.
pub fn graph(ns: &str, shm: bool, external: &[&str], nodes: &[String]) -> String {
    let external: Vec<String> = external.iter().map(|e| format!("{e:?}")).collect();
    format!(
        "namespace = \"{ns}\"\nshutdown_grace_s = 5\nexternal = [{}]\n[zenoh]\nshm = {shm}\n[summary]\nperiod_s = 1.0\n{}",
        external.join(", "),
        nodes.concat()
    )
}

fn fit(input: &str) -> String {
    let ports =
        format!("inputs = {{ cloud = \"{input}\" }}\noutputs = {{ surrogate = \"{input}\" }}");
    let args = ["--grid", "10x10", "--side", "sandwich", "--dir", "0,0,-1"];
    node("fit", "fit", &ports, &args)
}

/// The ports of the guard and the arm of the demo arm.
const GUARD_PORTS: &str = "inputs = { surrogate = \"SURROGATE\", joints = \"demo_arm\" }\n\
                           outputs = { collision = \"demo_arm\" }";
const ARM_PORTS: &str =
    "inputs = { collision = \"demo_arm\" }\noutputs = { joints = \"demo_arm\" }";

fn guard(surrogate: &str, max_age: &str) -> String {
    let policy = ["--max-age", max_age, "--unobserved", "ignore"];
    let ports = GUARD_PORTS.replace("SURROGATE", surrogate);
    node(
        "guard",
        "guard",
        &ports,
        &[&["--arm-file", ARM_FILE][..], &policy].concat(),
    )
}

fn arm() -> String {
    node(
        "arm",
        "arm",
        ARM_PORTS,
        &["--arm-file", ARM_FILE, "--rate", "50"],
    )
}

/// The scanner of `{dir}/scene.json` at 10 Hz on stream `s`.
pub fn scanner() -> String {
    let args = ["--config", "{dir}/scene.json", "--rate", "10"];
    node("scanner", "scanner", "outputs = { cloud = \"s\" }", &args)
}

/// The demo's chain: scanner → fit (a 10 x 10 sandwich) → guard (surrogates
/// older than `max_age` vouch for nothing) ← arm (50 Hz).
pub fn demo_chain(max_age: &str) -> Vec<String> {
    vec![scanner(), fit("s"), guard("s", max_age), arm()]
}

/// The scanner and the fit of the demo, and the dashboard.
pub fn stall_graph(ns: &str) -> String {
    let dashboard = node("dashboard", "dashboard", "", &["--listen", "127.0.0.1:0"]);
    graph(ns, true, &[], &[scanner(), fit("s"), dashboard])
}

/// Every node kind that subscribes, on stream `s` with no scanner (the test
/// is the sensor, so that it knows every cloud each node was sent): the fit,
/// guard and arm, the smooth fitter, the blend node (its parent the first
/// cloud of `s`, its commands on `blend/blend`) and the dashboard.
pub fn flood_graph(ns: &str) -> String {
    let smooth_ports = "inputs = { cloud = \"s\" }\noutputs = { smooth = \"s\" }";
    let blend_ports =
        "inputs = { cloud = \"s\", blend = \"blend\" }\noutputs = { cloud = \"blend\" }";
    let part = ["--child-part", "hemisphere", "--part-points", "500"];
    let dashboard = ["--listen", "127.0.0.1:0", "--arm-file", ARM_FILE];
    let nodes = [
        fit("s"),
        guard("s", "0.5"),
        arm(),
        node(
            "smooth",
            "smooth",
            smooth_ports,
            &["--domain", "plane:-1.1,-1.1,1.1,1.1,2"],
        ),
        node("blend", "blend", blend_ports, &part),
        node("dashboard", "dashboard", "", &dashboard),
    ];
    graph(ns, false, &["cloud/s", "blend/blend"], &nodes)
}

/// `launch/lidar.toml` (an emulated URG on a tilt unit → serial node → fit
/// from above → guard ← arm) with a URG that is unplugged 10 s after it
/// starts, for 4 s, and prefixes every 10th scan with garbage.
pub fn lidar_graph(ns: &str) -> String {
    let link = ["--link", "{dir}/urg", "--world", "table-top"];
    let faults = [
        "--garbage-every",
        "10",
        "--unplug-after",
        "10",
        "--unplug-for",
        "4",
    ];
    let device = [&["--device", "urg-04lx"][..], &link, &TILTING, &faults].concat();
    let lidar = [&["--device", "hokuyo", "--port", "{dir}/urg"][..], &TILTING].concat();
    let fit_ports = "inputs = { cloud = \"lidar\" }\noutputs = { surrogate = \"lidar\" }";
    let fit = ["--grid", "16x16", "--side", "upper", "--dir", "0,0,-1"];
    // As lidar.toml: sweeps of 1 s, so surrogates up to 2.5 s old vouch.
    let guard = ["--arm-file", ARM_FILE, "--max-age", "2.5"];
    let policy = ["--max-obstacle-speed", "0.05", "--unobserved", "ignore"];
    let nodes = [
        node("urg", "device-sim", "", &device),
        node("lidar", "serial", "outputs = { cloud = \"lidar\" }", &lidar),
        node("fit", "fit", fit_ports, &fit),
        node(
            "guard",
            "guard",
            &GUARD_PORTS.replace("SURROGATE", "lidar"),
            &[&guard[..], &policy].concat(),
        ),
        arm(),
    ];
    graph(ns, true, &[], &nodes)
}
