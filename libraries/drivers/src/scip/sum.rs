//! The SCIP 2.0 line sum: the low 6 bits of the byte sum of a line, plus
//! `0x30`, sent as the line's last character (spec C-42-03320B §7
//! "Communication Format"; urg_c `scip_checksum()`).

/// The sum character of `bytes`.
pub fn line_sum(bytes: &[u8]) -> u8 {
    let total = bytes.iter().fold(0u8, |acc, &b| acc.wrapping_add(b));
    (total & 0x3F) + 0x30
}

/// A line whose last character is a correct sum over everything before it:
/// the line without its sum, or `None`.
pub fn strip_sum(line: &[u8]) -> Option<&[u8]> {
    let (&sum, body) = line.split_last()?;
    (!body.is_empty() && line_sum(body) == sum).then_some(body)
}

/// A parameter line (`PP`, `VV`, `II`: `KEY:VALUE;S`) whose sum is correct
/// over either all bytes before it or all but the `;` before it: the spec's
/// example lines sum without the `;` (`DMIN:20;4`), some firmware sums with it,
/// and urg_c `scip_response()` accepts both. Returns the line without its sum
/// character (the `;` is kept), or `None`.
pub fn strip_parameter_sum(line: &[u8]) -> Option<&[u8]> {
    let (&sum, body) = line.split_last()?;
    let short = body.split_last().map(|(_, rest)| rest).unwrap_or(&[]);
    (!body.is_empty() && (line_sum(body) == sum || line_sum(short) == sum)).then_some(body)
}
