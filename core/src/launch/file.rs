//! The launch-file schema (TOML). Documented for users in `launch/README.md`.

use super::error::LaunchError;
use crate::message::check_name;
use serde::Deserialize;
use std::collections::BTreeMap;

/// When a node that exited is started again.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum RestartPolicy {
    Never,
    #[default]
    OnFailure,
    Always,
}

/// Where the graph's zenoh sessions meet.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ZenohSpec {
    /// `peer` (default) or `client` (through a zenohd router).
    pub mode: String,
    /// Endpoints the launcher listens on; every node connects to them.
    /// `tcp/127.0.0.1:0` picks a free port.
    pub listen: Vec<String>,
    /// Extra endpoints every node and the launcher connect to (a zenohd router).
    pub connect: Vec<String>,
    /// Multicast scouting (off by default: the launcher's endpoint is enough).
    pub multicast: bool,
    /// Zenoh shared memory for large payloads when peers share a machine.
    pub shm: bool,
}

impl Default for ZenohSpec {
    fn default() -> Self {
        Self {
            mode: "peer".into(),
            listen: vec!["tcp/127.0.0.1:0".into()],
            connect: Vec::new(),
            multicast: false,
            shm: true,
        }
    }
}

/// What the launcher's live one-line summary watches.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SummarySpec {
    pub enabled: bool,
    /// Seconds between summary lines.
    pub period_s: f64,
}

impl Default for SummarySpec {
    fn default() -> Self {
        Self {
            enabled: true,
            period_s: 1.0,
        }
    }
}

/// One node of the graph: `shroud node <run> --name <name> <args...>`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSpec {
    pub name: String,
    /// The node program (`scanner`, `fit`, `guard`, `arm`, ...).
    pub run: String,
    #[serde(default)]
    pub args: Vec<String>,
    #[serde(default)]
    pub env: BTreeMap<String, String>,
    #[serde(default)]
    pub restart: RestartPolicy,
    /// Consecutive quick failures tolerated before giving up.
    #[serde(default = "default_max_restarts")]
    pub max_restarts: u32,
    /// First restart delay; doubled after each quick failure.
    #[serde(default = "default_backoff_ms")]
    pub backoff_ms: u64,
    #[serde(default = "default_backoff_max_ms")]
    pub backoff_max_ms: u64,
    /// A run this long counts as healthy and resets the failure count.
    #[serde(default = "default_stable_after_ms")]
    pub stable_after_ms: u64,
    /// The whole graph stops when this node stops for good (e.g. a test driver).
    #[serde(default)]
    pub critical: bool,
}

fn default_max_restarts() -> u32 {
    5
}
fn default_backoff_ms() -> u64 {
    250
}
fn default_backoff_max_ms() -> u64 {
    8000
}
fn default_stable_after_ms() -> u64 {
    10_000
}

/// A whole launch file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaunchFile {
    /// Namespace of every key: `shroud/<namespace>/...`.
    #[serde(default = "default_namespace")]
    pub namespace: String,
    #[serde(default)]
    pub zenoh: ZenohSpec,
    #[serde(default)]
    pub summary: SummarySpec,
    /// Seconds a node gets to exit after SIGTERM before it is killed.
    #[serde(default = "default_grace_s")]
    pub shutdown_grace_s: f64,
    #[serde(rename = "node", default)]
    pub nodes: Vec<NodeSpec>,
}

fn default_namespace() -> String {
    "demo".into()
}
fn default_grace_s() -> f64 {
    3.0
}

impl LaunchFile {
    pub fn from_toml_str(text: &str) -> Result<Self, LaunchError> {
        let file: Self = toml::from_str(text).map_err(|e| LaunchError::Syntax(e.to_string()))?;
        file.validate()?;
        Ok(file)
    }

    pub fn validate(&self) -> Result<(), LaunchError> {
        let invalid = |field: &str, reason: String| LaunchError::Invalid {
            field: field.into(),
            reason,
        };
        check_name("namespace", &self.namespace)
            .map_err(|e| invalid("namespace", e.to_string()))?;
        if !matches!(self.zenoh.mode.as_str(), "peer" | "client") {
            return Err(invalid(
                "zenoh.mode",
                format!("{:?} is not peer or client", self.zenoh.mode),
            ));
        }
        if self.zenoh.mode == "peer" && self.zenoh.listen.is_empty() {
            return Err(invalid(
                "zenoh.listen",
                "a peer-mode launcher needs an endpoint to listen on".into(),
            ));
        }
        if !(self.shutdown_grace_s.is_finite()
            && self.shutdown_grace_s >= 0.0
            && self.shutdown_grace_s <= 600.0)
        {
            return Err(invalid(
                "shutdown_grace_s",
                format!("{} is not in [0, 600]", self.shutdown_grace_s),
            ));
        }
        if !(self.summary.period_s.is_finite() && self.summary.period_s >= 0.05) {
            return Err(invalid(
                "summary.period_s",
                format!("{} is below 0.05 s", self.summary.period_s),
            ));
        }
        if self.nodes.is_empty() {
            return Err(LaunchError::NoNodes);
        }
        let mut seen = std::collections::BTreeSet::new();
        for node in &self.nodes {
            if !seen.insert(node.name.as_str()) {
                return Err(LaunchError::DuplicateNode(node.name.clone()));
            }
            check_node(node)?;
        }
        Ok(())
    }
}

/// The launcher's own name in the namespace (its status message); no node
/// may take it.
pub const LAUNCHER_NAME: &str = "launcher";

/// The node programs `run` may name: `shroud node <kind>` (nodes/ checks that
/// this list is exactly its subcommands).
pub const NODE_KINDS: [&str; 13] = [
    "scanner",
    "fit",
    "guard",
    "arm",
    "serial",
    "can",
    "blend",
    "smooth",
    "device-sim",
    "dashboard",
    "foxglove",
    "record",
    "replay",
];

/// The options the launcher passes every child itself; `args` may not repeat
/// them (nodes/ checks that this is exactly what it passes).
pub const LAUNCHER_FLAGS: [&str; 7] = [
    "--log",
    "--name",
    "--namespace",
    "--mode",
    "--connect",
    "--multicast",
    "--shm",
];

fn check_node(node: &NodeSpec) -> Result<(), LaunchError> {
    let fail = |reason: String| LaunchError::Node {
        node: node.name.clone(),
        reason,
    };
    check_name("name", &node.name).map_err(|e| fail(e.to_string()))?;
    if node.name == LAUNCHER_NAME {
        return Err(fail(format!(
            "the name {LAUNCHER_NAME:?} is the launcher's own (its status message)"
        )));
    }
    check_name("run", &node.run).map_err(|e| fail(e.to_string()))?;
    if !NODE_KINDS.contains(&node.run.as_str()) {
        return Err(fail(format!(
            "run = {:?} is not a node kind ({})",
            node.run,
            NODE_KINDS.join(", ")
        )));
    }
    if node.backoff_ms == 0 || node.backoff_max_ms < node.backoff_ms {
        return Err(fail(format!(
            "backoff_ms ({}) must be positive and at most backoff_max_ms ({})",
            node.backoff_ms, node.backoff_max_ms
        )));
    }
    for reserved in LAUNCHER_FLAGS {
        if node
            .args
            .iter()
            .any(|a| a == reserved || a.starts_with(&format!("{reserved}=")))
        {
            return Err(fail(format!(
                "{reserved} is set by the launcher, not in args"
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEMO: &str = r#"
namespace = "lab"
shutdown_grace_s = 2
[zenoh]
connect = ["tcp/10.0.0.1:7447"]
[[node]]
name = "scanner"
run = "scanner"
args = ["--points", "30000"]
restart = "always"
[[node]]
name = "fit"
run = "fit"
env = { RUST_LOG = "debug" }
"#;

    #[test]
    fn parses_with_defaults() {
        let f = LaunchFile::from_toml_str(DEMO).unwrap();
        assert_eq!(f.namespace, "lab");
        assert_eq!(f.nodes.len(), 2);
        assert_eq!(f.nodes[0].restart, RestartPolicy::Always);
        assert_eq!(f.nodes[1].restart, RestartPolicy::OnFailure);
        assert_eq!(f.nodes[1].env["RUST_LOG"], "debug");
        assert_eq!(f.zenoh.listen, vec!["tcp/127.0.0.1:0".to_string()]);
        assert!(f.zenoh.shm && !f.zenoh.multicast);
    }

    #[test]
    fn every_mistake_is_named() {
        let cases = [
            (
                "namespace = \"a/b\"\n[[node]]\nname=\"x\"\nrun=\"fit\"",
                "namespace",
            ),
            ("", "no node"),
            (
                "[[node]]\nname=\"x\"\nrun=\"fit\"\n[[node]]\nname=\"x\"\nrun=\"fit\"",
                "two nodes",
            ),
            (
                "[[node]]\nname=\"x\"\nrun=\"fit\"\nargs=[\"--name\",\"y\"]",
                "--name",
            ),
            (
                "[[node]]\nname=\"x\"\nrun=\"fit\"\nbackoff_ms=0",
                "backoff_ms",
            ),
            ("[[node]]\nname=\"x\"\nrun=\"fitter\"", "not a node kind"),
            ("[[node]]\nname=\"launcher\"\nrun=\"fit\"", "launcher's own"),
            (
                "[[node]]\nname=\"x\"\nrun=\"fit\"\nrestart=\"sometimes\"",
                "TOML",
            ),
            ("[[node]]\nname=\"x\"\nrun=\"fit\"\ncolour=1", "TOML"),
            (
                "[zenoh]\nmode=\"router\"\n[[node]]\nname=\"x\"\nrun=\"fit\"",
                "zenoh.mode",
            ),
        ];
        for (text, needle) in cases {
            let err = LaunchFile::from_toml_str(text).unwrap_err().to_string();
            assert!(err.contains(needle), "{text:?}: {err}");
        }
    }

    #[test]
    fn every_launcher_flag_is_refused_in_args_and_every_kind_runs() {
        for flag in LAUNCHER_FLAGS {
            for arg in [flag.to_string(), format!("{flag}=x")] {
                let text = format!("[[node]]\nname=\"x\"\nrun=\"fit\"\nargs=[\"{arg}\"]");
                let err = LaunchFile::from_toml_str(&text).unwrap_err().to_string();
                assert!(err.contains(flag), "{arg}: {err}");
            }
        }
        // --listen is the node's own business (a fixed endpoint across hosts).
        let listen = "[[node]]\nname=\"x\"\nrun=\"fit\"\nargs=[\"--listen\",\"tcp/0.0.0.0:7448\"]";
        assert!(LaunchFile::from_toml_str(listen).is_ok());
        for kind in NODE_KINDS {
            let text = format!("[[node]]\nname=\"x\"\nrun=\"{kind}\"");
            assert!(LaunchFile::from_toml_str(&text).is_ok(), "{kind}");
        }
    }
}
