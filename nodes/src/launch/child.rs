//! One child process: spawned as `shroud node <run> ...` in its own process
//! group, tied to the launcher's life (parent-death signal and the node's own
//! watch on our pid), and its output prefixed line by line.

use super::plan::PlannedNode;
use crate::transport::die_with_parent;
use anyhow::{Context, Result};
#[cfg(doc)]
use shroud_graph::launch::LAUNCHER_FLAGS;
use std::process::Stdio;
use tokio::io::{AsyncBufReadExt, AsyncRead, BufReader};
use tokio::process::{Child, Command};

/// Arguments every child gets from the launcher, before its own.
#[derive(Debug, Clone)]
pub struct Wiring {
    pub namespace: String,
    pub mode: String,
    pub connect: Vec<String>,
    pub multicast: bool,
    pub shm: bool,
    pub log: String,
}

/// The child's command line: the launcher's own flags (exactly
/// [`LAUNCHER_FLAGS`], which launch files may not set), then the node's
/// options from its settings and ports. `--log` is left out when the node's
/// `env` sets `RUST_LOG`, so that the node reads that instead.
fn command(node: &PlannedNode, wiring: &Wiring) -> Result<Command> {
    let spec = &node.spec;
    let exe = std::env::current_exe().context("cannot find the shroud executable")?;
    let mut cmd = Command::new(exe);
    if !spec.env.contains_key("RUST_LOG") {
        cmd.arg("--log").arg(&wiring.log);
    }
    cmd.arg("node").arg(spec.kind.as_str());
    cmd.arg("--name").arg(&spec.name);
    cmd.arg("--namespace").arg(&wiring.namespace);
    cmd.arg("--mode").arg(&wiring.mode);
    for endpoint in &wiring.connect {
        cmd.arg("--connect").arg(endpoint);
    }
    cmd.arg("--multicast")
        .arg(if wiring.multicast { "on" } else { "off" });
    cmd.arg("--shm").arg(if wiring.shm { "on" } else { "off" });
    cmd.args(&node.args);
    cmd.envs(&spec.env);
    Ok(cmd)
}

pub fn spawn(node: &PlannedNode, wiring: &Wiring) -> Result<Child> {
    let spec = &node.spec;
    let mut cmd = command(node, wiring)?;
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    // Its own process group: a Ctrl-C in the terminal reaches only the launcher,
    // which then stops the children in order instead of all dying at once.
    cmd.process_group(0);
    cmd.kill_on_drop(true);
    // The parent-death signal, and our pid for the node's own watch on it: a
    // launcher killed outright leaves no live node, reaped or not.
    die_with_parent(cmd.as_std_mut());
    let mut child = cmd
        .spawn()
        .with_context(|| format!("cannot start node {} ({})", spec.name, spec.kind))?;
    if let Some(out) = child.stdout.take() {
        tokio::spawn(prefix_lines(out, spec.name.clone(), false));
    }
    if let Some(err) = child.stderr.take() {
        tokio::spawn(prefix_lines(err, spec.name.clone(), true));
    }
    Ok(child)
}

/// Copies a child's output, prefixed, to the launcher's output queue. It
/// keeps reading even when our own output fails or stalls (the queue drops,
/// never blocks): a child whose pipe has no reader gets EPIPE on every log line.
async fn prefix_lines(stream: impl AsyncRead + Unpin, name: String, is_err: bool) {
    let mut lines = BufReader::new(stream).lines();
    while let Ok(Some(line)) = lines.next_line().await {
        let text = format!("[{name}] {line}");
        if is_err {
            super::output::err(text);
        } else {
            super::output::out(text);
        }
    }
}

/// Asks a child to stop (SIGTERM), then kills it after `grace`.
pub async fn stop(child: &mut Child, name: &str, grace: std::time::Duration) {
    if let Some(pid) = child.id() {
        // SAFETY: plain kill(2) on our own child's pid.
        unsafe {
            libc::kill(pid as libc::pid_t, libc::SIGTERM);
        }
    }
    match tokio::time::timeout(grace, child.wait()).await {
        Ok(_) => {}
        Err(_) => {
            tracing::warn!(node = name, "did not stop within {grace:?}; killing it");
            let _ = child.start_kill();
            let _ = child.wait().await;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_graph::launch::{LaunchFile, LAUNCHER_FLAGS};

    /// A fit node fed from outside, with extra lines.
    fn fit(extra: &str) -> String {
        format!(
            "external=[\"cloud/c\"]\n[[node]]\nname=\"x\"\nkind=\"fit\"\n\
             inputs={{cloud=\"c\"}}\noutputs={{surrogate=\"s\"}}\n{extra}"
        )
    }

    fn flags_of(text: &str) -> Vec<String> {
        let file = LaunchFile::from_toml_str(text).unwrap();
        let nodes = super::super::plan::plan(&file).unwrap();
        let wiring = Wiring {
            namespace: "ns".into(),
            mode: "peer".into(),
            connect: vec!["tcp/127.0.0.1:1".into()],
            multicast: false,
            shm: true,
            log: "info".into(),
        };
        let cmd = command(&nodes[0], &wiring).unwrap();
        let args: Vec<String> = cmd
            .as_std()
            .get_args()
            .map(|a| a.to_string_lossy().into_owned())
            .collect();
        // The node's own options come last, exactly as planned.
        let own = args.len() - nodes[0].args.len();
        assert_eq!(args[own..], nodes[0].args[..]);
        args[..own]
            .iter()
            .filter(|a| a.starts_with("--"))
            .cloned()
            .collect()
    }

    #[test]
    fn the_launcher_passes_exactly_its_reserved_flags() {
        let mut flags = flags_of(&fit(""));
        flags.sort();
        flags.dedup();
        let mut reserved: Vec<String> = LAUNCHER_FLAGS.iter().map(|f| f.to_string()).collect();
        reserved.sort();
        assert_eq!(flags, reserved);
    }

    #[test]
    fn a_node_with_its_own_rust_log_gets_no_log_flag() {
        let flags = flags_of(&fit("env={RUST_LOG=\"debug\"}"));
        assert!(!flags.contains(&"--log".to_string()), "{flags:?}");
    }
}
