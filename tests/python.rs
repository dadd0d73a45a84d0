//! The Python example of `docs/formats.md`, run as documented against real nodes:
//! proves that a consumer in another language decodes what the nodes send with
//! the documented layout. The test installs its own Python environment (pinned
//! eclipse-zenoh, msgpack, numpy from PyPI) under the target directory.

mod common;

use common::{free_port, hub, wiring, Proc};
use shroud_msg::CloudMessage;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};
use zenoh::Wait;

const PACKAGES: [&str; 3] = ["eclipse-zenoh==1.10.2", "msgpack==1.1.2", "numpy==2.2.6"];

/// The venv with the example's packages.
fn python() -> PathBuf {
    common::python::python_with("pyenv", &PACKAGES)
}

/// The code block between the `marker` markers of `docs/formats.md`.
fn documented_example(marker: &str) -> String {
    let doc =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/formats.md")).unwrap();
    let start = doc
        .find(&format!("<!-- {marker}:start -->"))
        .expect("start marker");
    let end = doc
        .find(&format!("<!-- {marker}:end -->"))
        .expect("end marker");
    let block = &doc[start..end];
    let code_start = block.find("```python\n").expect("python fence") + "```python\n".len();
    let code_end = block[code_start..].find("```").expect("closing fence") + code_start;
    block[code_start..code_end].to_string()
}

/// Starts the example `script` listening to the graph at `endpoint`.
fn spawn_example(py: &Path, script: &Path, endpoint: &str, ns: &str) -> std::process::Child {
    Command::new(py)
        .arg(script)
        .args([endpoint, ns])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap()
}

/// The example's JSON lines and its stdout, once it exits (killed at
/// `deadline`); panics with its output if it failed.
fn example_lines(
    mut child: std::process::Child,
    deadline: Instant,
) -> (Vec<serde_json::Value>, String) {
    while child.try_wait().unwrap().is_none() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(100));
    }
    let _ = child.kill();
    let out = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "python failed (or did not finish in time): {stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines = stdout
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    (lines, stdout)
}

#[test]
fn python_decodes_what_the_nodes_send() {
    let py = python();
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("listen.py");
    std::fs::write(&script, documented_example("python-example")).unwrap();

    let endpoint = format!("tcp/127.0.0.1:{}", free_port());
    let session = hub(&endpoint);
    let ns = "e2e-python";
    let clouds = session
        .declare_subscriber(format!("shroud/{ns}/cloud/py"))
        .wait()
        .unwrap();
    let w = wiring(&endpoint, ns);
    let _fit = Proc::start(&[&["node", "fit", "--input", "py", "--grid", "10x8"][..], &w].concat());
    let _scanner = Proc::start(
        &[
            &[
                "node", "scanner", "--points", "2000", "--rate", "5", "--stream", "py",
            ][..],
            &w,
        ]
        .concat(),
    );

    let child = spawn_example(&py, &script, &endpoint, ns);
    // Collect our own decoding of the same clouds while Python listens.
    let mut sums: HashMap<u64, (usize, f64)> = HashMap::new();
    let deadline = Instant::now() + Duration::from_secs(60);
    let pid = child.id() as i32;
    while common::alive(pid) && Instant::now() < deadline {
        if let Ok(Some(sample)) = clouds.recv_timeout(Duration::from_millis(100)) {
            let msg = CloudMessage::from_bytes(&sample.payload().to_bytes()).unwrap();
            let pts = msg.point_array().unwrap();
            let sum = pts.iter().flatten().map(|&x| x as f64).sum();
            sums.insert(msg.sequence, (pts.len(), sum));
        }
    }
    let (lines, stdout) = example_lines(child, deadline);
    assert_eq!(
        lines.len(),
        3,
        "one cloud line and two surface lines: {stdout}"
    );
    let seq = lines[0]["cloud"].as_u64().unwrap();
    let (n, sum) = sums[&seq];
    assert_eq!(lines[0]["points"].as_u64().unwrap() as usize, n);
    let py_sum = lines[0]["sum"].as_f64().unwrap();
    assert!(
        (py_sum - sum).abs() <= 1e-9 * sum.abs().max(1.0),
        "python {py_sum} vs rust {sum}"
    );
    let sides: Vec<&str> = lines[1..]
        .iter()
        .map(|l| l["side"].as_str().unwrap())
        .collect();
    assert_eq!(sides, ["upper", "lower"]);
    for l in &lines[1..] {
        assert_eq!(l["grid"], serde_json::json!([8, 10]), "rows x cols");
        assert_eq!(l["checked"], 2000);
        assert_eq!(l["violations"], 0);
        // The fit node's own clock measured the cloud's time in the pipeline.
        let pipeline_ms = l["pipeline_ms"].as_f64().unwrap();
        assert!(pipeline_ms > 0.0 && pipeline_ms < 10_000.0, "{pipeline_ms}");
    }
}

#[test]
fn python_reads_radar_channels() {
    let py = python();
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("channels.py");
    std::fs::write(&script, documented_example("python-channels-example")).unwrap();
    let link = dir.path().join("slcan");
    let link = link.to_str().unwrap();
    let endpoint = format!("tcp/127.0.0.1:{}", free_port());
    let _session = hub(&endpoint);
    let ns = "e2e-python-radar";
    let w = wiring(&endpoint, ns);
    let emulator = Proc::start(&[
        "sensor-sim",
        "--device",
        "ars408",
        "--link",
        link,
        "--mount",
        "-4,0,0.5,0,0,0",
    ]);
    emulator.expect_line("sensor-sim: ars408 on", Duration::from_secs(60));
    let source = format!("slcan:{link}:500000");
    let _radar = Proc::start(
        &[
            &[
                "node", "can", "--device", "ars408", "--source", &source, "--stream", "radar",
            ][..],
            &w,
        ]
        .concat(),
    );
    let child = spawn_example(&py, &script, &endpoint, ns);
    let (lines, _) = example_lines(child, Instant::now() + Duration::from_secs(60));
    let names: Vec<&str> = lines
        .iter()
        .map(|l| l["channel"].as_str().unwrap())
        .collect();
    for name in ["dyn_prop", "rcs", "velocity_lat", "velocity_long"] {
        assert!(names.contains(&name), "{name} in {names:?}");
    }
    for l in &lines {
        assert!(l["points"].as_u64().unwrap() > 0, "{l}");
        if l["channel"] == "rcs" {
            // The DBC's range: -64 to 63.5 dBm².
            assert!(l["min"].as_f64().unwrap() >= -64.0, "{l}");
            assert!(l["max"].as_f64().unwrap() <= 63.5, "{l}");
        }
    }
}
