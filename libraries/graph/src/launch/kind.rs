//! The node kinds a launch file may name, and the topics each reads and writes.

use serde::Deserialize;
use shroud_msg::TopicKind;
use std::fmt;

/// A node program: `shroud node <kind>`. The `shroud` binary checks that this
/// list is exactly its node subcommands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NodeKind {
    Scanner,
    Fit,
    Guard,
    Arm,
    Serial,
    Can,
    Blend,
    Smooth,
    DeviceSim,
    Dashboard,
    Foxglove,
    Ros2,
    Record,
    Replay,
}

/// Whether a port is read or written by its node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    Input,
    Output,
}

impl Direction {
    /// The launch file's table for this direction.
    pub fn section(self) -> &'static str {
        match self {
            Self::Input => "inputs",
            Self::Output => "outputs",
        }
    }

    pub fn verb(self) -> &'static str {
        match self {
            Self::Input => "reads",
            Self::Output => "writes",
        }
    }
}

/// How a port's topic names reach the node's command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FlagStyle {
    /// `--flag NAME`, once per name.
    Name,
    /// One `--flag KIND/NAME,KIND/NAME` for every port that shares the flag
    /// (the replay's topic filter).
    KeyList,
}

/// One input or output of a node kind: a topic kind and the option that names
/// the stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Port {
    pub topic: TopicKind,
    pub direction: Direction,
    /// The node's option (without `--`) that carries the stream's name. Ports
    /// that share an option must name the same stream (the guard reads and
    /// writes one arm's topics).
    pub flag: &'static str,
    pub style: FlagStyle,
    /// Several streams (the guard's views).
    pub many: bool,
    /// The launch file must name it.
    pub required: bool,
    /// The node reads or writes the port only when this setting is given
    /// (a mount's joint): the file names both or neither.
    pub with_setting: Option<&'static str>,
}

const fn port(topic: TopicKind, direction: Direction, flag: &'static str) -> Port {
    Port {
        topic,
        direction,
        flag,
        style: FlagStyle::Name,
        many: false,
        required: true,
        with_setting: None,
    }
}

const fn optional(p: Port) -> Port {
    Port {
        required: false,
        ..p
    }
}

const fn many(p: Port) -> Port {
    Port { many: true, ..p }
}

const fn replayed(topic: TopicKind) -> Port {
    Port {
        topic,
        direction: Direction::Output,
        flag: "topics",
        style: FlagStyle::KeyList,
        many: true,
        required: false,
        with_setting: None,
    }
}

use Direction::{Input, Output};
use TopicKind::{Blend, Cloud, Collision, Joints, Smooth, Surrogate};

const SCANNER: &[Port] = &[port(Cloud, Output, "stream")];
const FIT: &[Port] = &[
    port(Cloud, Input, "input"),
    port(Surrogate, Output, "output"),
];
const GUARD: &[Port] = &[
    many(port(Surrogate, Input, "surrogate")),
    port(Joints, Input, "arm"),
    port(Collision, Output, "arm"),
];
const ARM: &[Port] = &[port(Collision, Input, "arm"), port(Joints, Output, "arm")];
const SERIAL: &[Port] = &[
    port(Cloud, Output, "stream"),
    Port {
        with_setting: Some("mount_joint"),
        ..optional(port(Joints, Input, "joints"))
    },
];
const CAN: &[Port] = &[port(Cloud, Output, "stream")];
const BLEND: &[Port] = &[
    optional(port(Cloud, Input, "parent-stream")),
    port(Blend, Input, "stream"),
    port(Cloud, Output, "output"),
];
const SMOOTH: &[Port] = &[port(Cloud, Input, "input"), port(Smooth, Output, "output")];
const VIEWER: &[Port] = &[optional(port(Blend, Output, "blend-stream"))];
const ROS2: &[Port] = &[
    optional(port(Cloud, Output, "cloud")),
    optional(port(Joints, Output, "arm")),
    optional(port(Collision, Input, "arm")),
    optional(many(port(Surrogate, Input, "surrogate"))),
    optional(many(port(Cloud, Input, "publish-cloud"))),
];
const REPLAY: &[Port] = &[
    replayed(Cloud),
    replayed(Surrogate),
    replayed(Joints),
    replayed(Collision),
    replayed(Blend),
    replayed(Smooth),
];

impl NodeKind {
    pub const ALL: [NodeKind; 14] = [
        Self::Scanner,
        Self::Fit,
        Self::Guard,
        Self::Arm,
        Self::Serial,
        Self::Can,
        Self::Blend,
        Self::Smooth,
        Self::DeviceSim,
        Self::Dashboard,
        Self::Foxglove,
        Self::Ros2,
        Self::Record,
        Self::Replay,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            Self::Scanner => "scanner",
            Self::Fit => "fit",
            Self::Guard => "guard",
            Self::Arm => "arm",
            Self::Serial => "serial",
            Self::Can => "can",
            Self::Blend => "blend",
            Self::Smooth => "smooth",
            Self::DeviceSim => "device-sim",
            Self::Dashboard => "dashboard",
            Self::Foxglove => "foxglove",
            Self::Ros2 => "ros2",
            Self::Record => "record",
            Self::Replay => "replay",
        }
    }

    /// The topics the kind reads and writes, besides its own status and
    /// presence, which every node publishes.
    pub fn ports(self) -> &'static [Port] {
        match self {
            Self::Scanner => SCANNER,
            Self::Fit => FIT,
            Self::Guard => GUARD,
            Self::Arm => ARM,
            Self::Serial => SERIAL,
            Self::Can => CAN,
            Self::Blend => BLEND,
            Self::Smooth => SMOOTH,
            // An emulator talks to its driver over a pseudo-terminal, not zenoh.
            Self::DeviceSim => &[],
            Self::Dashboard | Self::Foxglove => VIEWER,
            Self::Ros2 => ROS2,
            Self::Record => &[],
            Self::Replay => REPLAY,
        }
    }

    /// Kinds that subscribe to every topic of the namespace (viewers and the
    /// recorder): they need no producer. Viewers also send blend commands to
    /// the blend node they find when their `blend` output is not named, which
    /// is why blend commands may have several producers.
    pub fn observes_everything(self) -> bool {
        matches!(self, Self::Dashboard | Self::Foxglove | Self::Record)
    }

    /// The port of `direction` carrying `topic`, if the kind has one.
    pub fn port(self, direction: Direction, topic: TopicKind) -> Option<&'static Port> {
        self.ports()
            .iter()
            .find(|p| p.direction == direction && p.topic == topic)
    }
}

impl fmt::Display for NodeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_is_listed_once_and_names_parse_back() {
        for kind in NodeKind::ALL {
            let text = format!("k = {:?}", kind.as_str());
            #[derive(Deserialize)]
            struct K {
                k: NodeKind,
            }
            let parsed: K = toml::from_str(&text).unwrap();
            assert_eq!(parsed.k, kind);
        }
        let mut sorted = NodeKind::ALL.to_vec();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), NodeKind::ALL.len());
    }

    #[test]
    fn ports_of_one_kind_and_direction_carry_distinct_topics() {
        for kind in NodeKind::ALL {
            for (i, a) in kind.ports().iter().enumerate() {
                for b in &kind.ports()[i + 1..] {
                    assert!(
                        a.direction != b.direction || a.topic != b.topic,
                        "{kind}: two {:?} ports of {}",
                        a.direction,
                        a.topic
                    );
                    if a.flag == b.flag && a.style == FlagStyle::Name {
                        assert!(!a.many && !b.many, "{kind}: --{} is shared", a.flag);
                    }
                }
            }
        }
    }
}
