//! A blend command as a viewer sends it in JSON (the dashboard's `blend`
//! frame, a Foxglove client's `/shroud/blend` message): the fields of a
//! [`BlendCommandMessage`] but its version, stamp and sequence, which the node
//! that forwards it sets. Checked by the rules every blend command obeys.

use super::BlendCommand;
use super::{BlendCommandMessage, MessageError, SCHEMA_VERSION};
use serde::Deserialize;

/// Longest JSON blend request a node reads (one is a few hundred bytes).
pub const MAX_REQUEST_BYTES: usize = 16 * 1024;

/// See the module documentation; unknown fields are ignored.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct BlendRequest {
    /// `drop`, `adjust`, `clear` or `commit`.
    pub command: String,
    #[serde(default)]
    pub part: Option<String>,
    #[serde(default)]
    pub at: Option<[f64; 3]>,
    #[serde(default)]
    pub normal: Option<[f64; 3]>,
    #[serde(default)]
    pub lift: f64,
    #[serde(default)]
    pub spin: f64,
    #[serde(default)]
    pub tilt: [f64; 2],
}

impl BlendRequest {
    /// Decodes a JSON object, refusing one longer than [`MAX_REQUEST_BYTES`].
    pub fn from_json(bytes: &[u8]) -> Result<Self, MessageError> {
        if bytes.len() > MAX_REQUEST_BYTES {
            return Err(MessageError::Invalid {
                field: "blend request",
                reason: format!("{} bytes, at most {MAX_REQUEST_BYTES}", bytes.len()),
            });
        }
        serde_json::from_slice(bytes)
            .map_err(|e| MessageError::Malformed(format!("blend request JSON: {e}")))
    }

    /// The command and the part it names, checked by
    /// [`BlendCommandMessage::command`] and [`BlendCommandMessage::check_part`].
    pub fn checked(self) -> Result<(BlendCommand, Option<String>), MessageError> {
        let msg = BlendCommandMessage {
            version: SCHEMA_VERSION,
            stamp_ns: 0,
            sequence: 0,
            command: self.command,
            at: self.at,
            normal: self.normal,
            part: self.part,
            lift: self.lift,
            spin: self.spin,
            tilt: self.tilt,
        };
        let command = msg.command()?;
        msg.check_part()?;
        Ok((command, msg.part))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn checked(text: &str) -> Result<(BlendCommand, Option<String>), MessageError> {
        BlendRequest::from_json(text.as_bytes())?.checked()
    }

    #[test]
    fn requests_decode_to_checked_commands() {
        let (command, part) =
            checked(r#"{"command":"drop","at":[1,2,3],"part":"hemisphere","extra":1}"#).unwrap();
        assert_eq!(
            command,
            BlendCommand::Drop {
                at: DVec3::new(1.0, 2.0, 3.0),
                normal: None
            }
        );
        assert_eq!(part.as_deref(), Some("hemisphere"));
        assert_eq!(
            checked(r#"{"command":"commit"}"#).unwrap().0,
            BlendCommand::Commit
        );
    }

    #[test]
    fn bad_requests_are_named_errors() {
        for bad in [
            "",
            "[]",
            "{}",
            "not json",
            r#"{"command":"drop"}"#,
            r#"{"command":"explode"}"#,
            r#"{"command":"drop","at":[1,2]}"#,
            r#"{"command":"clear","part":"hemisphere"}"#,
            r#"{"command":"drop","at":[0,0,0],"part":"../etc"}"#,
            r#"{"command":"adjust","lift":1e999}"#,
        ] {
            assert!(checked(bad).is_err(), "{bad}");
        }
        let long = format!(
            r#"{{"command":"clear","pad":"{}"}}"#,
            "x".repeat(MAX_REQUEST_BYTES)
        );
        assert!(matches!(
            checked(&long),
            Err(MessageError::Invalid {
                field: "blend request",
                ..
            })
        ));
    }
}
