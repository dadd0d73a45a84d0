//! What a Foxglove client publishes on `/shroud/blend` (`BlendRequest`, JSON):
//! a request either gives a checked blend command or a named error, and one
//! over the size limit is never taken.

use crate::check::named;
use shroud_msg::{BlendRequest, MAX_REQUEST_BYTES};

pub fn run(data: &[u8]) {
    match BlendRequest::from_json(data).and_then(|request| request.checked()) {
        Ok(_) => assert!(
            data.len() <= MAX_REQUEST_BYTES,
            "a request over the size limit was taken"
        ),
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    [
        r#"{"command":"drop","at":[0.1,-0.2,0.75],"part":"hemisphere"}"#,
        r#"{"command":"drop","at":[0,0,1],"normal":[0,0,1]}"#,
        r#"{"command":"adjust","lift":0.01,"spin":0.3,"tilt":[0.1,-0.1]}"#,
        r#"{"command":"commit"}"#,
        r#"{"command":"clear"}"#,
    ]
    .iter()
    .map(|t| t.as_bytes().to_vec())
    .collect()
}
