//! Who may publish what, from the graph file: zenoh's access control for one
//! host, so that a stranger holding another host's certificate cannot
//! publish a verdict, a joint state or a surrogate it does not own.
//!
//! Every stream a node of the file writes, and every node's status, is
//! denied to every link, then allowed to the links that carry its producer:
//! the producing host's certificate (by common name, which `shroud certs`
//! sets to the host's name), the router hosts' (they relay), and, on the
//! producer's own host, its local processes (plain `tcp` links, which only
//! loopback carries when the graph runs TLS between hosts). Everything else
//! (subscriptions, queries, liveliness, streams from outside the file) keeps
//! zenoh's default, allow.
//!
//! How zenoh 1.10 decides (`access_control.rs`, checked by
//! `tests/multihost.rs`): each subject a link matches gives deny if one of
//! its rules denies the key, allow if one allows it, and the default if none
//! names it; the message passes if any subject gives allow. So every subject
//! names every protected key, allowing its own and denying the rest.

use super::error::LaunchError;
use super::file::LaunchFile;
use super::kind::Direction;
use serde::Serialize;
use shroud_msg::{TopicKind, Topics};
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
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AclPolicy {
    pub id: String,
    pub rules: Vec<String>,
    pub subjects: Vec<String>,
}

/// The messages that publish data.
const PUBLISH: [&str; 2] = ["put", "delete"];
/// The catch-all subject (no property: every link).
const EVERYONE: &str = "everyone";
/// The local processes' subject.
const LOCAL: &str = "local";

impl LaunchFile {
    /// The key expressions each host's nodes publish on (their output
    /// streams, a fit node's sectors included, and their status).
    pub fn keys_by_host(&self) -> Result<BTreeMap<String, Vec<String>>, LaunchError> {
        let topics = Topics::new(&self.namespace).map_err(|e| LaunchError::Invalid {
            field: "namespace".into(),
            reason: e.to_string(),
        })?;
        let key = |kind: TopicKind, name: &str| format!("{}/{kind}/{name}", topics_root(&topics));
        let mut keys: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for node in &self.nodes {
            let Some(host) = &node.host else { continue };
            let own = keys.entry(host.clone()).or_default();
            own.push(key(TopicKind::Status, &node.name));
            for wire in node.wires()? {
                if wire.port.direction != Direction::Output {
                    continue;
                }
                let kind = TopicKind::parse(wire.stream.topic).expect("a port's topic kind");
                own.push(key(kind, &wire.stream.name));
                if kind == TopicKind::Surrogate {
                    // A fit node with sectors also writes `<name>.s<i>`
                    // (`shroud_msg::sector_stream`); `$*` is zenoh's
                    // wildcard within a chunk.
                    own.push(key(kind, &format!("{}.s$*", wire.stream.name)));
                }
            }
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
        let keys = self.keys_by_host()?;
        let every_key: Vec<String> = keys.values().flatten().cloned().collect();
        let mut acl = AccessControl {
            enabled: true,
            default_permission: "allow",
            rules: vec![rule("deny-streams", "deny", every_key.clone())],
            subjects: vec![subject(EVERYONE, None, None)],
            policies: vec![policy("deny-streams", EVERYONE)],
        };
        let routers: Vec<String> = (self.hosts.iter())
            .filter(|(_, h)| h.router)
            .map(|(name, _)| name.clone())
            .collect();
        if !routers.is_empty() {
            acl.rules.push(rule("relay", "allow", every_key.clone()));
            acl.subjects.push(subject("routers", Some(routers), None));
            acl.policies.push(policy("relay", "routers"));
        }
        for (name, own) in &keys {
            // A subject a link matches that has no rule for a key gives
            // the default (allow), and any allowing subject wins: so each
            // host's subject denies every stream but its own, explicitly.
            let others: Vec<String> = (every_key.iter())
                .filter(|k| !own.contains(k))
                .cloned()
                .collect();
            let (allow, deny) = (format!("{name}-streams"), format!("not-{name}-streams"));
            acl.rules.push(rule(&allow, "allow", own.clone()));
            let mut rules = vec![allow];
            if !others.is_empty() {
                acl.rules.push(rule(&deny, "deny", others));
                rules.push(deny);
            }
            let mut subjects = vec![format!("host-{name}")];
            acl.subjects
                .push(subject(&subjects[0], Some(vec![name.clone()]), None));
            if name == host {
                acl.subjects.push(subject(LOCAL, None, Some(vec!["tcp"])));
                subjects.push(LOCAL.to_owned());
            }
            acl.policies.push(AclPolicy {
                id: format!("{name}-publishes"),
                rules,
                subjects,
            });
        }
        Ok(Some(acl))
    }
}

fn topics_root(topics: &Topics) -> String {
    topics.all().trim_end_matches("/**").to_owned()
}

fn rule(id: &str, permission: &'static str, key_exprs: Vec<String>) -> AclRule {
    AclRule {
        id: id.to_owned(),
        messages: PUBLISH.to_vec(),
        flows: vec!["ingress"],
        permission,
        key_exprs,
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
    }
}

fn policy(rule: &str, subject: &str) -> AclPolicy {
    AclPolicy {
        id: format!("{rule}-for-{subject}"),
        rules: vec![rule.to_owned()],
        subjects: vec![subject.to_owned()],
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

    /// The permission zenoh 1.10 gives a put on `key` over a link with
    /// `common_name` (None: no certificate) and `protocol`: each matched
    /// subject gives deny if a rule of its denies, allow if one allows, the
    /// default if none applies; any allow passes (a model of
    /// `access_control.rs` that tests/multihost.rs checks against zenoh, for
    /// the rules built here: exact keys and `$*` only at a chunk's end).
    fn permits(acl: &AccessControl, common_name: Option<&str>, protocol: &str, key: &str) -> bool {
        let matches = |s: &AclSubject| {
            let cn = s
                .cert_common_names
                .as_ref()
                .is_none_or(|names| common_name.is_some_and(|cn| names.iter().any(|n| n == cn)));
            let link = s
                .link_protocols
                .as_ref()
                .is_none_or(|p| p.contains(&protocol));
            cn && link
        };
        let includes = |expr: &str| match expr.strip_suffix("$*") {
            Some(prefix) => key.starts_with(prefix) && !key[prefix.len()..].contains('/'),
            None => expr == key,
        };
        let default = acl.default_permission == "allow";
        let verdicts: Vec<bool> = (acl.subjects.iter().filter(|s| matches(s)))
            .map(|subject| {
                let rules = acl
                    .policies
                    .iter()
                    .filter(|p| p.subjects.contains(&subject.id));
                let applicable: Vec<&AclRule> = rules
                    .flat_map(|p| p.rules.iter())
                    .filter_map(|id| acl.rules.iter().find(|r| &r.id == id))
                    .filter(|r| r.key_exprs.iter().any(|e| includes(e)))
                    .collect();
                match applicable.is_empty() {
                    true => default,
                    false => applicable.iter().all(|r| r.permission == "allow"),
                }
            })
            .collect();
        match verdicts.is_empty() {
            true => default,
            false => verdicts.contains(&true),
        }
    }

    #[test]
    fn each_host_publishes_only_its_own_streams() {
        let acl = cell().access_control("arm").unwrap().unwrap();
        let verdict = "shroud/demo/collision/demo_arm";
        let joints = "shroud/demo/joints/demo_arm";
        let surrogate = "shroud/demo/surrogate/spheres";
        // The arm host's own processes publish its verdicts and joints.
        assert!(permits(&acl, None, "tcp", verdict));
        assert!(permits(&acl, None, "tcp", joints));
        // ...but not the sensor host's surrogates.
        assert!(!permits(&acl, None, "tcp", surrogate));
        // The sensor host's certificate may send surrogates, sectors too,
        // never a verdict or joint state.
        assert!(permits(&acl, Some("sensor"), "tls", surrogate));
        assert!(permits(
            &acl,
            Some("sensor"),
            "tls",
            "shroud/demo/surrogate/spheres.s3"
        ));
        assert!(!permits(&acl, Some("sensor"), "tls", verdict));
        assert!(!permits(&acl, Some("sensor"), "tls", joints));
        assert!(!permits(
            &acl,
            Some("sensor"),
            "tls",
            "shroud/demo/status/guard"
        ));
        // The router relays everything; a stranger's certificate nothing.
        assert!(permits(&acl, Some("hub"), "tls", verdict));
        assert!(!permits(&acl, Some("intruder"), "tls", surrogate));
        // What the file does not produce keeps zenoh's default.
        assert!(permits(
            &acl,
            Some("sensor"),
            "tls",
            "shroud/demo/cloud/other"
        ));
    }

    #[test]
    fn the_router_host_lets_no_local_process_publish_a_stream() {
        let acl = cell().access_control("hub").unwrap().unwrap();
        assert!(!acl.subjects.iter().any(|s| s.id == LOCAL));
        assert!(!permits(
            &acl,
            None,
            "tcp",
            "shroud/demo/collision/demo_arm"
        ));
        assert!(permits(
            &acl,
            Some("arm"),
            "tls",
            "shroud/demo/collision/demo_arm"
        ));
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
