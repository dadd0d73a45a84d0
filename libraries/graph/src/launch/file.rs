//! The launch-file schema (TOML). Documented for users in `launch/README.md`.

use super::error::LaunchError;
use super::hosts::HostSpec;
#[cfg(test)]
use super::kind::Direction;
use super::kind::NodeKind;
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

/// One node of the graph: `shroud node <kind> --name <name>`, its options
/// built from `settings`, `inputs` and `outputs`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeSpec {
    pub name: String,
    /// The node program.
    pub kind: NodeKind,
    /// The node's options by name (`grid = "20x20"` is `--grid 20x20`; `true`
    /// is a switch; an array repeats the option). The launcher checks them
    /// against the node's own parser before it starts anything.
    #[serde(default)]
    pub settings: BTreeMap<String, toml::Value>,
    /// Streams the node reads, by topic kind: `{ cloud = "spheres" }`.
    #[serde(default)]
    pub inputs: BTreeMap<String, StreamNames>,
    /// Streams the node writes, by topic kind.
    #[serde(default)]
    pub outputs: BTreeMap<String, StreamNames>,
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
    /// The host (a key of `[hosts]`) the node runs on: `shroud launch FILE
    /// --host NAME` starts only that host's nodes.
    #[serde(default)]
    pub host: Option<String>,
    /// The line of the file where the node's table starts (1-based; 0 when the
    /// spec was not read from a file).
    #[serde(skip)]
    pub line: usize,
}

/// One stream name or several: `"top"` or `["top", "front"]`.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(from = "OneOrMany")]
pub struct StreamNames(pub Vec<String>);

#[derive(Deserialize)]
#[serde(untagged)]
enum OneOrMany {
    One(String),
    Many(Vec<String>),
}

impl From<OneOrMany> for StreamNames {
    fn from(value: OneOrMany) -> Self {
        match value {
            OneOrMany::One(name) => Self(vec![name]),
            OneOrMany::Many(names) => Self(names),
        }
    }
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
    /// Streams that come from outside the file (another launcher, a test, a
    /// robot's own publisher), as `kind/name`: inputs they feed need no
    /// producer among the nodes.
    #[serde(default)]
    pub external: Vec<String>,
    /// The computers the graph runs on, by name (none: one machine).
    #[serde(default)]
    pub hosts: BTreeMap<String, HostSpec>,
    #[serde(rename = "node", default, deserialize_with = "nodes_with_offsets")]
    pub nodes: Vec<NodeSpec>,
}

/// Reads the node tables, keeping where each starts (as a byte offset in
/// `line` until [`LaunchFile::from_toml_str`] turns it into a line number).
fn nodes_with_offsets<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<NodeSpec>, D::Error> {
    let spanned: Vec<toml::Spanned<NodeSpec>> = Vec::deserialize(d)?;
    Ok(spanned
        .into_iter()
        .map(|s| {
            let offset = s.span().start;
            let mut node = s.into_inner();
            node.line = offset;
            node
        })
        .collect())
}

fn default_namespace() -> String {
    "demo".into()
}
fn default_grace_s() -> f64 {
    3.0
}

/// The launcher's own name in the namespace (its status message); no node
/// may take it.
pub const LAUNCHER_NAME: &str = "launcher";

/// The options the launcher passes every child itself; `settings` may not
/// name them (nodes/ checks that this is exactly what it passes).
pub const LAUNCHER_FLAGS: [&str; 7] = [
    "--log",
    "--name",
    "--namespace",
    "--mode",
    "--connect",
    "--multicast",
    "--shm",
];

impl NodeSpec {
    /// Why `key` may not be a setting of this node: the launcher or one of
    /// the node's ports sets that option.
    pub fn reserved_setting(&self, key: &str) -> Option<String> {
        let flag = format!("--{}", key.replace('_', "-"));
        if LAUNCHER_FLAGS.contains(&flag.as_str()) {
            return Some(format!("{flag} is set by the launcher, not in settings"));
        }
        let port = self
            .kind
            .ports()
            .iter()
            .find(|p| flag == format!("--{}", p.flag))?;
        Some(format!(
            "{flag} is wired by {}.{}, not in settings",
            port.direction.section(),
            port.topic
        ))
    }

    /// An error about this node, naming it and its line.
    pub fn error(&self, reason: String) -> LaunchError {
        LaunchError::Node {
            node: self.name.clone(),
            line: self.line,
            reason,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::launch::{wiring_mermaid, wiring_text};

    const DEMO: &str = r#"
namespace = "lab"
shutdown_grace_s = 2
[zenoh]
connect = ["tcp/10.0.0.1:7447"]

[[node]]
name = "scanner"
kind = "scanner"
settings = { points = 30000 }
outputs = { cloud = "table" }
restart = "always"

[[node]]
name = "fit"
kind = "fit"
inputs = { cloud = "table" }
outputs = { surrogate = "top" }
settings = { grid = "20x20", dir = "0,0,-1" }
env = { RUST_LOG = "debug" }
"#;

    /// A node table of `kind` named `x` with extra lines.
    fn one(kind: &str, extra: &str) -> String {
        format!("[[node]]\nname=\"x\"\nkind=\"{kind}\"\n{extra}\n")
    }

    const FIT_PORTS: &str = "inputs={cloud=\"c\"}\noutputs={surrogate=\"s\"}\n";
    const FED: &str = "external=[\"cloud/c\"]\n";

    #[test]
    fn parses_with_defaults_and_lines() {
        let f = LaunchFile::from_toml_str(DEMO).unwrap();
        assert_eq!(f.namespace, "lab");
        assert_eq!(f.nodes.len(), 2);
        assert_eq!(f.nodes[0].kind, NodeKind::Scanner);
        assert_eq!(f.nodes[0].line, 7);
        assert_eq!(f.nodes[1].line, 14);
        assert_eq!(f.nodes[0].restart, RestartPolicy::Always);
        assert_eq!(f.nodes[1].restart, RestartPolicy::OnFailure);
        assert_eq!(f.nodes[1].env["RUST_LOG"], "debug");
        assert_eq!(f.zenoh.listen, vec!["tcp/127.0.0.1:0".to_string()]);
        assert!(f.zenoh.shm && !f.zenoh.multicast);
        assert_eq!(
            f.nodes[1].port_args().unwrap(),
            vec!["--input=table", "--output=top"]
        );
    }

    #[test]
    fn the_wiring_is_drawn() {
        let f = LaunchFile::from_toml_str(DEMO).unwrap();
        let text = wiring_text(&f).unwrap();
        assert!(
            text.contains("fit [fit]\n  reads  cloud/table from scanner\n  writes surrogate/top")
        );
        let chart = wiring_mermaid(&f).unwrap();
        assert!(chart.starts_with("flowchart LR\n"), "{chart}");
        assert!(chart.contains("n0 -- \"cloud/table\" --> n1"), "{chart}");
    }

    #[test]
    fn every_mistake_is_named_with_its_line() {
        let fit = |extra: &str| format!("{FED}{}", one("fit", &format!("{FIT_PORTS}{extra}")));
        let cases = [
            (
                format!("namespace = \"a/b\"\n{}", fit("")),
                "namespace".to_string(),
            ),
            (String::new(), "no node".into()),
            (format!("{}{}", fit(""), one("fit", "")), "two nodes".into()),
            (
                fit("settings={name=\"y\"}"),
                "line 2: node \"x\": settings.name: --name is set by the launcher".into(),
            ),
            (
                fit("settings={input=\"y\"}"),
                "--input is wired by inputs.cloud".into(),
            ),
            (fit("backoff_ms=0"), "backoff_ms".into()),
            (one("fitter", ""), "unknown variant `fitter`".into()),
            (
                fit("").replace("name=\"x\"", "name=\"launcher\""),
                "launcher's own".into(),
            ),
            (fit("restart=\"sometimes\""), "TOML".into()),
            (fit("colour=1"), "TOML".into()),
            (
                fit("args=[\"--grid\", \"8x8\"]"),
                "unknown field `args`".into(),
            ),
            (
                format!("{FED}[zenoh]\nmode=\"router\"\n{}", one("fit", FIT_PORTS)),
                "zenoh.mode".into(),
            ),
            (
                one("fit", "outputs={surrogate=\"s\"}"),
                "inputs.cloud is required".into(),
            ),
            (
                format!("{FED}{}", one("fit", "inputs={cloud=\"c\"}")),
                "outputs.surrogate is required".into(),
            ),
            (
                format!(
                    "{FED}{}",
                    one(
                        "fit",
                        "inputs={cloud=\"c\",joints=\"a\"}\noutputs={surrogate=\"s\"}"
                    )
                ),
                "inputs.joints: a fit node reads no joints stream (its inputs: cloud)".into(),
            ),
            (
                one("fit", "inputs={cloud=\"c\"}\noutputs={surrogate=\"s\"}"),
                "input cloud/c has no producer".into(),
            ),
            (
                format!(
                    "{FED}{}",
                    one(
                        "fit",
                        "inputs={cloud=[\"c\",\"d\"]}\noutputs={surrogate=\"s\"}"
                    )
                ),
                "names 2 streams".into(),
            ),
            (
                format!(
                    "{FED}{}",
                    one("fit", "inputs={cloud=\"c/d\"}\noutputs={surrogate=\"s\"}")
                ),
                "inputs.cloud".into(),
            ),
            (
                format!("external=[\"clouds/c\"]\n{}", one("fit", FIT_PORTS)),
                "not a topic kind".into(),
            ),
            (
                format!(
                    "external=[\"surrogate/s\"]\n{}",
                    one(
                        "guard",
                        "inputs={surrogate=\"s\",joints=\"a\"}\noutputs={collision=\"b\"}"
                    )
                ),
                "inputs.joints (a) and outputs.collision (b) are both --arm".into(),
            ),
            (
                format!(
                    "{FED}{}{}",
                    one("fit", FIT_PORTS),
                    one("fit", FIT_PORTS).replace("\"x\"", "\"y\"")
                ),
                "surrogate/s is also written by node \"x\"".into(),
            ),
            (
                format!(
                    "external=[\"cloud/c\",\"surrogate/s\"]\n{}",
                    one("fit", FIT_PORTS)
                ),
                "surrogate/s is written here and listed in external".into(),
            ),
        ];
        for (text, needle) in cases {
            let err = LaunchFile::from_toml_str(&text).unwrap_err().to_string();
            assert!(err.contains(&needle), "{text:?}: {err}");
        }
    }

    #[test]
    fn every_launcher_flag_is_refused_in_settings_and_every_kind_parses() {
        for flag in LAUNCHER_FLAGS {
            let key = flag.trim_start_matches("--");
            let text = format!(
                "{FED}{}",
                one("fit", &format!("{FIT_PORTS}settings={{{key}=\"x\"}}"))
            );
            let err = LaunchFile::from_toml_str(&text).unwrap_err().to_string();
            assert!(err.contains(flag), "{key}: {err}");
        }
        // --listen is the node's own business (a fixed endpoint across hosts).
        let listen = format!(
            "{FED}{}",
            one(
                "fit",
                &format!("{FIT_PORTS}settings={{listen=\"tcp/0.0.0.0:7448\"}}")
            )
        );
        assert!(LaunchFile::from_toml_str(&listen).is_ok());
        // Each kind with its required ports named, fed from outside.
        for kind in NodeKind::ALL {
            let mut inputs = Vec::new();
            let mut outputs = Vec::new();
            let mut external = Vec::new();
            for port in kind.ports().iter().filter(|p| p.required) {
                // Ports sharing an option name the same stream.
                let entry = format!("{}=\"{}\"", port.topic, port.flag);
                match port.direction {
                    Direction::Input => {
                        external.push(format!("\"{}/{}\"", port.topic, port.flag));
                        inputs.push(entry)
                    }
                    Direction::Output => outputs.push(entry),
                }
            }
            if kind == NodeKind::Replay {
                outputs.push("cloud=\"r\"".into());
            }
            let text = format!(
                "external=[{}]\n{}",
                external.join(","),
                one(
                    kind.as_str(),
                    &format!(
                        "inputs={{{}}}\noutputs={{{}}}",
                        inputs.join(","),
                        outputs.join(",")
                    )
                )
            );
            if let Err(e) = LaunchFile::from_toml_str(&text) {
                panic!("{kind}: {e}\n{text}");
            }
        }
    }

    #[test]
    fn self_feeding_repeated_names_and_duplicate_nodes_are_refused() {
        let blend = |extra: &str| {
            one(
                "blend",
                &format!("inputs={{blend=\"b\",cloud=\"p\"}}\noutputs={{cloud=\"p\"}}{extra}"),
            )
        };
        let err = LaunchFile::from_toml_str(&format!("external=[\"blend/b\"]\n{}", blend("")))
            .unwrap_err()
            .to_string();
        assert!(err.contains("reads cloud/p and writes it too"), "{err}");
        let guard = "inputs={surrogate=[\"s\",\"s\"],joints=\"a\"}\noutputs={collision=\"a\"}";
        let text = format!(
            "external=[\"surrogate/s\",\"joints/a\"]\n{}",
            one("guard", guard)
        );
        let err = LaunchFile::from_toml_str(&text).unwrap_err().to_string();
        assert!(err.contains("inputs.surrogate names \"s\" twice"), "{err}");
        let twice = format!("{FED}{}\n{}", one("fit", FIT_PORTS), one("fit", FIT_PORTS));
        let err = LaunchFile::from_toml_str(&twice).unwrap_err().to_string();
        assert!(
            err.contains("lines 2 and 9: two nodes are named \"x\""),
            "{err}"
        );
    }

    /// Blend commands may come from several senders: viewers, a command
    /// line tool outside the file.
    #[test]
    fn blend_commands_may_have_several_producers() {
        let viewer = |name: &str| {
            one("dashboard", "outputs={blend=\"b\"}")
                .replace("name=\"x\"", &format!("name=\"{name}\""))
        };
        let blend = one("blend", "inputs={blend=\"b\"}\noutputs={cloud=\"o\"}");
        let text = format!(
            "external=[\"blend/b\"]\n{}{}{blend}",
            viewer("d1"),
            viewer("d2")
        );
        let file = LaunchFile::from_toml_str(&text).unwrap();
        // Each sender is drawn: both viewers and the outside.
        let chart = wiring_mermaid(&file).unwrap();
        assert!(chart.contains("n0 -- \"blend/b\" --> n2"), "{chart}");
        assert!(chart.contains("n1 -- \"blend/b\" --> n2"), "{chart}");
        assert!(chart.contains("x0 --> n2"), "{chart}");
    }

    #[test]
    fn a_replay_names_its_topics_in_one_filter() {
        let text = one(
            "replay",
            "settings={file=\"r.mcap\"}\noutputs={cloud=[\"a\",\"b\"],joints=\"arm\"}",
        );
        let f = LaunchFile::from_toml_str(&text).unwrap();
        assert_eq!(
            f.nodes[0].port_args().unwrap(),
            vec!["--topics=cloud/a,cloud/b,joints/arm"]
        );
    }

    #[test]
    fn a_guard_and_an_arm_close_the_loop() {
        let text = format!(
            "{FED}{}{}{}",
            one("fit", FIT_PORTS).replace("\"x\"", "\"f\""),
            one(
                "guard",
                "inputs={surrogate=\"s\",joints=\"a\"}\noutputs={collision=\"a\"}"
            )
            .replace("\"x\"", "\"g\""),
            one("arm", "inputs={collision=\"a\"}\noutputs={joints=\"a\"}")
        );
        let f = LaunchFile::from_toml_str(&text).unwrap();
        assert_eq!(
            f.nodes[1].port_args().unwrap(),
            vec!["--surrogate=s", "--arm=a"]
        );
        let edges = f.edges().unwrap();
        let into_guard: Vec<String> = edges
            .iter()
            .filter(|e| e.to.name == "g")
            .map(|e| e.stream.to_string())
            .collect();
        assert_eq!(into_guard, vec!["surrogate/s", "joints/a"]);
    }
}
