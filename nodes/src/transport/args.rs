//! zenoh session options shared by every node and tool: mode, endpoints,
//! namespace, scouting and shared memory.

use anyhow::{Context, Result};
use clap::Args;
use shroud_msg::Topics;
use std::path::PathBuf;

/// The kernel's send buffer of a `tls/` link (a link between hosts), bytes.
/// zenoh orders messages by priority in its own queues; what it has written
/// to the socket goes out first, whatever its priority, and TCP keeps at
/// most this much in flight, so it also bounds what a slow link's own queue
/// holds of this link. Left to the kernel's autotuning, a socket of a link
/// slower than the clouds it carries fills to megabytes: a joint state then
/// waited 1.6 s (p50) behind 30 000-point clouds on a link with 20 ms of
/// delay, 1 % loss and 10 Mbit/s (docs/multi-host.md, slow links). Linux
/// doubles the value: 32 KiB is 0.26 ms at 1 Gbit/s and 13 ms at 20
/// Mbit/s, and caps one link at 32 KiB per round trip (260 Mbit/s at 1 ms,
/// 26 Mbit/s at 10 ms), which surrogates, joint states and verdicts never
/// need; only clouds sent across a long link would.
pub const TLS_SEND_BUFFER: u32 = 16 * 1024;

/// The largest batch zenoh writes to a link at once, bytes (its default is
/// 64 KiB). A real-time message waits for the batch being written: 16 KiB
/// is 13 ms at 10 Mbit/s where 64 KiB is 52 ms. Like the queue sizes below,
/// it is a setting of the whole session (set with TLS, so on a host's
/// router and on tools that reach it), and zenoh takes the smaller batch of
/// a link's two ends: the router's loopback links to its nodes use it too,
/// which costs them nothing (clouds cross those in shared memory).
pub const TLS_BATCH_SIZE: u32 = 16 * 1024;

#[derive(Debug, Clone, Args)]
pub struct ZenohArgs {
    /// Namespace of every key: `shroud/<namespace>/...`.
    #[arg(long, default_value = "demo")]
    pub namespace: String,
    /// zenoh mode: `peer` (default; talks directly to other processes),
    /// `client` (through a router given with --connect), or `router` (what
    /// `shroud router` and a launcher started with `--host` run).
    #[arg(long, default_value = "peer")]
    pub mode: String,
    /// Endpoint to connect to, e.g. `tcp/192.168.1.10:7447` (a zenohd router or
    /// the launcher). Repeatable.
    #[arg(long = "connect", value_name = "ENDPOINT")]
    pub connect: Vec<String>,
    /// Endpoint to listen on, e.g. `tcp/0.0.0.0:7448`. Repeatable. Default: a
    /// free loopback port in peer mode.
    #[arg(long = "listen", value_name = "ENDPOINT")]
    pub listen: Vec<String>,
    /// Multicast scouting, to find peers on the LAN without endpoints.
    /// Default: on when no --connect is given.
    #[arg(long, value_name = "on|off")]
    pub multicast: Option<OnOff>,
    /// zenoh shared memory for large payloads between processes of one machine.
    #[arg(long, default_value = "on", value_name = "on|off")]
    pub shm: OnOff,
    /// A zenoh JSON5 configuration file; the options above override it.
    #[arg(long, value_name = "FILE")]
    pub zenoh_config: Option<PathBuf>,
    /// The certificate authority (PEM) every host's certificate chains to:
    /// with --tls-certificate and --tls-private-key, `tls/` links are mutual
    /// TLS (`shroud certs` makes all three).
    #[arg(long, value_name = "FILE", requires_all = ["tls_certificate", "tls_private_key"])]
    pub tls_root_ca: Option<PathBuf>,
    /// This host's certificate (PEM), its common name the host's name.
    #[arg(long, value_name = "FILE", requires = "tls_root_ca")]
    pub tls_certificate: Option<PathBuf>,
    /// This host's private key (PEM).
    #[arg(long, value_name = "FILE", requires = "tls_root_ca")]
    pub tls_private_key: Option<PathBuf>,
    /// zenoh's `access_control` section (JSON), set by the launcher and
    /// `shroud router` from a graph file's hosts.
    #[arg(skip)]
    pub access_control: Option<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum OnOff {
    On,
    Off,
}

impl OnOff {
    pub fn is_on(self) -> bool {
        self == Self::On
    }
}

impl ZenohArgs {
    pub fn topics(&self) -> Result<Topics> {
        Ok(Topics::new(&self.namespace)?)
    }

    /// The zenoh configuration these options describe.
    pub fn config(&self) -> Result<zenoh::Config> {
        let mut config = match &self.zenoh_config {
            Some(path) => zenoh::Config::from_file(path)
                .map_err(|e| anyhow::anyhow!("zenoh config {}: {e}", path.display()))?,
            None => zenoh::Config::default(),
        };
        anyhow::ensure!(
            matches!(self.mode.as_str(), "peer" | "client" | "router"),
            "--mode must be peer, client or router, not {:?}",
            self.mode
        );
        let listen = if self.listen.is_empty() && self.mode == "peer" {
            vec!["tcp/127.0.0.1:0".to_string()]
        } else {
            self.listen.clone()
        };
        let multicast = self
            .multicast
            .map(OnOff::is_on)
            .unwrap_or(self.connect.is_empty());
        let settings = [
            ("mode", json(&self.mode)),
            ("connect/endpoints", json(&self.connect)),
            ("listen/endpoints", json(&listen)),
            ("scouting/multicast/enabled", multicast.to_string()),
            (
                "transport/shared_memory/enabled",
                self.shm.is_on().to_string(),
            ),
            // A peer keeps retrying its endpoints instead of failing at start, so
            // nodes may start in any order.
            ("connect/exit_on_failure", "false".to_string()),
            // Every sample carries its publication time (the session's hybrid
            // logical clock, i.e. its wall clock): the receivers count the
            // transit, and whatever held a sample up before their callbacks
            // ran, toward the data's age.
            // The session's own admin space answers `session_drops` (what
            // zenoh dropped, for the status messages).
            (
                "adminspace",
                "{ enabled: true, permissions: { read: true, write: false } }".to_string(),
            ),
            (
                "timestamping/enabled",
                r#"{ router: true, peer: true, client: true }"#.to_string(),
            ),
        ];
        let tls = self.tls_settings()?;
        let access = self
            .access_control
            .iter()
            .map(|acl| ("access_control", acl.clone()));
        for (key, value) in settings.into_iter().chain(tls).chain(access) {
            config
                .insert_json5(key, &value)
                .map_err(|e| anyhow::anyhow!("zenoh config {key} = {value}: {e}"))?;
        }
        Ok(config)
    }

    /// Mutual TLS on every `tls/` link (zenoh 1.x `transport/link/tls`): the
    /// listener accepts only certificates chained to the root (TLS 1.3), the
    /// connecting side checks the listener's name against its certificate.
    fn tls_settings(&self) -> Result<Vec<(&'static str, String)>> {
        let (Some(ca), Some(cert), Some(key)) = (
            &self.tls_root_ca,
            &self.tls_certificate,
            &self.tls_private_key,
        ) else {
            return Ok(Vec::new());
        };
        for (flag, path) in [
            ("--tls-root-ca", ca),
            ("--tls-certificate", cert),
            ("--tls-private-key", key),
        ] {
            anyhow::ensure!(path.is_file(), "{flag} {}: no such file", path.display());
        }
        let path = |p: &PathBuf| json(&p.display().to_string());
        Ok(vec![
            ("transport/link/tls/root_ca_certificate", path(ca)),
            ("transport/link/tls/listen_certificate", path(cert)),
            ("transport/link/tls/listen_private_key", path(key)),
            ("transport/link/tls/connect_certificate", path(cert)),
            ("transport/link/tls/connect_private_key", path(key)),
            ("transport/link/tls/enable_mtls", "true".into()),
            ("transport/link/tls/verify_name_on_connect", "true".into()),
            // A link does not outlive the certificate it was opened with.
            ("transport/link/tls/close_link_on_expiration", "true".into()),
            ("transport/link/tls/so_sndbuf", TLS_SEND_BUFFER.to_string()),
            // Clouds (priority data-low) wait in zenoh's queue, not in the
            // socket: the most it allows, 16 batches (256 KiB). A cloud that
            // does not fit waits for room at most 50 ms in all (zenoh's
            // `max_wait_before_drop_fragments`, left as it is: the router's
            // task routing a cloud waits with it, holding up whatever else
            // came on the same link), and is then cut short, its sent
            // fragments wasted: so a cloud crosses a link only if the link
            // drains what exceeds the queue within 50 ms. Real-time messages
            // are sent first whatever this queue holds.
            ("transport/link/tx/queue/size/data_low", "16".into()),
            // An express message (joint states, verdicts, surrogates) takes
            // a batch of its own: two (the default) are two messages, and a
            // third that comes while a cloud's batch is being written is
            // dropped after a millisecond.
            ("transport/link/tx/queue/size/real_time", "16".into()),
            ("transport/link/tx/batch_size", TLS_BATCH_SIZE.to_string()),
        ])
    }

    /// Opens a session with these options.
    pub async fn open(&self) -> Result<zenoh::Session> {
        let config = self.config()?;
        zenoh::open(config)
            .await
            .map_err(|e| anyhow::anyhow!("{e}"))
            .with_context(|| {
                format!(
                    "cannot open a zenoh session (mode {}, connect {:?})",
                    self.mode, self.connect
                )
            })
    }
}

fn json<T: serde::Serialize + ?Sized>(value: &T) -> String {
    serde_json::to_string(value).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Wrap {
        #[command(flatten)]
        z: ZenohArgs,
    }

    #[test]
    fn builds_a_config_and_rejects_bad_modes() {
        let w = Wrap::parse_from(["x", "--connect", "tcp/127.0.0.1:7447", "--shm", "off"]);
        assert!(w.z.config().is_ok());
        let w = Wrap::parse_from(["x", "--mode", "bridge"]);
        assert!(w.z.config().unwrap_err().to_string().contains("--mode"));
        let w = Wrap::parse_from(["x", "--connect", "not an endpoint"]);
        assert!(w.z.config().is_err());
    }

    #[test]
    fn tls_files_are_checked_and_set_for_both_ends_of_a_link() {
        let dir = tempfile::tempdir().unwrap();
        let file = |name: &str| {
            let path = dir.path().join(name);
            std::fs::write(&path, "pem").unwrap();
            path.display().to_string()
        };
        let (ca, cert, key) = (file("ca.pem"), file("h.pem"), file("h.key"));
        let with_key = |key: &str| {
            let tls = [
                "--tls-root-ca",
                &ca,
                "--tls-certificate",
                &cert,
                "--tls-private-key",
                key,
            ];
            Wrap::parse_from(["x"].into_iter().chain(tls))
        };
        let settings = with_key(&key).z.tls_settings().unwrap();
        let keys: Vec<&str> = settings.iter().map(|(k, _)| *k).collect();
        assert!(keys.contains(&"transport/link/tls/connect_certificate"));
        assert!(settings.contains(&("transport/link/tls/enable_mtls", "true".into())));
        let missing = dir.path().join("none.key").display().to_string();
        let w = with_key(&missing);
        let error = w.z.config().unwrap_err().to_string();
        assert!(
            error.contains("--tls-private-key") && error.contains("no such file"),
            "{error}"
        );
        assert!(Wrap::try_parse_from(["x", "--tls-root-ca", &ca]).is_err());
    }
}
