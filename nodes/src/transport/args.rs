//! zenoh session options shared by every node and tool: mode, endpoints,
//! namespace, scouting and shared memory.

use anyhow::{Context, Result};
use clap::Args;
use shroud_msg::Topics;
use std::path::PathBuf;

#[derive(Debug, Clone, Args)]
pub struct ZenohArgs {
    /// Namespace of every key: `shroud/<namespace>/...`.
    #[arg(long, default_value = "demo")]
    pub namespace: String,
    /// zenoh mode: `peer` (default; talks directly to other processes) or
    /// `client` (through a zenohd router given with --connect).
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
            matches!(self.mode.as_str(), "peer" | "client"),
            "--mode must be peer or client, not {:?}",
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
            (
                "timestamping/enabled",
                r#"{ router: true, peer: true, client: true }"#.to_string(),
            ),
        ];
        for (key, value) in settings {
            config
                .insert_json5(key, &value)
                .map_err(|e| anyhow::anyhow!("zenoh config {key} = {value}: {e}"))?;
        }
        Ok(config)
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
        let w = Wrap::parse_from(["x", "--mode", "router"]);
        assert!(w.z.config().unwrap_err().to_string().contains("--mode"));
        let w = Wrap::parse_from(["x", "--connect", "not an endpoint"]);
        assert!(w.z.config().is_err());
    }
}
