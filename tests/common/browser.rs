//! Runs the dashboard page's checks (`tests/browser/dashboard_check.mjs`, real
//! headless Chromium through playwright-core) and reads their JSON results.
//! Without Chromium or playwright-core a check says SKIP with the install
//! commands, unless `CI=true`, where a missing tool is a failure.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

const INSTALL: &str = "apt-get install -y chromium && npm ci --prefix tests/browser (see .ci/run)";

/// Exit status of dashboard_check.mjs when Chromium or playwright-core is missing.
const MISSING_TOOL: i32 = 3;

/// Where a test's screenshots go: `target/tmp/dashboard/<test>`.
pub fn out_dir(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("dashboard")
        .join(test);
    std::fs::create_dir_all(&dir).expect("screenshot folder");
    dir
}

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/browser/dashboard_check.mjs")
}

/// True when the browser tools are there; otherwise prints SKIP (or panics
/// under CI=true, where .ci/run installs them).
pub fn browser_available() -> bool {
    let chromium = std::env::var("SHROUD_CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    let missing = (!Path::new(&chromium).exists()).then_some("chromium");
    tools_available("browser", &["playwright-core"], missing)
}

/// True when node and the npm packages `modules` of tests/browser are there;
/// otherwise prints SKIP for `what` (or panics under CI=true).
pub fn node_modules_available(what: &str, modules: &[&str]) -> bool {
    tools_available(what, modules, None)
}

fn tools_available(what: &str, modules: &[&str], also_missing: Option<&str>) -> bool {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/browser/node_modules");
    let node = Command::new("node")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    let mut missing: Vec<String> = [(!node).then_some("node"), also_missing]
        .into_iter()
        .flatten()
        .map(str::to_owned)
        .collect();
    missing.extend(
        modules
            .iter()
            .filter(|m| !root.join(m).exists())
            .map(|m| format!("{m} (tests/browser/node_modules)")),
    );
    if missing.is_empty() {
        return true;
    }
    let message = format!("missing {}: {INSTALL}", missing.join(", "));
    assert!(
        std::env::var("CI").as_deref() != Ok("true"),
        "CI=true and {message}"
    );
    eprintln!("SKIP: {what} test needs {message}");
    false
}

/// Runs check `name` against `url` with extra options; returns its JSON
/// result, panicking with the check's output if it failed.
pub fn check(url: &str, out: &Path, name: &str, extra: &[&str]) -> serde_json::Value {
    let output = Command::new("node")
        .arg(script())
        .args(["--url", url, "--check", name, "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("node runs");
    result(name, output.status.code(), &output.stdout, &output.stderr)
}

fn result(name: &str, code: Option<i32>, stdout: &[u8], stderr: &[u8]) -> serde_json::Value {
    let stdout = String::from_utf8_lossy(stdout);
    let stderr = String::from_utf8_lossy(stderr);
    assert_ne!(
        code,
        Some(MISSING_TOOL),
        "check {name}: a browser tool is missing ({INSTALL}): {stderr}"
    );
    let last = stdout.lines().last().unwrap_or("");
    let value: serde_json::Value = serde_json::from_str(last).unwrap_or_else(|e| {
        panic!("check {name} printed no JSON result ({e}): {stdout}\n{stderr}")
    });
    assert!(
        code == Some(0) && value["ok"] == true,
        "check {name} failed (exit {code:?}): {value}\n{stderr}"
    );
    value
}

/// The `node_dies` check with its kill handshake: once the page shows node
/// `node` alive, `kill` runs and its time (ms since the Unix epoch) goes to
/// the check, which reports how long the row took to turn red.
pub fn node_dies(url: &str, out: &Path, node: &str, kill: impl FnOnce()) -> serde_json::Value {
    let mut child = Command::new("node")
        .arg(script())
        .args([
            "--url",
            url,
            "--check",
            "node_dies",
            "--node",
            node,
            "--out",
        ])
        .arg(out)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("node runs");
    let mut stderr = BufReader::new(child.stderr.take().expect("stderr"));
    let mut seen = String::new();
    let mut line = String::new();
    while stderr.read_line(&mut line).is_ok_and(|n| n > 0) {
        seen.push_str(&line);
        if line.trim() == format!("ready {node}") {
            break;
        }
        line.clear();
    }
    if seen.lines().last().map(str::trim) == Some(&format!("ready {node}")) {
        kill();
        let now_ms = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_millis())
            .unwrap_or(0);
        let mut stdin = child.stdin.take().expect("stdin");
        writeln!(stdin, "{now_ms}").expect("the check reads the kill time");
    }
    let mut rest = String::new();
    let _ = std::io::Read::read_to_string(&mut stderr, &mut rest);
    seen.push_str(&rest);
    let output = child.wait_with_output().expect("the check ends");
    result(
        "node_dies",
        output.status.code(),
        &output.stdout,
        seen.as_bytes(),
    )
}
