//! The computers a graph runs on: each host's endpoints and TLS identity
//! (the schema of `[hosts.NAME]`).

use serde::Deserialize;

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
