//! SCIP 2.0 character encoding: each character carries 6 bits (`c - 0x30`),
//! concatenated big-endian into 2-, 3- or 4-character values (SCIP 2.0 spec
//! C-42-03320B §6 "Data Encoding and Decoding"; urg_c `urg_scip_decode()`).

/// The offset added to every 6-bit group (spec §6).
const BASE: u8 = 0x30;

/// The widest value the protocol encodes: 4 characters, 24 bits (timestamps).
pub const MAX_WIDTH: usize = 4;

/// Whether `c` is a valid encoding character (`0x30..=0x6F`, 6 bits above
/// `0x30`).
pub fn is_code_char(c: u8) -> bool {
    (BASE..BASE + 64).contains(&c)
}

/// Decodes 1 to 4 encoded characters into their value, or `None` when the
/// width is out of range or a character is outside `0x30..=0x6F`.
pub fn decode(chars: &[u8]) -> Option<u32> {
    if chars.is_empty() || chars.len() > MAX_WIDTH {
        return None;
    }
    chars.iter().try_fold(0u32, |value, &c| {
        is_code_char(c).then(|| (value << 6) | u32::from(c - BASE))
    })
}

/// Encodes `value` in `width` (1 to 4) characters, or `None` when it does not
/// fit in `6 * width` bits.
pub fn encode(value: u32, width: usize) -> Option<Vec<u8>> {
    if width == 0 || width > MAX_WIDTH || u64::from(value) >= 1u64 << (6 * width) {
        return None;
    }
    Some(
        (0..width)
            .rev()
            .map(|group| BASE + ((value >> (6 * group)) & 0x3F) as u8)
            .collect(),
    )
}
