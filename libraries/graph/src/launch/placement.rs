//! Where a graph's nodes run: a host of the file by name, and the checks that
//! every node is placed on a complete host, that hosts meet only over TLS
//! when any has it, and that nodes aging another host's data state the
//! hosts' clock offset. Above the schema (`file`, `hosts`), as `load` is.

use super::error::LaunchError;
use super::file::LaunchFile;
use super::hosts::HostSpec;
use super::kind::{Direction, NodeKind};
use shroud_msg::check_name;
use std::collections::BTreeMap;

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
        self.check_clock_offsets()?;
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

    /// A node that ages what another host sent (a fit node's clouds, a
    /// guard's surrogates and joint states) counts the transit on two
    /// hosts' clocks: it must state the bound on their offset
    /// (`max_clock_offset`, whose default is one host's), which it then adds
    /// to every transit and checks every message against.
    fn check_clock_offsets(&self) -> Result<(), LaunchError> {
        let mut producer_host = BTreeMap::new();
        for node in &self.nodes {
            for wire in node.wires()? {
                if wire.port.direction == Direction::Output {
                    producer_host.insert(wire.stream.to_string(), node.host.clone());
                }
            }
        }
        let ages = |kind: NodeKind| matches!(kind, NodeKind::Fit | NodeKind::Guard);
        for node in self.nodes.iter().filter(|n| ages(n.kind)) {
            let stated = node.settings.contains_key("max_clock_offset")
                || node.settings.contains_key("max-clock-offset");
            let remote = node.wires()?.into_iter().find(|w| {
                w.port.direction == Direction::Input
                    && producer_host.get(&w.stream.to_string()) != Some(&node.host)
            });
            if let (false, Some(wire)) = (stated, remote) {
                return Err(node.error(format!(
                    "reads {} from another host: set max_clock_offset (seconds) to the bound \
                     on the hosts' clock offset (its default, 0.001, is one host's)",
                    wire.stream
                )));
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
    // A host's identity is its certificate's common name, and zenoh's
    // connecting side trusts the public web authorities besides the graph's:
    // a name that could be a DNS name could be certified by any of them.
    if name.contains('.') {
        return Err(invalid(
            "name",
            "a host name has no '.' (it must not be a DNS name a public authority certifies)"
                .into(),
        ));
    }
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
