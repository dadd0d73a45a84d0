//! Hosts on one machine for the multi-host tests: a network namespace per
//! host, each with a veth on a bridge (in a namespace of its own, out of the
//! root namespace's firewall), and a veth from the root namespace onto that
//! bridge with an address, so that the test process reaches every host. A
//! process started on a host runs in its namespace with a private `/dev/shm`
//! (zenoh's shared memory would cross namespaces otherwise). Everything,
//! processes left in the namespaces included, goes when the [`Lan`] is
//! dropped. Needs root and `ip netns`. A host may be given a link with delay
//! and loss instead of a veth ([`Lan::with_relayed`], [`super::impair`]), and
//! any host's link a bandwidth limit ([`Lan::limit_rate`]).

use super::impair::{Impairment, Relay, RelayCounts};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use zenoh::Wait;

/// Why network namespaces cannot be made here, if they cannot.
pub fn unusable() -> Option<String> {
    if unsafe { libc::geteuid() } != 0 {
        return Some("not root: network namespaces need root".into());
    }
    let tools = [
        ("ip", &["netns", "list"][..]),
        ("unshare", &["--help"][..]),
        ("tc", &["qdisc", "show"][..]),
    ];
    for (tool, args) in tools {
        match Command::new(tool).args(args).output() {
            Ok(out) if out.status.success() => {}
            Ok(out) => {
                return Some(format!(
                    "`{tool} {}` fails: {}",
                    args.join(" "),
                    String::from_utf8_lossy(&out.stderr).trim()
                ))
            }
            Err(e) => return Some(format!("no `{tool}` ({e})")),
        }
    }
    None
}

/// Skips the calling test (it returns after this) with `reason`, or fails it
/// under `CI=true`, where it must run.
pub fn skip(reason: &str) {
    if std::env::var("CI").as_deref() == Ok("true") {
        panic!("cannot run under CI=true: {reason}");
    }
    eprintln!("skipped: {reason}");
}

/// Hosts in network namespaces on one bridge; see the module documentation.
pub struct Lan {
    /// Names of this run's namespaces and root interface start with it.
    prefix: String,
    /// The first three bytes of the hosts' /24.
    subnet: String,
    hosts: Vec<String>,
    /// The relays of hosts whose link has delay and loss, by host.
    relays: BTreeMap<String, Relay>,
}

/// Runs `ip args`; its stderr as the error.
fn ip(args: &[&str]) -> Result<(), String> {
    ip_tool("ip", args)
}

/// Runs `tool args` (`ip`, `tc`); its stderr as the error.
fn ip_tool(tool: &str, args: &[&str]) -> Result<(), String> {
    let out = Command::new(tool)
        .args(args)
        .output()
        .map_err(|e| format!("{tool}: {e}"))?;
    match out.status.success() {
        true => Ok(()),
        false => Err(format!(
            "{tool} {}: {}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr).trim()
        )),
    }
}

impl Lan {
    /// One namespace per host of `hosts`, at `10.X.Y.1`, `10.X.Y.2`, ... in
    /// their order (X and Y from the test's pid, as the names are), and the
    /// root namespace at `10.X.Y.254`.
    pub fn new(hosts: &[&str]) -> Result<Lan, String> {
        Lan::with_relayed(hosts, &[])
    }

    /// [`Lan::new`], but the hosts of `relayed` reach the bridge through a
    /// [`Relay`] between two TAPs (no delay nor loss until
    /// [`Lan::impair`]).
    pub fn with_relayed(hosts: &[&str], relayed: &[&str]) -> Result<Lan, String> {
        if !relayed.is_empty() && !Path::new("/dev/net/tun").exists() {
            return Err("no /dev/net/tun: a relayed link needs TAP devices".into());
        }
        let pid = std::process::id();
        let mut lan = Lan {
            prefix: format!("shr{pid}"),
            subnet: format!("10.{}.{}", 100 + (pid >> 8) % 100, pid & 0xff),
            hosts: hosts.iter().map(|h| h.to_string()).collect(),
            relays: BTreeMap::new(),
        };
        // Leftovers of runs that were killed, this pid's included.
        sweep_dead_runs();
        lan.remove();
        let switch = lan.switch();
        ip(&["netns", "add", &switch])?;
        ip(&["-n", &switch, "link", "add", "br0", "type", "bridge"])?;
        ip(&["-n", &switch, "link", "set", "br0", "up"])?;
        if !relayed.is_empty() {
            // [`Lan::limit_rate`] needs the kernel's token bucket: say so
            // now rather than halfway through a test.
            let probe = ["-n", &switch, "qdisc", "add", "dev", "br0", "root", "tbf"];
            let rate = ["rate", "1mbit", "burst", "3000", "latency", "10ms"];
            ip_tool("tc", &[&probe[..], &rate[..]].concat())
                .map_err(|e| format!("no tbf qdisc to limit a link's rate: {e}"))?;
            ip_tool("tc", &["-n", &switch, "qdisc", "del", "dev", "br0", "root"])?;
        }
        for (i, host) in lan.hosts.iter().enumerate() {
            let ns = lan.ns(host);
            let port = format!("v{i}");
            ip(&["netns", "add", &ns])?;
            match relayed.contains(&host.as_str()) {
                true => {
                    ip(&["-n", &ns, "tuntap", "add", "dev", "eth0", "mode", "tap"])?;
                    ip(&["-n", &switch, "tuntap", "add", "dev", &port, "mode", "tap"])?;
                    let relay = Relay::start(&ns, "eth0", &switch, &port)
                        .map_err(|e| format!("the relay of {host}'s link: {e}"))?;
                    lan.relays.insert(host.clone(), relay);
                }
                false => ip(&[
                    "-n", &switch, "link", "add", &port, "type", "veth", "peer", "name", "eth0",
                    "netns", &ns,
                ])?,
            }
            ip(&["-n", &switch, "link", "set", &port, "master", "br0", "up"])?;
            let address = format!("{}/24", lan.addr(host));
            ip(&["-n", &ns, "addr", "add", &address, "dev", "eth0"])?;
            ip(&["-n", &ns, "link", "set", "eth0", "up"])?;
            ip(&["-n", &ns, "link", "set", "lo", "up"])?;
        }
        let root = lan.root_interface();
        ip(&[
            "link", "add", &root, "type", "veth", "peer", "name", "uplink", "netns", &switch,
        ])?;
        ip(&[
            "-n", &switch, "link", "set", "uplink", "master", "br0", "up",
        ])?;
        ip(&[
            "addr",
            "add",
            &format!("{}/24", lan.root_addr()),
            "dev",
            &root,
        ])?;
        ip(&["link", "set", &root, "up"])?;
        Ok(lan)
    }

    fn switch(&self) -> String {
        format!("{}-switch", self.prefix)
    }

    fn root_interface(&self) -> String {
        // At most 15 characters: "shr" and a pid.
        self.prefix.clone()
    }

    /// The namespace of `host`.
    pub fn ns(&self, host: &str) -> String {
        format!("{}-{host}", self.prefix)
    }

    /// The address of `host` on the bridge.
    pub fn addr(&self, host: &str) -> String {
        format!("{}.{}", self.subnet, self.index(host) + 1)
    }

    fn index(&self, host: &str) -> usize {
        (self.hosts.iter().position(|h| h == host))
            .unwrap_or_else(|| panic!("{host} is not a host of the LAN"))
    }

    /// The root namespace's address on the bridge.
    pub fn root_addr(&self) -> String {
        format!("{}.254", self.subnet)
    }

    /// Takes `host`'s link to the bridge down (inside its namespace).
    pub fn link_down(&self, host: &str) {
        ip(&["-n", &self.ns(host), "link", "set", "eth0", "down"]).unwrap();
    }

    /// Brings `host`'s link back up.
    pub fn link_up(&self, host: &str) {
        ip(&["-n", &self.ns(host), "link", "set", "eth0", "up"]).unwrap();
    }

    /// Delay and loss on `host`'s link from now on, both ways (a host given
    /// to [`Lan::with_relayed`]).
    pub fn impair(&self, host: &str, impairment: Impairment) {
        self.relay(host).set(impairment);
    }

    /// The frames `host`'s relay handled so far.
    pub fn relay_counts(&self, host: &str) -> RelayCounts {
        self.relay(host).counts()
    }

    fn relay(&self, host: &str) -> &Relay {
        (self.relays.get(host)).unwrap_or_else(|| panic!("{host}'s link has no relay"))
    }

    /// Limits `host`'s link to `mbit_s` megabits a second each way with the
    /// kernel's token bucket (`tbf`: a 10 ms burst, at most 100 ms queued,
    /// beyond which frames are dropped), or lifts the limit (`None`).
    pub fn limit_rate(&self, host: &str, mbit_s: Option<f64>) {
        let port = format!("v{}", self.index(host));
        for (ns, device) in [(self.ns(host), "eth0"), (self.switch(), port.as_str())] {
            let _ = ip_tool("tc", &["-n", &ns, "qdisc", "del", "dev", device, "root"]);
            let Some(rate) = mbit_s else { continue };
            let burst = format!("{}", ((rate * 1e6 / 8.0 * 0.01) as u64).max(3_000));
            let rate = format!("{}kbit", (rate * 1000.0) as u64);
            let args = [
                "-n", &ns, "qdisc", "add", "dev", device, "root", "tbf", "rate", &rate, "burst",
                &burst, "latency", "100ms",
            ];
            ip_tool("tc", &args).unwrap();
        }
    }

    /// `program` to run on `host`: in its namespace, in a mount namespace of
    /// its own with a fresh tmpfs on `/dev/shm` (add the arguments).
    pub fn command(&self, host: &str, program: impl AsRef<Path>) -> Command {
        let mut command = Command::new("ip");
        command
            .args(["netns", "exec", &self.ns(host)])
            .args(["unshare", "--mount", "--propagation", "private"])
            .args([
                "sh",
                "-c",
                "mount -t tmpfs -o size=512m shm /dev/shm && exec \"$0\" \"$@\"",
            ])
            .arg(program.as_ref())
            .stdin(Stdio::null());
        command
    }

    /// The pids of the processes in `host`'s namespace.
    pub fn pids(&self, host: &str) -> Vec<i32> {
        namespace_pids(&self.ns(host))
    }

    /// Kills what runs in the namespaces, deletes them (and with them every
    /// veth, the root namespace's end included).
    fn remove(&mut self) {
        // The relays hold the TAPs: stop them before their namespaces go.
        self.relays.clear();
        let mut namespaces: Vec<String> = self.hosts.iter().map(|h| self.ns(h)).collect();
        namespaces.push(self.switch());
        for ns in &namespaces {
            for pid in namespace_pids(ns) {
                unsafe {
                    libc::kill(pid, libc::SIGKILL);
                }
            }
        }
        for ns in &namespaces {
            // A killed process may take a moment to release it.
            for _ in 0..20 {
                if !Path::new("/run/netns").join(ns).exists() || ip(&["netns", "del", ns]).is_ok() {
                    break;
                }
                std::thread::sleep(std::time::Duration::from_millis(100));
            }
        }
        let _ = ip(&["link", "del", &self.root_interface()]);
    }
}

impl Drop for Lan {
    fn drop(&mut self) {
        self.remove();
    }
}

/// Removes the namespaces (and what runs in them) and root interfaces of
/// runs whose test process is gone (killed before its [`Lan`] was dropped).
fn sweep_dead_runs() {
    let dead = |name: &str| {
        let pid = name.strip_prefix("shr").and_then(|rest| {
            let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
            digits.parse::<u32>().ok()
        });
        pid.is_some_and(|pid| !Path::new(&format!("/proc/{pid}")).exists())
    };
    let listed = |args: &[&str]| {
        let out = Command::new("ip").args(args).output();
        out.map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
            .unwrap_or_default()
    };
    for line in listed(&["netns", "list"]).lines() {
        let name = line.split_whitespace().next().unwrap_or_default();
        if dead(name) {
            for pid in namespace_pids(name) {
                unsafe {
                    libc::kill(pid, libc::SIGKILL);
                }
            }
            let _ = ip(&["netns", "del", name]);
        }
    }
    for line in listed(&["-o", "link", "show"]).lines() {
        // `7: shr1234@if6: <...`
        let name = line.split_whitespace().nth(1).unwrap_or_default();
        let name = name
            .trim_end_matches(':')
            .split('@')
            .next()
            .unwrap_or_default();
        if dead(name) {
            let _ = ip(&["link", "del", name]);
        }
    }
}

fn namespace_pids(ns: &str) -> Vec<i32> {
    let Ok(out) = Command::new("ip").args(["netns", "pids", ns]).output() else {
        return Vec::new();
    };
    String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .filter_map(|p| p.parse().ok())
        .collect()
}

/// The names in `/dev/shm` as process `pid` sees it (its mount namespace's).
pub fn shm_of(pid: i32) -> Vec<String> {
    let dir = PathBuf::from(format!("/proc/{pid}/root/dev/shm"));
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

/// The mount namespace of process `pid` (`mnt:[...]`).
pub fn mount_ns_of(pid: i32) -> String {
    std::fs::read_link(format!("/proc/{pid}/ns/mnt"))
        .map(|p| p.display().to_string())
        .unwrap_or_default()
}

/// A zenoh client session of the router at `endpoint` (a host's address on
/// the LAN, reached from the root namespace), over mutual TLS only with
/// `identity`'s certificate and key from `certs` (`<identity>.pem`,
/// `<identity>.key`, `ca.pem`, as `shroud certs` writes them).
pub fn lan_client(certs: &Path, endpoint: &str, identity: &str) -> zenoh::Result<zenoh::Session> {
    let file = |name: String| serde_json::to_string(&certs.join(name).display().to_string());
    let mut config = zenoh::Config::default();
    let settings = [
        ("mode", "\"client\"".to_string()),
        ("connect/endpoints", serde_json::to_string(&[endpoint])?),
        ("scouting/multicast/enabled", "false".into()),
        ("scouting/gossip/enabled", "false".into()),
        ("transport/link/protocols", "[\"tls\"]".into()),
        ("transport/shared_memory/enabled", "false".into()),
        (
            "transport/link/tls/root_ca_certificate",
            file("ca.pem".into())?,
        ),
        (
            "transport/link/tls/connect_certificate",
            file(format!("{identity}.pem"))?,
        ),
        (
            "transport/link/tls/connect_private_key",
            file(format!("{identity}.key"))?,
        ),
        ("transport/link/tls/enable_mtls", "true".into()),
        ("transport/link/tls/verify_name_on_connect", "true".into()),
    ];
    for (key, value) in settings {
        config.insert_json5(key, &value)?;
    }
    zenoh::open(config).wait()
}
