//! Encodes Benewake data frames: the standard 9-byte frame `59 59 DL DH SL
//! SH TL TH CS`, CS the low byte of the sum of bytes 0..8 (TFmini Plus /
//! TFmini-S / TF-Luna manuals §5.3, "Standard data output format"), and the
//! "Pix" string format, metres with two decimals then `\r\n`.

/// The frame header byte (ASCII 'Y'), sent twice.
pub(crate) const HEADER: u8 = 0x59;
/// Bytes in a standard frame.
pub(crate) const FRAME_LEN: usize = 9;

/// The low byte of the sum of `bytes`.
pub(crate) fn sum8(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0u8, |acc, b| acc.wrapping_add(*b))
}

/// A standard frame; `tail` fills bytes 6 and 7 (LE). `broken` makes the
/// checksum wrong.
pub(crate) fn standard(distance: u16, strength: u16, tail: u16, broken: bool) -> [u8; FRAME_LEN] {
    let [d0, d1] = distance.to_le_bytes();
    let [s0, s1] = strength.to_le_bytes();
    let [t0, t1] = tail.to_le_bytes();
    let mut frame = [HEADER, HEADER, d0, d1, s0, s1, t0, t1, 0];
    frame[8] = sum8(&frame[..8]) ^ if broken { 0xFF } else { 0 };
    frame
}

/// The raw temperature field: (°C + 256) × 8, saturating to u16.
pub(crate) fn temperature_raw(celsius: f64) -> u16 {
    let raw = ((celsius + 256.0) * 8.0).round();
    if raw.is_nan() {
        0
    } else {
        raw.clamp(0.0, f64::from(u16::MAX)) as u16
    }
}

/// The Pix string: `metres` with two decimals, then `\r\n`.
pub(crate) fn pix(metres: f64) -> Vec<u8> {
    format!("{metres:.2}\r\n").into_bytes()
}
