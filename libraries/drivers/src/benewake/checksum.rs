//! The one checksum Benewake uses on both its data frames and its command
//! frames: the low byte of the sum of every byte before the checksum.

/// Low 8 bits of the sum of `bytes` (TFmini Plus manual §7.3 "Checksum: sum of
/// all bytes from Head to payload. Lower 8 bits"; the same rule closes the
/// 9-byte data frame, TFmini-S manual §6.1 / sensors.md §1.3).
pub fn sum8(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0u8, |sum, byte| sum.wrapping_add(*byte))
}
