//! CRC-32 (IEEE 802.3, the checksum of zip and PNG) guarding the binary surrogate
//! format against corruption: it detects every error burst of at most 32 bits, so
//! every single corrupted byte. Computed by the maintained `crc32fast` crate.

/// The CRC-32 of `bytes`.
pub fn crc32(bytes: &[u8]) -> u32 {
    crc32fast::hash(bytes)
}

#[cfg(test)]
mod tests {
    #[test]
    fn matches_the_standard_check_value() {
        assert_eq!(super::crc32(b"123456789"), 0xCBF4_3926);
    }
}
