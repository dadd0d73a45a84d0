//! The computers a graph runs on: each host's endpoints and TLS identity,
//! and which host each node runs on (`shroud launch FILE --host NAME`).

use super::error::LaunchError;
use super::file::LaunchFile;
use serde::Deserialize;
use shroud_msg::check_name;

/// One computer of the graph and how its launcher meets the others'.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HostSpec {
    /// Endpoints this host's launcher listens on for the other hosts
    /// (`tls/0.0.0.0:7447`).
    #[serde(default)]
    pub listen: Vec<String>,
    /// Endpoints of other hosts (a router host) this host's launcher
    /// connects to.
    #[serde(default)]
    pub connect: Vec<String>,
    /// A router host relays every stream: its certificate may forward what
    /// the other hosts publish (it runs `shroud router`, or a launcher).
    #[serde(default)]
    pub router: bool,
    /// The host's certificate and key and the authority that signed every
    /// host's: links between hosts are mutual TLS, and a host's identity is
    /// its certificate's common name, which must be the host's name.
    pub tls: Option<TlsSpec>,
}

/// Paths (relative to the directory the launcher runs in) of a host's TLS
/// files, as `shroud certs` writes them.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TlsSpec {
    pub root_ca: String,
    pub certificate: String,
    pub private_key: String,
}

impl LaunchFile {
    /// The host `name` of the file.
    pub fn host(&self, name: &str) -> Result<&HostSpec, LaunchError> {
        self.hosts.get(name).ok_or_else(|| LaunchError::Invalid {
            field: "--host".into(),
            reason: format!(
                "{name:?} is not a host of the file (its hosts: {})",
                self.host_names().join(", ")
            ),
        })
    }

    /// The names of the file's hosts, sorted.
    pub fn host_names(&self) -> Vec<&str> {
        self.hosts.keys().map(String::as_str).collect()
    }

    /// Every host is named correctly and complete; with hosts, every node
    /// names one of them; with TLS on one host, it is on all, and every
    /// endpoint between hosts is a TLS one.
    pub(super) fn check_hosts(&self) -> Result<(), LaunchError> {
        if self.hosts.is_empty() {
            return match self.nodes.iter().find(|n| n.host.is_some()) {
                Some(node) => Err(node.error("names a host, but the file has no [hosts]".into())),
                None => Ok(()),
            };
        }
        let with_tls = self.hosts.values().filter(|h| h.tls.is_some()).count();
        for (name, host) in &self.hosts {
            check_host(name, host, with_tls > 0)?;
        }
        for node in &self.nodes {
            match &node.host {
                Some(host) if self.hosts.contains_key(host) => {}
                Some(host) => {
                    return Err(node.error(format!(
                        "host {host:?} is not in [hosts] ({})",
                        self.host_names().join(", ")
                    )))
                }
                None => {
                    return Err(node.error(format!(
                        "names no host; a file with [hosts] places every node ({})",
                        self.host_names().join(", ")
                    )))
                }
            }
        }
        Ok(())
    }
}

fn check_host(name: &str, host: &HostSpec, tls_everywhere: bool) -> Result<(), LaunchError> {
    let invalid = |field: &str, reason: String| LaunchError::Invalid {
        field: format!("hosts.{name}.{field}"),
        reason,
    };
    check_name("host", name).map_err(|e| invalid("name", e.to_string()))?;
    if tls_everywhere && host.tls.is_none() {
        return Err(invalid(
            "tls",
            "another host has TLS: every host needs its certificate (links between hosts are mutual TLS)".into(),
        ));
    }
    for (field, endpoints) in [("listen", &host.listen), ("connect", &host.connect)] {
        for endpoint in endpoints {
            if !endpoint.contains('/') {
                return Err(invalid(
                    field,
                    format!("{endpoint:?} is not protocol/address:port"),
                ));
            }
            if tls_everywhere && !endpoint.starts_with("tls/") {
                return Err(invalid(
                    field,
                    format!("{endpoint:?} is not a TLS endpoint (tls/...): the graph uses TLS between hosts"),
                ));
            }
        }
    }
    Ok(())
}
