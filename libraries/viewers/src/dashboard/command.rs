//! What a browser may ask of the dashboard node (docs/dashboard-protocol.md, "Browser to
//! server"), decoded and checked: blend commands, validated exactly as a
//! `BlendCommandMessage` from any other sender is, and per-browser options.

use super::error::DashboardError;
use serde::Deserialize;
use shroud_msg::BlendRequest;
use shroud_shapes::blend::BlendCommand;

/// Longest text frame a browser may send (a command is a few hundred bytes).
pub const MAX_COMMAND_BYTES: usize = 16 * 1024;

/// A browser's request.
#[derive(Debug, Clone, PartialEq)]
pub enum BrowserCommand {
    /// Publish this blend command; `id` is echoed in the `blend_result`.
    Blend {
        id: u64,
        command: BlendCommand,
        part: Option<String>,
    },
    /// This browser's point budget per cloud.
    Options { point_budget: u64 },
}

#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
enum Wire {
    Blend {
        #[serde(default)]
        id: u64,
        #[serde(flatten)]
        request: BlendRequest,
    },
    Options {
        point_budget: u64,
    },
}

impl BrowserCommand {
    /// Decodes a text frame. Blend commands are checked by
    /// [`BlendRequest::checked`], the rules every blend command obeys.
    pub fn parse(text: &str) -> Result<Self, DashboardError> {
        if text.len() > MAX_COMMAND_BYTES {
            return Err(DashboardError::CommandTooLong {
                len: text.len(),
                max: MAX_COMMAND_BYTES,
            });
        }
        let wire: Wire =
            serde_json::from_str(text).map_err(|e| DashboardError::Command(e.to_string()))?;
        match wire {
            Wire::Options { point_budget } => Ok(Self::Options { point_budget }),
            Wire::Blend { id, request } => {
                let (command, part) =
                    request
                        .checked()
                        .map_err(|e| DashboardError::CommandField {
                            field: "blend",
                            reason: e.to_string(),
                        })?;
                Ok(Self::Blend { id, command, part })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn commands_decode_as_documented() {
        let drop = BrowserCommand::parse(
            r#"{"type":"blend","id":7,"command":"drop","part":"hemisphere","at":[1,2,3],"extra":1}"#,
        )
        .unwrap();
        assert_eq!(
            drop,
            BrowserCommand::Blend {
                id: 7,
                command: BlendCommand::Drop {
                    at: DVec3::new(1.0, 2.0, 3.0),
                    normal: None
                },
                part: Some("hemisphere".into()),
            }
        );
        let adjust = BrowserCommand::parse(
            r#"{"type":"blend","command":"adjust","spin":0.5,"tilt":[0.1,0]}"#,
        )
        .unwrap();
        assert!(
            matches!(adjust, BrowserCommand::Blend { id: 0, command: BlendCommand::Adjust(a), .. } if a.spin == 0.5 && a.tilt == [0.1, 0.0])
        );
        assert_eq!(
            BrowserCommand::parse(r#"{"type":"options","point_budget":2000}"#).unwrap(),
            BrowserCommand::Options { point_budget: 2000 }
        );
    }

    #[test]
    fn bad_commands_are_named_errors() {
        for bad in [
            "",
            "[]",
            "{}",
            r#"{"type":"launch"}"#,
            r#"{"type":"blend","command":"drop"}"#,
            r#"{"type":"blend","command":"explode"}"#,
            r#"{"type":"blend","command":"drop","at":[1,2]}"#,
            r#"{"type":"blend","command":"clear","part":"hemisphere"}"#,
            r#"{"type":"blend","command":"drop","at":[0,0,0],"part":"../etc"}"#,
            r#"{"type":"blend","command":"adjust","lift":1e999}"#,
            r#"{"type":"options","point_budget":-1}"#,
        ] {
            assert!(BrowserCommand::parse(bad).is_err(), "{bad}");
        }
        let long = format!(
            r#"{{"type":"options","point_budget":1,"pad":"{}"}}"#,
            "x".repeat(MAX_COMMAND_BYTES)
        );
        assert!(matches!(
            BrowserCommand::parse(&long),
            Err(DashboardError::CommandTooLong { .. })
        ));
    }
}
