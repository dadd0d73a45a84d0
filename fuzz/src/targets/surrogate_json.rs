//! Surrogates as JSON (`format::surrogate_from_json`), validated on read.
//! A decoded surrogate re-encodes to the same JSON, and survives the binary
//! format (which leaves out the fit statistics) unchanged otherwise.

use crate::check::named;
use crate::round_trip::stable;
use shroud_shapes::format::{
    surrogate_from_binary, surrogate_from_json, surrogate_to_binary, surrogate_to_json,
};

pub fn run(data: &[u8]) {
    match surrogate_from_json(data) {
        Ok(surrogate) => {
            stable(&surrogate, surrogate_to_json, surrogate_from_json);
            stable(&surrogate, surrogate_to_binary, surrogate_from_binary);
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![surrogate_to_json(&crate::seeds::surrogate())]
}
