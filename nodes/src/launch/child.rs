//! One child process: spawned as `shroud node <run> ...` in its own process
//! group, with a parent-death signal, and its output prefixed line by line.

use anyhow::{Context, Result};
use shroud_core::launch::NodeSpec;
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

pub fn spawn(spec: &NodeSpec, wiring: &Wiring) -> Result<Child> {
    let exe = std::env::current_exe().context("cannot find the shroud executable")?;
    let mut cmd = Command::new(exe);
    cmd.arg("--log").arg(&wiring.log).arg("node").arg(&spec.run);
    cmd.arg("--name").arg(&spec.name);
    cmd.arg("--namespace").arg(&wiring.namespace);
    cmd.arg("--mode").arg(&wiring.mode);
    for endpoint in &wiring.connect {
        cmd.arg("--connect").arg(endpoint);
    }
    cmd.arg("--multicast")
        .arg(if wiring.multicast { "on" } else { "off" });
    cmd.arg("--shm").arg(if wiring.shm { "on" } else { "off" });
    cmd.args(&spec.args);
    cmd.envs(&spec.env);
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    // Its own process group: a Ctrl-C in the terminal reaches only the launcher,
    // which then stops the children in order instead of all dying at once.
    cmd.process_group(0);
    cmd.kill_on_drop(true);
    let launcher = std::process::id() as libc::pid_t;
    // SAFETY: only async-signal-safe calls (prctl, getppid, kill) run between
    // fork and exec.
    unsafe {
        cmd.pre_exec(move || {
            if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            // The launcher may have died before prctl took effect.
            if libc::getppid() != launcher {
                libc::kill(libc::getpid(), libc::SIGTERM);
            }
            Ok(())
        });
    }
    let mut child = cmd
        .spawn()
        .with_context(|| format!("cannot start node {} ({})", spec.name, spec.run))?;
    if let Some(out) = child.stdout.take() {
        tokio::spawn(prefix_lines(out, spec.name.clone(), false));
    }
    if let Some(err) = child.stderr.take() {
        tokio::spawn(prefix_lines(err, spec.name.clone(), true));
    }
    Ok(child)
}

async fn prefix_lines(stream: impl AsyncRead + Unpin, name: String, is_err: bool) {
    let mut lines = BufReader::new(stream).lines();
    while let Ok(Some(line)) = lines.next_line().await {
        if is_err {
            eprintln!("[{name}] {line}");
        } else {
            println!("[{name}] {line}");
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
