//! Graphs started by `shroud launch` from a launch file the test writes: the
//! file in a temp dir, the launcher's endpoint and the pids of the nodes it
//! started, read from its output.

use super::Proc;
use std::time::Duration;

const LONG: Duration = Duration::from_secs(60);

/// Writes `body` as `graph.toml` in `dir`; its path.
pub fn write_launch(dir: &std::path::Path, body: &str) -> String {
    let path = dir.join("graph.toml");
    std::fs::write(&path, body).unwrap();
    path.to_str().unwrap().to_string()
}

/// The endpoint the launcher announces (nodes and tests connect to it).
pub fn endpoint_of(launcher: &Proc) -> String {
    let line = launcher.expect_line("nodes connect to", LONG);
    line.rsplit("nodes connect to ")
        .next()
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .trim()
        .to_string()
}

/// The pids of the nodes `names`, from the launcher's `started` lines.
pub fn pids_of(launcher: &Proc, names: &[&str]) -> Vec<i32> {
    let mut found = std::collections::HashMap::new();
    while found.len() < names.len() {
        let line = launcher.expect_line("[launch] started ", LONG);
        let rest = line.rsplit("started ").next().unwrap();
        let (name, pid) = rest.split_once(" (pid ").unwrap();
        found.insert(
            name.to_string(),
            pid.trim_end_matches(')').parse::<i32>().unwrap(),
        );
    }
    names.iter().map(|n| found[*n]).collect()
}

/// A launched graph: the launcher, the endpoint it announced, and the temp
/// dir holding its launch file (and whatever else the test put there).
pub struct Launched {
    pub launcher: Proc,
    pub endpoint: String,
    pub dir: tempfile::TempDir,
}

impl Launched {
    /// Writes `body` (with `{dir}` replaced by the temp dir's path) and
    /// launches it; `prepare` first writes further files into the dir.
    pub fn start(body: &str, prepare: impl FnOnce(&std::path::Path)) -> Launched {
        let dir = tempfile::tempdir().unwrap();
        prepare(dir.path());
        let body = body.replace("{dir}", dir.path().to_str().unwrap());
        let file = write_launch(dir.path(), &body);
        let launcher = Proc::start(&["launch", &file]);
        let endpoint = endpoint_of(&launcher);
        Launched {
            launcher,
            endpoint,
            dir,
        }
    }
}
