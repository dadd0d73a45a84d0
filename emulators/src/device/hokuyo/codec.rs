//! SCIP character encoding and line sums, and a builder for reply messages.
//!
//! Encoding (spec §6, pp. 6-8): a value is cut into 6-bit groups, most
//! significant first, and 0x30 is added to each ("1Dh" = 5432). The sum of a
//! line (spec §7, p. 9) is the low 6 bits of the byte sum of the line, plus
//! 0x30.

/// Characters per data line before its sum (spec §8.1, p. 11).
pub(crate) const DATA_BLOCK_LEN: usize = 64;

/// The SCIP sum character of `bytes`.
pub(crate) fn checksum(bytes: &[u8]) -> u8 {
    let sum = bytes.iter().fold(0u8, |acc, &b| acc.wrapping_add(b));
    (sum & 0x3F) + 0x30
}

/// Appends `value` encoded in `width` characters (2, 3 or 4); bits above
/// `6 * width` are dropped, so callers pass values that fit.
pub(crate) fn encode_into(value: u32, width: u32, out: &mut Vec<u8>) {
    for group in (0..width).rev() {
        let bits = value.checked_shr(6 * group).unwrap_or(0) & 0x3F;
        // `bits` < 64, so the sum stays below 0x70.
        out.push(bits as u8 + 0x30);
    }
}

/// A reply message being built: echo, status line, data lines, and the
/// empty line that ends every SCIP 2.0 message (spec §7, p. 9).
pub(crate) struct Reply {
    bytes: Vec<u8>,
}

impl Reply {
    /// Starts a reply with the command echo and the status line
    /// (`status` + its sum).
    pub(crate) fn new(echo: &[u8], status: [u8; 2]) -> Self {
        let mut bytes = Vec::with_capacity(echo.len() + 8);
        bytes.extend_from_slice(echo);
        bytes.push(b'\n');
        let mut reply = Reply { bytes };
        reply.line_with_sum(&status);
        reply
    }

    /// Appends `text`, its sum and LF.
    pub(crate) fn line_with_sum(&mut self, text: &[u8]) {
        self.bytes.extend_from_slice(text);
        self.bytes.push(checksum(text));
        self.bytes.push(b'\n');
    }

    /// Appends a `KEY:value;sum` line of a VV/PP/II reply; the sum covers
    /// `KEY:value` without the ';' (spec p. 21: "DMIN:20;4").
    pub(crate) fn key_value(&mut self, key: &str, value: &str) {
        let start = self.bytes.len();
        self.bytes.extend_from_slice(key.as_bytes());
        self.bytes.push(b':');
        self.bytes.extend_from_slice(value.as_bytes());
        let sum = checksum(self.bytes.get(start..).unwrap_or_default());
        self.bytes.push(b';');
        self.bytes.push(sum);
        self.bytes.push(b'\n');
    }

    /// Appends `payload` cut into lines of [`DATA_BLOCK_LEN`] characters,
    /// each followed by its sum (spec p. 11). Line number `corrupt_line`, if
    /// any, gets a wrong sum.
    pub(crate) fn data_blocks(&mut self, payload: &[u8], corrupt_line: Option<usize>) {
        for (index, block) in payload.chunks(DATA_BLOCK_LEN).enumerate() {
            self.bytes.extend_from_slice(block);
            let sum = checksum(block);
            let sum = if corrupt_line == Some(index) {
                wrong_sum(sum)
            } else {
                sum
            };
            self.bytes.push(sum);
            self.bytes.push(b'\n');
        }
    }

    /// Ends the message with the empty line and returns its bytes.
    pub(crate) fn finish(mut self) -> Vec<u8> {
        self.bytes.push(b'\n');
        self.bytes
    }
}

/// A sum character that differs from `sum` but is still a plausible one.
fn wrong_sum(sum: u8) -> u8 {
    (sum.wrapping_sub(0x30).wrapping_add(1) & 0x3F) + 0x30
}

/// The number of data lines a payload of `len` characters takes.
pub(crate) fn data_line_count(len: usize) -> usize {
    len.div_ceil(DATA_BLOCK_LEN)
}
