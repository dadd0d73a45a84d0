//! The graph a launch file declares: every node's ports checked against its
//! kind, every input fed by a producer (or declared external), and the
//! options that carry the streams' names to each node.

use super::error::LaunchError;
use super::file::{LaunchFile, NodeSpec, StreamNames};
use super::kind::{Direction, FlagStyle, Port};
use super::sectors::{check_sectors_match, check_sectors_policy};
use shroud_msg::{check_name, TopicKind};
use std::collections::BTreeMap;
use std::fmt;

/// A topic of the namespace: `cloud/spheres` is `shroud/<ns>/cloud/spheres`.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Stream {
    pub topic: TopicKindName,
    pub name: String,
}

/// A topic kind's name, ordered for stable output.
pub type TopicKindName = &'static str;

impl fmt::Display for Stream {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.topic, self.name)
    }
}

impl Stream {
    /// Parses `kind/name` (an entry of `external`).
    pub fn parse(text: &str) -> Result<Self, String> {
        let (kind, name) = text
            .split_once('/')
            .ok_or_else(|| format!("{text:?} is not kind/name"))?;
        let topic = TopicKind::parse(kind)
            .ok_or_else(|| format!("{text:?}: {kind:?} is not a topic kind"))?;
        check_name("stream", name).map_err(|e| format!("{text:?}: {e}"))?;
        Ok(Self {
            topic: topic.as_str(),
            name: name.to_owned(),
        })
    }
}

/// A stream read or written by one node through one of its ports.
#[derive(Debug, Clone)]
pub struct Wire<'a> {
    pub port: &'static Port,
    pub stream: Stream,
    pub node: &'a NodeSpec,
}

impl NodeSpec {
    /// The node's ports with the streams the file names for them, in the
    /// order of its kind's port table.
    pub fn wires(&self) -> Result<Vec<Wire<'_>>, LaunchError> {
        self.check_port_keys(Direction::Input)?;
        self.check_port_keys(Direction::Output)?;
        let mut wires = Vec::new();
        for port in self.kind.ports() {
            self.check_port_names(port)?;
            for name in self.names_of(port) {
                wires.push(Wire {
                    port,
                    stream: Stream {
                        topic: port.topic.as_str(),
                        name: name.clone(),
                    },
                    node: self,
                });
            }
        }
        self.check_shared_flags(&wires)?;
        self.check_not_self_fed(&wires)?;
        let key_list = self
            .kind
            .ports()
            .iter()
            .any(|p| p.style == FlagStyle::KeyList);
        if key_list && !wires.iter().any(|w| w.port.style == FlagStyle::KeyList) {
            return Err(self.error(format!(
                "a {} node names the streams it publishes in outputs \
                 (e.g. outputs = {{ cloud = \"spheres\" }})",
                self.kind
            )));
        }
        Ok(wires)
    }

    /// The names the file gives one port: present when required (or when
    /// the setting it goes with is given), one unless it takes several, each
    /// a valid stream name, none twice.
    fn check_port_names(&self, port: &Port) -> Result<(), LaunchError> {
        let names = self.names_of(port);
        let at = format!("{}.{}", port.direction.section(), port.topic);
        if names.is_empty() && port.required {
            return Err(self.error(format!(
                "{at} is required: the {} stream it {} (option --{})",
                port.topic,
                port.direction.verb(),
                port.flag
            )));
        }
        if let Some(setting) = port.with_setting {
            let set = self.settings.contains_key(setting)
                || self.settings.contains_key(&setting.replace('_', "-"));
            if set == names.is_empty() {
                return Err(self.error(format!(
                    "{at} and settings.{setting} go together: name both or neither"
                )));
            }
        }
        if names.len() > 1 && !port.many {
            return Err(self.error(format!(
                "{at} names {} streams; a {} node {} one",
                names.len(),
                self.kind,
                port.direction.verb()
            )));
        }
        let mut seen = std::collections::BTreeSet::new();
        for name in names {
            check_name("stream", name).map_err(|e| self.error(format!("{at}: {e}")))?;
            if !seen.insert(name) {
                return Err(self.error(format!("{at} names {name:?} twice")));
            }
        }
        Ok(())
    }

    /// A node never feeds itself (a blend whose parent is its own output
    /// would wait for ever).
    fn check_not_self_fed(&self, wires: &[Wire<'_>]) -> Result<(), LaunchError> {
        let outputs: Vec<&Stream> = wires
            .iter()
            .filter(|w| w.port.direction == Direction::Output)
            .map(|w| &w.stream)
            .collect();
        match wires
            .iter()
            .find(|w| w.port.direction == Direction::Input && outputs.contains(&&w.stream))
        {
            Some(w) => Err(self.error(format!("reads {} and writes it too", w.stream))),
            None => Ok(()),
        }
    }

    fn names_of(&self, port: &Port) -> &[String] {
        self.table(port.direction)
            .get(port.topic.as_str())
            .map(|n| n.0.as_slice())
            .unwrap_or(&[])
    }

    fn table(&self, direction: Direction) -> &BTreeMap<String, StreamNames> {
        match direction {
            Direction::Input => &self.inputs,
            Direction::Output => &self.outputs,
        }
    }

    /// Every key of `inputs` or `outputs` must be a port of the kind.
    fn check_port_keys(&self, direction: Direction) -> Result<(), LaunchError> {
        for key in self.table(direction).keys() {
            let known = TopicKind::parse(key)
                .and_then(|topic| self.kind.port(direction, topic))
                .is_some();
            if !known {
                let ports: Vec<&str> = self
                    .kind
                    .ports()
                    .iter()
                    .filter(|p| p.direction == direction)
                    .map(|p| p.topic.as_str())
                    .collect();
                let list = if ports.is_empty() {
                    "none".to_owned()
                } else {
                    ports.join(", ")
                };
                return Err(self.error(format!(
                    "{}.{key}: a {} node {} no {key} stream (its {}: {list})",
                    direction.section(),
                    self.kind,
                    direction.verb(),
                    direction.section()
                )));
            }
        }
        Ok(())
    }

    /// Ports that share one option (`--arm` for the guard's joints and
    /// verdicts) must name the same stream.
    fn check_shared_flags(&self, wires: &[Wire<'_>]) -> Result<(), LaunchError> {
        for (i, a) in wires.iter().enumerate() {
            for b in &wires[i + 1..] {
                let shared = a.port.flag == b.port.flag && a.port.style == FlagStyle::Name;
                if shared && !std::ptr::eq(a.port, b.port) && a.stream.name != b.stream.name {
                    return Err(self.error(format!(
                        "{}.{} ({}) and {}.{} ({}) are both --{} and must name the same stream",
                        a.port.direction.section(),
                        a.port.topic,
                        a.stream.name,
                        b.port.direction.section(),
                        b.port.topic,
                        b.stream.name,
                        a.port.flag
                    )));
                }
            }
        }
        Ok(())
    }

    /// The options that name the node's streams, e.g. `--input=spheres`.
    /// Call after the file was validated.
    pub fn port_args(&self) -> Result<Vec<String>, LaunchError> {
        let wires = self.wires()?;
        let mut args = Vec::new();
        let mut key_lists: BTreeMap<&str, Vec<String>> = BTreeMap::new();
        for wire in &wires {
            match wire.port.style {
                FlagStyle::Name => {
                    let arg = format!("--{}={}", wire.port.flag, wire.stream.name);
                    if !args.contains(&arg) {
                        args.push(arg);
                    }
                }
                FlagStyle::KeyList => key_lists
                    .entry(wire.port.flag)
                    .or_default()
                    .push(wire.stream.to_string()),
            }
        }
        for (flag, keys) in key_lists {
            args.push(format!("--{flag}={}", keys.join(",")));
        }
        Ok(args)
    }
}

/// Who feeds an input.
#[derive(Debug, Clone, PartialEq)]
pub enum Source<'a> {
    Node(&'a NodeSpec),
    External,
}

/// One edge of the graph: a stream from its source into a node's input.
#[derive(Debug, Clone)]
pub struct Edge<'a> {
    pub from: Source<'a>,
    pub to: &'a NodeSpec,
    pub stream: Stream,
}

impl LaunchFile {
    /// The streams from outside the file.
    pub fn external_streams(&self) -> Result<Vec<Stream>, LaunchError> {
        self.external
            .iter()
            .map(|text| {
                Stream::parse(text).map_err(|reason| LaunchError::Invalid {
                    field: "external".into(),
                    reason,
                })
            })
            .collect()
    }

    /// Every input with each of its sources, in the file's order of nodes.
    pub fn edges(&self) -> Result<Vec<Edge<'_>>, LaunchError> {
        let external = self.external_streams()?;
        // Each node's ports are checked and resolved once.
        let wired = self
            .nodes
            .iter()
            .map(NodeSpec::wires)
            .collect::<Result<Vec<_>, _>>()?;
        let producers = producers(&wired, &external)?;
        let mut edges = Vec::new();
        for wire in wired.into_iter().flatten() {
            let node = wire.node;
            if wire.port.direction != Direction::Input {
                continue;
            }
            let mut sources: Vec<Source<'_>> = producers
                .get(&wire.stream)
                .map(|list| list.iter().map(|n| Source::Node(n)).collect())
                .unwrap_or_default();
            if external.contains(&wire.stream) {
                sources.push(Source::External);
            }
            if sources.is_empty() {
                return Err(node.error(format!(
                    "input {} has no producer: no node of this file writes it and \
                     `external` does not list it",
                    wire.stream
                )));
            }
            edges.extend(sources.into_iter().map(|from| Edge {
                from,
                to: node,
                stream: wire.stream.clone(),
            }));
        }
        Ok(edges)
    }
}

/// Who writes each stream: one node, except blend commands, which may come
/// from several senders (pages, panels, `shroud blend-cmd` from outside the
/// file).
fn producers<'a>(
    wired: &[Vec<Wire<'a>>],
    external: &[Stream],
) -> Result<BTreeMap<Stream, Vec<&'a NodeSpec>>, LaunchError> {
    let mut producers: BTreeMap<Stream, Vec<&'a NodeSpec>> = BTreeMap::new();
    for wire in wired.iter().flatten() {
        let node = wire.node;
        if wire.port.direction != Direction::Output {
            continue;
        }
        let writers = producers.entry(wire.stream.clone()).or_default();
        writers.push(node);
        if wire.port.topic == TopicKind::Blend {
            continue;
        }
        if writers.len() > 1 {
            return Err(node.error(format!(
                "{} is also written by node {:?}: one producer per stream",
                wire.stream, writers[0].name
            )));
        }
        if external.contains(&wire.stream) {
            return Err(node.error(format!(
                "{} is written here and listed in external",
                wire.stream
            )));
        }
    }
    Ok(producers)
}

/// The graph's checks: ports, shared options, one producer per stream (blend
/// commands may have several, `external` among them), a producer for every
/// input, and a guard's `sectors` the same as its fit nodes' (and only under
/// the Stop policy for unseen space).
pub fn check_graph(file: &LaunchFile) -> Result<(), LaunchError> {
    file.nodes.iter().try_for_each(check_sectors_policy)?;
    for edge in file.edges()? {
        if let Source::Node(writer) = edge.from {
            check_sectors_match(edge.to, writer, &edge.stream)?;
        }
    }
    Ok(())
}
