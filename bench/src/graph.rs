//! A graph of real node processes on a private zenoh hub, for benchmarks that
//! measure the graph itself (latency, consumers, soak): start and stop nodes by
//! name (each a `shroud node` process of the `shroud` binary beside this one),
//! read their CPU time and memory from `/proc`, and hear their messages.

use anyhow::{bail, Context, Result};
use shroud_msg::{NodeStatusMessage, SurrogateMessage, TopicKind};
use shroud_nodes::transport::{die_with_parent, OnOff, ZenohArgs};
use shroud_surrogate::SurrogateWire;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};

/// The graph: a hub session and the node processes started on it.
pub struct BenchGraph {
    pub session: zenoh::Session,
    pub namespace: String,
    endpoint: String,
    /// The `shroud` binary the nodes run.
    shroud: PathBuf,
    nodes: BTreeMap<String, Child>,
}

/// The `shroud` binary in this executable's directory: `cargo build` puts
/// both binaries of one profile in the same target directory.
fn shroud_beside_this_binary() -> Result<PathBuf> {
    let this = std::env::current_exe().context("cannot find the shroud-bench executable")?;
    let shroud = this.with_file_name(format!("shroud{}", std::env::consts::EXE_SUFFIX));
    if !shroud.is_file() {
        bail!(
            "this benchmark runs its nodes with the shroud binary, and there is none at {}: \
             build it first with `cargo build --release -p shroud` (the same profile as \
             shroud-bench; without --release for a debug shroud-bench)",
            shroud.display()
        );
    }
    say_which_binary(&shroud);
    Ok(shroud)
}

/// Names the binary the nodes run and when it was built: a `shroud` older
/// than the node code being measured gives old figures, and cargo does not
/// rebuild it for `cargo run -p shroud-bench`.
fn say_which_binary(shroud: &std::path::Path) {
    let age = std::fs::metadata(shroud)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|built| built.elapsed().ok());
    match age {
        Some(age) => eprintln!(
            "nodes run from {} (built {:.0} minutes ago; rebuild it with `cargo build --release -p shroud` after changing node code)",
            shroud.display(),
            age.as_secs_f64() / 60.0
        ),
        None => eprintln!("nodes run from {}", shroud.display()),
    }
}

impl BenchGraph {
    /// A hub on a free loopback port, in namespace `bench-<pid>-<tag>`.
    pub async fn start(tag: &str) -> Result<Self> {
        let shroud = shroud_beside_this_binary()?;
        let namespace = format!("bench-{}-{tag}", std::process::id());
        let hub = ZenohArgs {
            namespace: namespace.clone(),
            mode: "peer".into(),
            connect: vec![],
            listen: vec!["tcp/127.0.0.1:0".into()],
            multicast: Some(OnOff::Off),
            shm: OnOff::On,
            zenoh_config: None,
            tls_root_ca: None,
            tls_certificate: None,
            tls_private_key: None,
            access_control: None,
        };
        let session = hub.open().await?;
        let endpoint = session
            .info()
            .locators()
            .await
            .first()
            .map(|l| l.to_string())
            .context("the bench hub has no endpoint")?;
        Ok(Self {
            session,
            namespace,
            endpoint,
            shroud,
            nodes: BTreeMap::new(),
        })
    }

    /// Starts `shroud node <kind> --name <name> <args>` wired to the hub; its
    /// standard error goes to `log` (a file) when given, else nowhere.
    pub fn spawn(
        &mut self,
        name: &str,
        kind: &str,
        args: &[&str],
        log: Option<&std::path::Path>,
    ) -> Result<u32> {
        let mut cmd = Command::new(&self.shroud);
        cmd.args(["--log", "warn", "node", kind, "--name", name])
            .args(["--namespace", &self.namespace, "--connect", &self.endpoint])
            .args(["--multicast", "off"])
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::null());
        match log {
            Some(path) => cmd.stderr(std::fs::File::create(path)?),
            None => cmd.stderr(Stdio::null()),
        };
        // A bench killed outright must not leave its nodes running.
        die_with_parent(&mut cmd);
        let child = cmd
            .spawn()
            .with_context(|| format!("cannot start node {name}"))?;
        let pid = child.id();
        self.nodes.insert(name.to_string(), child);
        Ok(pid)
    }

    /// Calls `f` with every valid message of `kind` on stream `name` (`*`: all).
    async fn on<M: 'static>(
        &self,
        kind: TopicKind,
        name: &str,
        decode: fn(&[u8]) -> Option<M>,
        f: impl Fn(M) + Send + Sync + 'static,
    ) -> Result<zenoh::pubsub::Subscriber<()>> {
        let key = format!("shroud/{}/{kind}/{name}", self.namespace);
        self.session
            .declare_subscriber(&key)
            .callback(move |sample| {
                if let Some(m) = decode(&sample.payload().to_bytes()) {
                    f(m);
                }
            })
            .await
            .map_err(|e| anyhow::anyhow!("subscribe {key}: {e}"))
    }

    /// Every certified surrogate of `stream`.
    pub async fn on_surrogates(
        &self,
        stream: &str,
        f: impl Fn(SurrogateMessage) + Send + Sync + 'static,
    ) -> Result<zenoh::pubsub::Subscriber<()>> {
        let decode = |b: &[u8]| SurrogateMessage::from_bytes(b).ok().map(|(m, _)| m);
        self.on(TopicKind::Surrogate, stream, decode, f).await
    }

    /// Every status message of node `name` (`*`: every node).
    pub async fn on_status(
        &self,
        name: &str,
        f: impl Fn(NodeStatusMessage) + Send + Sync + 'static,
    ) -> Result<zenoh::pubsub::Subscriber<()>> {
        let decode = |b: &[u8]| NodeStatusMessage::from_bytes(b).ok();
        self.on(TopicKind::Status, name, decode, f).await
    }

    pub fn pid(&self, name: &str) -> Option<u32> {
        self.nodes.get(name).map(Child::id)
    }

    /// Stops node `name` with SIGTERM and waits for it.
    pub fn stop(&mut self, name: &str) {
        if let Some(mut child) = self.nodes.remove(name) {
            terminate(&mut child);
        }
    }

    pub fn stop_all(&mut self) {
        for (_, mut child) in std::mem::take(&mut self.nodes) {
            terminate(&mut child);
        }
    }
}

impl Drop for BenchGraph {
    fn drop(&mut self) {
        for child in self.nodes.values_mut() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

fn terminate(child: &mut Child) {
    // SAFETY: kill(2) on our own child.
    unsafe {
        libc::kill(child.id() as libc::pid_t, libc::SIGTERM);
    }
    let _ = child.wait();
}

/// CPU seconds (user + system) a process and its live descendants have used,
/// from `/proc/<pid>/stat`.
pub fn tree_cpu_seconds(root: u32) -> f64 {
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return 0.0;
    };
    let stats: Vec<(u32, u32, u64)> = entries
        .flatten()
        .filter_map(|e| e.file_name().to_str()?.parse::<u32>().ok())
        .filter_map(|pid| {
            let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
            let (ppid, ticks) = parse_stat(&stat)?;
            Some((pid, ppid, ticks))
        })
        .collect();
    let mut members = vec![root];
    let mut i = 0;
    while i < members.len() {
        let parent = members[i];
        members.extend(stats.iter().filter(|s| s.1 == parent).map(|s| s.0));
        i += 1;
    }
    let ticks: u64 = stats
        .iter()
        .filter(|s| members.contains(&s.0))
        .map(|s| s.2)
        .sum();
    ticks as f64 / clock_ticks_per_second()
}

/// Resident memory of a process, bytes (`/proc/<pid>/statm`).
pub fn rss_bytes(pid: u32) -> Option<u64> {
    let statm = std::fs::read_to_string(format!("/proc/{pid}/statm")).ok()?;
    let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    // SAFETY: sysconf has no preconditions.
    let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) }.max(1) as u64;
    Some(pages * page)
}

/// (parent pid, utime + stime in clock ticks) from a `/proc/<pid>/stat` line;
/// the command name may hold spaces and parentheses, so fields are counted
/// from the last `)`.
fn parse_stat(stat: &str) -> Option<(u32, u64)> {
    let rest = &stat[stat.rfind(')')? + 1..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // After the name: state(0) ppid(1) ... utime(11) stime(12).
    let ppid = fields.get(1)?.parse().ok()?;
    let utime: u64 = fields.get(11)?.parse().ok()?;
    let stime: u64 = fields.get(12)?.parse().ok()?;
    Some((ppid, utime + stime))
}

fn clock_ticks_per_second() -> f64 {
    // SAFETY: sysconf has no preconditions.
    let ticks = unsafe { libc::sysconf(libc::_SC_CLK_TCK) };
    if ticks > 0 {
        ticks as f64
    } else {
        100.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stat_lines_with_odd_names_parse() {
        let line =
            "4242 (a (b) c) S 17 4242 4242 0 -1 4194560 100 0 0 0 250 50 0 0 20 0 1 0 100 1000 10";
        assert_eq!(parse_stat(line), Some((17, 300)));
        assert_eq!(parse_stat("garbage"), None);
        assert!(tree_cpu_seconds(std::process::id()) >= 0.0);
        assert!(rss_bytes(std::process::id()).is_some_and(|b| b > 0));
    }
}
