//! Who may publish what, from the graph file: zenoh's access control for one
//! host, so that a stranger holding another host's certificate cannot
//! publish a verdict, a joint state or a surrogate it does not own.
//!
//! Nothing may be published that a rule does not allow (zenoh's default
//! here is deny): a host's certificate (its common name, which `shroud
//! certs` sets to the host's name) may publish exactly the keys its nodes
//! write (their outputs, a fit node's sector streams, their statuses, and its
//! launcher's and router's statuses), a router host's certificate anything
//! (it relays what other routers checked), and the router's own host's
//! processes anything, over loopback only. A put on a wildcard key (`*`,
//! `**`) is allowed to no host, since zenoh allows a put only when a rule's
//! key expression includes the put's. Data goes out to any subscriber;
//! subscribing, liveliness and replies are free; queries and queryables only
//! in shroud's key space, so zenoh's admin space answers no remote query and
//! no remote queryable can pose as it (but for the host's own processes,
//! whose statuses query their own admin space, [`ADMIN_SPACE`], over
//! loopback).
//! A link matching several subjects is allowed what any of them allows
//! (zenoh 1.10 `access_control.rs`; checked against zenoh in
//! `tests/multihost.rs`).

use super::error::LaunchError;
use super::file::{LaunchFile, NodeSpec, LAUNCHER_NAME};
use super::kind::Direction;
use super::kind::NodeKind;
use super::sectors::sectors_of;
use serde::Serialize;
use shroud_msg::{sector_stream, TopicKind, Topics};
use std::collections::BTreeMap;

/// zenoh's `access_control` configuration section, as plain data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AccessControl {
    pub enabled: bool,
    pub default_permission: &'static str,
    pub rules: Vec<AclRule>,
    pub subjects: Vec<AclSubject>,
    pub policies: Vec<AclPolicy>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AclRule {
    pub id: String,
    pub messages: Vec<&'static str>,
    pub flows: Vec<&'static str>,
    pub permission: &'static str,
    pub key_exprs: Vec<String>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AclSubject {
    pub id: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cert_common_names: Option<Vec<String>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub link_protocols: Option<Vec<&'static str>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interfaces: Option<Vec<&'static str>>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AclPolicy {
    pub id: String,
    pub rules: Vec<String>,
    pub subjects: Vec<String>,
}

/// The messages that publish data.
const PUBLISH: [&str; 2] = ["put", "delete"];
/// The messages that declare interest or answer, allowed to every link.
const DECLARE: [&str; 5] = [
    "declare_subscriber",
    "reply",
    "liveliness_token",
    "liveliness_query",
    "declare_liveliness_subscriber",
];
/// Both directions of a link.
const BOTH: [&str; 2] = ["ingress", "egress"];
/// The loopback interface (Linux), the only one local processes use.
const LOOPBACK: &str = "lo";
/// The admin spaces, which a host's own processes may query (a node asks
/// its own for its drop counts, `@/<zid>/<kind>/metrics`).
pub const ADMIN_SPACE: &str = "@/**";
/// The catch-all subject (no property: every link).
const EVERYONE: &str = "everyone";
/// The local processes' subject.
const LOCAL: &str = "local";

impl LaunchFile {
    /// The keys each host may publish on: its nodes' output streams (a fit
    /// node's sector streams `<name>.s<i>` for its `sectors`), its nodes'
    /// statuses, and its launcher's and router's statuses.
    pub fn keys_by_host(&self) -> Result<BTreeMap<String, Vec<String>>, LaunchError> {
        let topics = Topics::new(&self.namespace).map_err(|e| LaunchError::Invalid {
            field: "namespace".into(),
            reason: e.to_string(),
        })?;
        let key = |kind: TopicKind, name: &str| {
            (topics.key(kind, name)).map_err(|e| LaunchError::Invalid {
                field: format!("{kind}/{name}"),
                reason: e.to_string(),
            })
        };
        let mut keys: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for host in self.hosts.keys() {
            let own = keys.entry(host.clone()).or_default();
            for status in [format!("{LAUNCHER_NAME}.{host}"), format!("router.{host}")] {
                own.push(key(TopicKind::Status, &status)?);
            }
        }
        for node in &self.nodes {
            let Some(host) = &node.host else { continue };
            let own = keys.entry(host.clone()).or_default();
            own.push(key(TopicKind::Status, &node.name)?);
            for wire in node.wires()? {
                if wire.port.direction != Direction::Output {
                    continue;
                }
                let Some(kind) = TopicKind::parse(wire.stream.topic) else {
                    return Err(node.error(format!("{} is not a topic kind", wire.stream.topic)));
                };
                own.push(key(kind, &wire.stream.name)?);
                for sector in 0..sector_count(node) {
                    own.push(key(kind, &sector_stream(&wire.stream.name, sector))?);
                }
            }
        }
        for own in keys.values_mut() {
            own.sort();
            own.dedup();
        }
        Ok(keys)
    }

    /// The access control of host `host`'s router (its launcher or `shroud
    /// router`); `None` when the graph has no TLS, so no identities to
    /// check.
    pub fn access_control(&self, host: &str) -> Result<Option<AccessControl>, LaunchError> {
        self.host(host)?;
        if self.hosts.values().all(|h| h.tls.is_none()) {
            return Ok(None);
        }
        let mut acl = AccessControl {
            enabled: true,
            default_permission: "deny",
            rules: vec![
                // Data goes out to whoever subscribed.
                rule_for("deliver", &PUBLISH, &["egress"], &["**"]),
                // Subscribing, liveliness and replies are free; queries and
                // queryables only in shroud's key space (not zenoh's admin
                // space, `@/...`).
                rule_for("declare", &DECLARE, &BOTH, &["**"]),
                rule_for(
                    "query",
                    &["query", "declare_queryable"],
                    &BOTH,
                    &["shroud/**"],
                ),
            ],
            subjects: vec![subject(EVERYONE, None, None)],
            policies: vec![policy(&["deliver", "declare", "query"], &[EVERYONE])],
        };
        let routers: Vec<String> = (self.hosts.iter())
            .filter(|(_, h)| h.router)
            .map(|(name, _)| name.clone())
            .collect();
        if !routers.is_empty() {
            acl.rules
                .push(rule_for("relay", &PUBLISH, &["ingress"], &["**"]));
            acl.subjects.push(subject("routers", Some(routers), None));
            acl.policies.push(policy(&["relay"], &["routers"]));
        }
        // This host's own processes: only over loopback. Their queries of
        // their own admin space (the drop counts of their statuses) reach
        // the router too, which has nothing to answer: allowed, so that they
        // are not counted as refused. (These processes may publish
        // anything already; they may read the router's admin space too. A
        // few such queries a minute still go on to other routers, which
        // refuse and count them.)
        acl.rules
            .push(rule_for("local", &PUBLISH, &["ingress"], &["**"]));
        acl.rules.push(rule_for(
            "local-admin",
            &["query"],
            &["ingress"],
            &[ADMIN_SPACE],
        ));
        acl.subjects.push(AclSubject {
            interfaces: Some(vec![LOOPBACK]),
            ..subject(LOCAL, None, Some(vec!["tcp"]))
        });
        acl.policies
            .push(policy(&["local", "local-admin"], &[LOCAL]));
        for (name, own) in self.keys_by_host()? {
            let (rule_id, subject_id) = (format!("{name}-publishes"), format!("host-{name}"));
            let own: Vec<&str> = own.iter().map(String::as_str).collect();
            acl.rules
                .push(rule_for(&rule_id, &PUBLISH, &["ingress"], &own));
            acl.subjects
                .push(subject(&subject_id, Some(vec![name]), None));
            acl.policies.push(policy(&[&rule_id], &[&subject_id]));
        }
        Ok(Some(acl))
    }
}

/// How many sector streams a fit node writes besides its whole view
/// (`sectors` N: N x N).
fn sector_count(node: &NodeSpec) -> usize {
    if node.kind != NodeKind::Fit {
        return 0;
    }
    let n = sectors_of(node).unwrap_or(0).clamp(0, 64) as usize;
    n * n
}

fn rule_for(id: &str, messages: &[&'static str], flows: &[&'static str], keys: &[&str]) -> AclRule {
    AclRule {
        id: id.to_owned(),
        messages: messages.to_vec(),
        flows: flows.to_vec(),
        permission: "allow",
        key_exprs: keys.iter().map(|k| (*k).to_owned()).collect(),
    }
}

fn subject(
    id: &str,
    cert_common_names: Option<Vec<String>>,
    link_protocols: Option<Vec<&'static str>>,
) -> AclSubject {
    AclSubject {
        id: id.to_owned(),
        cert_common_names,
        link_protocols,
        interfaces: None,
    }
}

fn policy(rules: &[&str], subjects: &[&str]) -> AclPolicy {
    AclPolicy {
        id: format!("{}-for-{}", rules.join("-"), subjects.join("-")),
        rules: rules.iter().map(|r| (*r).to_owned()).collect(),
        subjects: subjects.iter().map(|s| (*s).to_owned()).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The demo over a sensor host and an arm host around a router host.
    const CELL: &str = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../launch/hosts.toml"
    ));

    fn cell() -> LaunchFile {
        LaunchFile::from_toml_str(CELL).unwrap()
    }

    /// The permission zenoh 1.10 gives an ingress put on `key` over a link
    /// with `common_name` (None: no certificate), `protocol` and
    /// `interface`: allowed when a subject the link matches has an allow
    /// rule for puts whose key expression includes `key`; the default,
    /// deny, otherwise (a model of `access_control.rs` for these rules, which
    /// allow only: exact keys and `**`; tests/multihost.rs checks it against
    /// zenoh).
    fn permits(acl: &AccessControl, link: (Option<&str>, &str, &str), key: &str) -> bool {
        let (common_name, protocol, interface) = link;
        let matches = |s: &AclSubject| {
            let cn = s
                .cert_common_names
                .as_ref()
                .is_none_or(|names| common_name.is_some_and(|cn| names.iter().any(|n| n == cn)));
            let by_protocol = s
                .link_protocols
                .as_ref()
                .is_none_or(|p| p.contains(&protocol));
            let by_interface = s.interfaces.as_ref().is_none_or(|i| i.contains(&interface));
            cn && by_protocol && by_interface
        };
        let includes = |expr: &str| expr == "**" || expr == key;
        let allows = |subject: &AclSubject| {
            (acl.policies
                .iter()
                .filter(|p| p.subjects.contains(&subject.id)))
            .flat_map(|p| p.rules.iter())
            .filter_map(|id| acl.rules.iter().find(|r| &r.id == id))
            .filter(|r| r.messages.contains(&"put"))
            .filter(|r| r.flows.is_empty() || r.flows.contains(&"ingress"))
            .any(|r| r.key_exprs.iter().any(|e| includes(e)))
        };
        assert_eq!(acl.default_permission, "deny");
        acl.subjects.iter().filter(|s| matches(s)).any(allows)
    }

    const LOCAL_LINK: (Option<&str>, &str, &str) = (None, "tcp", "lo");

    fn tls(common_name: &str) -> (Option<&str>, &str, &str) {
        (Some(common_name), "tls", "eth0")
    }

    #[test]
    fn only_local_processes_may_query_the_admin_space() {
        let acl = cell().access_control("arm").unwrap().unwrap();
        let metric_rules: Vec<&AclRule> = (acl.rules.iter())
            .filter(|r| r.key_exprs.contains(&ADMIN_SPACE.to_string()))
            .collect();
        assert_eq!(metric_rules.len(), 1);
        let rule = metric_rules[0];
        assert_eq!(
            (rule.messages.clone(), rule.flows.clone()),
            (vec!["query"], vec!["ingress"])
        );
        let holders: Vec<&AclPolicy> = (acl.policies.iter())
            .filter(|p| p.rules.contains(&rule.id))
            .collect();
        assert_eq!(holders.len(), 1);
        assert_eq!(holders[0].subjects, vec![LOCAL.to_string()]);
        let local = acl.subjects.iter().find(|s| s.id == LOCAL).unwrap();
        assert_eq!(local.interfaces, Some(vec![LOOPBACK]));
        // No other rule lets a query into the admin space.
        let admin = (acl.rules.iter())
            .filter(|r| r.messages.contains(&"query"))
            .flat_map(|r| r.key_exprs.iter())
            .filter(|k| k.starts_with('@') || k.as_str() == "**");
        assert_eq!(admin.collect::<Vec<_>>(), vec![ADMIN_SPACE]);
    }

    #[test]
    fn each_host_publishes_only_its_own_streams() {
        let acl = cell().access_control("arm").unwrap().unwrap();
        let verdict = "shroud/demo/collision/demo_arm";
        let joints = "shroud/demo/joints/demo_arm";
        let surrogate = "shroud/demo/surrogate/spheres";
        // The arm host's own processes publish, over loopback only.
        assert!(permits(&acl, LOCAL_LINK, verdict));
        assert!(permits(&acl, LOCAL_LINK, joints));
        assert!(!permits(&acl, (None, "tcp", "eth0"), verdict));
        // The sensor host's certificate may send its surrogates, never a
        // verdict, a joint state, another node's status or a wildcard.
        assert!(permits(&acl, tls("sensor"), surrogate));
        assert!(permits(
            &acl,
            tls("sensor"),
            "shroud/demo/status/launcher.sensor"
        ));
        for key in [
            verdict,
            joints,
            "shroud/demo/status/guard",
            "shroud/demo/status/router.hub",
            "shroud/demo/collision/*",
            "shroud/demo/**",
            "shroud/demo/cloud/other",
        ] {
            assert!(!permits(&acl, tls("sensor"), key), "{key}");
        }
        // The router relays everything; a stranger's certificate nothing.
        assert!(permits(&acl, tls("hub"), verdict));
        assert!(!permits(&acl, tls("intruder"), surrogate));
        assert!(!permits(&acl, (None, "tls", "eth0"), surrogate));
    }

    #[test]
    fn a_fit_node_owns_exactly_its_sector_streams() {
        let text = (CELL.replace("dir = \"0,0,-1\"", "dir = \"0,0,-1\"\nsectors = 2")).replace(
            "max_clock_offset = 0.001",
            "max_clock_offset = 0.001\nsectors = 2",
        );
        let keys = LaunchFile::from_toml_str(&text)
            .unwrap()
            .keys_by_host()
            .unwrap();
        let sectors: Vec<&String> = keys["sensor"]
            .iter()
            .filter(|k| k.contains("spheres.s"))
            .collect();
        assert_eq!(sectors.len(), 4, "{sectors:?}");
        assert!(keys["sensor"].contains(&"shroud/demo/surrogate/spheres.s3".to_string()));
        assert!(!cell().keys_by_host().unwrap()["sensor"]
            .iter()
            .any(|k| k.contains("spheres.s")));
    }

    #[test]
    fn a_graph_without_tls_has_no_access_control_and_unknown_hosts_are_named() {
        let plain = CELL
            .lines()
            .filter(|l| {
                !l.starts_with("tls") && !l.starts_with("listen") && !l.starts_with("connect")
            })
            .collect::<Vec<_>>()
            .join("\n");
        let file = LaunchFile::from_toml_str(&plain).unwrap();
        assert_eq!(file.access_control("arm").unwrap(), None);
        let error = file.access_control("gripper").unwrap_err().to_string();
        assert!(
            error.contains("\"gripper\" is not a host") && error.contains("arm, hub, sensor"),
            "{error}"
        );
    }

    #[test]
    fn host_mistakes_are_named() {
        let arm_node = "host = \"arm\"\ninputs = { collision";
        let arm_tls = "\ntls = { root_ca = \"certs/ca.pem\", certificate = \"certs/arm.pem\", private_key = \"certs/arm.key\" }";
        let hub_listen = "listen = [\"tls/127.0.0.1:7450\"]";
        let cases = [
            (
                CELL.replace(arm_node, "inputs = { collision"),
                "node \"arm\": names no host",
            ),
            (
                CELL.replace(arm_node, "host = \"gripper\"\ninputs = { collision"),
                "host \"gripper\" is not in [hosts]",
            ),
            (
                CELL.replace(arm_tls, ""),
                "hosts.arm.tls: another host has TLS",
            ),
            (
                CELL.replace(hub_listen, "listen = [\"tcp/127.0.0.1:7450\"]"),
                "hosts.hub.listen: \"tcp/127.0.0.1:7450\" is not a TLS endpoint",
            ),
            (
                CELL.replace("[hosts.arm]", "[hosts.\"a/b\"]"),
                "hosts.a/b.name",
            ),
            (
                CELL.replace("max_clock_offset = 0.001\n", ""),
                "node \"guard\": reads surrogate/spheres from another host: set max_clock_offset",
            ),
        ];
        for (text, expected) in cases {
            let error = LaunchFile::from_toml_str(&text).unwrap_err().to_string();
            assert!(error.contains(expected), "{expected:?} not in {error:?}");
        }
        let one_machine =
            "[[node]]\nname=\"s\"\nkind=\"scanner\"\nhost=\"x\"\noutputs={cloud=\"c\"}\n";
        let error = LaunchFile::from_toml_str(one_machine)
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("names a host, but the file has no [hosts]"),
            "{error}"
        );
    }
}
