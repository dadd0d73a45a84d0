//! Surrogates in the binary format (`format::surrogate_from_binary`). Each
//! input is read as given and with its CRC-32 trailer recomputed, so that the
//! fuzzer reaches the validation behind the checksum.

use crate::check::named;
use crate::round_trip::stable;
use shroud_shapes::format::{
    crc32, surrogate_from_binary, surrogate_from_json, surrogate_to_binary, surrogate_to_json,
};

pub fn run(data: &[u8]) {
    decode(data);
    if let Some(body_len) = data.len().checked_sub(4) {
        let mut fixed = data.to_vec();
        let crc = crc32(&data[..body_len]);
        fixed[body_len..].copy_from_slice(&crc.to_le_bytes());
        decode(&fixed);
    }
}

fn decode(data: &[u8]) {
    match surrogate_from_binary(data) {
        Ok(surrogate) => {
            stable(&surrogate, surrogate_to_binary, surrogate_from_binary);
            stable(&surrogate, surrogate_to_json, surrogate_from_json);
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![surrogate_to_binary(&crate::seeds::surrogate())]
}
