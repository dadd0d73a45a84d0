//! Reading a launch file: its TOML parsed into the schema of `file`, then
//! checked, from its fields and nodes to the graph they form (`wiring`). Above
//! both, so that the schema need not know the graph built on it.

use super::error::LaunchError;
use super::file::{LaunchFile, NodeSpec, LAUNCHER_NAME};
use super::wiring::check_graph;
use shroud_msg::check_name;

impl LaunchFile {
    pub fn from_toml_str(text: &str) -> Result<Self, LaunchError> {
        let mut file: Self =
            toml::from_str(text).map_err(|e| LaunchError::Syntax(e.to_string()))?;
        for node in &mut file.nodes {
            node.line = line_of(text, node.line);
        }
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
        let mut seen = std::collections::BTreeMap::new();
        for node in &self.nodes {
            if let Some(first) = seen.insert(node.name.as_str(), node.line) {
                return Err(LaunchError::DuplicateNode {
                    name: node.name.clone(),
                    first,
                    again: node.line,
                });
            }
            check_node(node)?;
        }
        self.check_hosts()?;
        check_graph(self)
    }
}

fn check_node(node: &NodeSpec) -> Result<(), LaunchError> {
    let fail = |reason: String| node.error(reason);
    check_name("name", &node.name).map_err(|e| fail(e.to_string()))?;
    if node.name == LAUNCHER_NAME {
        return Err(fail(format!(
            "the name {LAUNCHER_NAME:?} is the launcher's own (its status message)"
        )));
    }
    if node.backoff_ms == 0 || node.backoff_max_ms < node.backoff_ms {
        return Err(fail(format!(
            "backoff_ms ({}) must be positive and at most backoff_max_ms ({})",
            node.backoff_ms, node.backoff_max_ms
        )));
    }
    for key in node.settings.keys() {
        if let Some(reason) = node.reserved_setting(key) {
            return Err(fail(format!("settings.{key}: {reason}")));
        }
    }
    Ok(())
}

/// The 1-based line of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    let offset = offset.min(text.len());
    1 + text.as_bytes()[..offset]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}
