//! What browsers send the dashboard (`BrowserCommand::parse`): JSON text
//! frames, blend commands checked as every blend command is.

use crate::check::named;
use shroud_viewers::dashboard::{BrowserCommand, MAX_COMMAND_BYTES};

pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match BrowserCommand::parse(text) {
        Ok(_) => assert!(
            text.len() <= MAX_COMMAND_BYTES,
            "a command over the size limit was taken"
        ),
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    [
        r#"{"type":"blend","id":3,"command":"drop","at":[0.1,0.2,0.3],"normal":[0,0,1],"part":"bracket"}"#,
        r#"{"type":"blend","command":"adjust","lift":0.01,"spin":0.5,"tilt":[0.1,-0.1]}"#,
        r#"{"type":"blend","command":"clear"}"#,
        r#"{"type":"options","point_budget":200000}"#,
    ]
    .iter()
    .map(|t| t.as_bytes().to_vec())
    .collect()
}
