//! The encapsulation header before a CDR payload (OMG DDS-RTPS 2.5 §10.2:
//! a 2-byte representation identifier and 2 bytes of options).

use super::error::CdrError;

/// The header's length; CDR alignment counts from the byte after it.
pub const HEADER_LEN: usize = 4;
/// `CDR_LE`: classic CDR, little endian (what every rmw writes on x86 and ARM).
pub const CDR_LE: [u8; 2] = [0x00, 0x01];
/// `CDR_BE`: classic CDR, big endian (decoded, never written).
pub const CDR_BE: [u8; 2] = [0x00, 0x00];

/// The byte order a payload's header announces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Endianness {
    Little,
    Big,
}

/// Reads the header of `bytes`. The options (bytes 2 and 3) are ignored:
/// XCDR1 defines none that change the body (Fast-DDS puts the count of
/// trailing padding bytes there, see [`super::MAX_TRAILING_PADDING`]).
pub fn read_header(bytes: &[u8]) -> Result<Endianness, CdrError> {
    let Some(identifier) = bytes.get(..2) else {
        return Err(CdrError::Truncated {
            field: "encapsulation header",
            needed: HEADER_LEN,
            remaining: bytes.len(),
        });
    };
    let endianness = match [identifier[0], identifier[1]] {
        CDR_LE => Endianness::Little,
        CDR_BE => Endianness::Big,
        other => return Err(CdrError::Header { identifier: other }),
    };
    if bytes.len() < HEADER_LEN {
        return Err(CdrError::Truncated {
            field: "encapsulation options",
            needed: HEADER_LEN,
            remaining: bytes.len(),
        });
    }
    Ok(endianness)
}

/// The header [`super::CdrWriter`] writes: `CDR_LE` and no options.
pub fn little_endian_header() -> [u8; HEADER_LEN] {
    [CDR_LE[0], CDR_LE[1], 0, 0]
}
