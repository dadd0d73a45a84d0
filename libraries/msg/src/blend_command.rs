//! Blend commands: what a dashboard's drag-and-drop (or `shroud blend-cmd`) sends
//! to a `blend` node: drop the child near a point, adjust it, clear it, or commit
//! the blend as the new parent (paper 001, Section 3).

use super::blob::{decode, encode};
use super::error::MessageError;
use super::{check_finite, check_name, check_version, SCHEMA_VERSION};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// What a user does to the child during a blending session (paper 001,
/// Section 3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BlendCommand {
    /// Paste (or move) the child to the parent's surface near `at`; `normal`
    /// overrides the surface normal estimated there. The current local
    /// adjustment is kept, as when a dragged child keeps its orientation.
    Drop { at: DVec3, normal: Option<DVec3> },
    /// Replace the local adjustment (slide, spin, tilt) of the dropped child;
    /// before any drop, it sets the adjustment the next drop uses.
    Adjust(LocalAdjust),
    /// Take the child away: the model is the parent alone.
    Clear,
    /// Make the current blend the new parent (the next drop composes onto it).
    Commit,
}

/// The joystick of Section 3.3 (Fig. 7): four degrees of freedom at the target.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LocalAdjust {
    /// (1) Slide along the (tilted) normal at the centroid.
    pub lift: f64,
    /// (2) Spin about the normal, radians.
    pub spin: f64,
    /// (3) Tilt about the centroid: rotations (radians) about the two tangent
    /// axes `u`, `v` of the normal's deterministic frame.
    pub tilt: [f64; 2],
}

/// One command. `command` is `drop` (needs `at`; `normal` and `part`
/// optional), `adjust` (`lift` in cloud units, `spin` and `tilt` in radians),
/// `clear` or `commit`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BlendCommandMessage {
    pub version: u16,
    pub stamp_ns: u64,
    pub sequence: u64,
    pub command: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub at: Option<[f64; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<[f64; 3]>,
    /// Which of the blend node's parts a drop pastes (a name from its
    /// `blend.parts` status label); absent: the one it holds now.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub part: Option<String>,
    #[serde(default)]
    pub lift: f64,
    #[serde(default)]
    pub spin: f64,
    #[serde(default)]
    pub tilt: [f64; 2],
}

impl BlendCommandMessage {
    pub fn new(stamp_ns: u64, sequence: u64, command: &BlendCommand) -> Self {
        let mut msg = Self {
            version: SCHEMA_VERSION,
            stamp_ns,
            sequence,
            command: String::new(),
            at: None,
            normal: None,
            part: None,
            lift: 0.0,
            spin: 0.0,
            tilt: [0.0; 2],
        };
        msg.command = match command {
            BlendCommand::Drop { at, normal } => {
                msg.at = Some(at.to_array());
                msg.normal = normal.map(|n| n.to_array());
                "drop"
            }
            BlendCommand::Adjust(a) => {
                (msg.lift, msg.spin, msg.tilt) = (a.lift, a.spin, a.tilt);
                "adjust"
            }
            BlendCommand::Clear => "clear",
            BlendCommand::Commit => "commit",
        }
        .to_owned();
        msg
    }

    pub fn to_bytes(&self) -> Result<Vec<u8>, MessageError> {
        encode(self)
    }

    /// The same drop, of the part named `part`.
    pub fn with_part(mut self, part: &str) -> Self {
        self.part = Some(part.to_owned());
        self
    }

    /// Decodes and validates: version, a known command with its fields, finite
    /// numbers, a part name only on a drop.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, MessageError> {
        let msg: Self = decode(bytes)?;
        check_version("blend command", msg.version, SCHEMA_VERSION)?;
        msg.command()?;
        msg.check_part()?;
        Ok(msg)
    }

    /// A part is named with a drop only, and by a valid name.
    pub fn check_part(&self) -> Result<(), MessageError> {
        match &self.part {
            None => Ok(()),
            Some(_) if self.command != "drop" => Err(MessageError::Invalid {
                field: "part",
                reason: format!("only a drop names a part, not {:?}", self.command),
            }),
            Some(name) => check_name("part", name),
        }
    }

    /// The command this message asks for.
    pub fn command(&self) -> Result<BlendCommand, MessageError> {
        let numbers = [self.lift, self.spin, self.tilt[0], self.tilt[1]];
        check_finite("lift, spin, tilt", &numbers)?;
        match self.command.as_str() {
            "drop" => {
                let at = self.at.ok_or_else(|| MessageError::Invalid {
                    field: "at",
                    reason: "a drop needs the point to drop at".into(),
                })?;
                check_finite("at", &at)?;
                if let Some(n) = &self.normal {
                    check_finite("normal", n)?;
                }
                Ok(BlendCommand::Drop {
                    at: DVec3::from(at),
                    normal: self.normal.map(DVec3::from),
                })
            }
            "adjust" => Ok(BlendCommand::Adjust(LocalAdjust {
                lift: self.lift,
                spin: self.spin,
                tilt: self.tilt,
            })),
            "clear" => Ok(BlendCommand::Clear),
            "commit" => Ok(BlendCommand::Commit),
            other => Err(MessageError::Invalid {
                field: "command",
                reason: format!("{other:?} is not drop, adjust, clear or commit"),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_command_round_trips() {
        let commands = [
            BlendCommand::Drop {
                at: DVec3::new(0.5, -1.0, 2.0),
                normal: Some(DVec3::Z),
            },
            BlendCommand::Drop {
                at: DVec3::ZERO,
                normal: None,
            },
            BlendCommand::Adjust(LocalAdjust {
                lift: 0.01,
                spin: 0.5,
                tilt: [0.1, -0.2],
            }),
            BlendCommand::Clear,
            BlendCommand::Commit,
        ];
        for (i, c) in commands.iter().enumerate() {
            let msg = BlendCommandMessage::new(7, i as u64, c);
            let back = BlendCommandMessage::from_bytes(&msg.to_bytes().unwrap()).unwrap();
            assert_eq!(back, msg);
            assert_eq!(back.command().unwrap(), *c);
        }
    }

    #[test]
    fn bad_commands_are_named_errors() {
        let drop = BlendCommand::Drop {
            at: DVec3::ONE,
            normal: None,
        };
        let mut msg = BlendCommandMessage::new(1, 1, &drop);
        msg.at = None;
        assert!(matches!(
            BlendCommandMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::Invalid { field: "at", .. })
        ));
        let mut msg = BlendCommandMessage::new(1, 1, &drop);
        msg.at = Some([0.0, f64::NAN, 0.0]);
        assert!(matches!(
            BlendCommandMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::NonFinite { index: 1, .. })
        ));
        let mut msg = BlendCommandMessage::new(1, 1, &BlendCommand::Clear);
        msg.command = "explode".into();
        assert!(matches!(
            BlendCommandMessage::from_bytes(&msg.to_bytes().unwrap()),
            Err(MessageError::Invalid {
                field: "command",
                ..
            })
        ));
        let named = BlendCommandMessage::new(1, 1, &drop).with_part("half-cylinder");
        let back = BlendCommandMessage::from_bytes(&named.to_bytes().unwrap()).unwrap();
        assert_eq!(back.part.as_deref(), Some("half-cylinder"));
        for (command, part) in [
            (&drop, "a/b"),
            (&drop, ""),
            (&BlendCommand::Clear, "hemisphere"),
        ] {
            let mut msg = BlendCommandMessage::new(1, 1, command);
            msg.part = Some(part.into());
            assert!(matches!(
                BlendCommandMessage::from_bytes(&msg.to_bytes().unwrap()),
                Err(MessageError::Invalid { field: "part", .. })
            ));
        }
        let mut msg = BlendCommandMessage::new(1, 1, &BlendCommand::Clear);
        msg.spin = f64::INFINITY;
        assert!(BlendCommandMessage::from_bytes(&msg.to_bytes().unwrap()).is_err());
        let bytes = msg.to_bytes().unwrap();
        for len in 0..bytes.len() {
            assert!(BlendCommandMessage::from_bytes(&bytes[..len]).is_err());
        }
    }
}
