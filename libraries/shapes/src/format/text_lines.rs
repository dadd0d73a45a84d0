//! The lines of the text part of a file (a header, an ASCII body) with their
//! 1-based numbers and byte offsets, for readers whose errors name the line.

/// Lines of `bytes` read one at a time from a start offset.
pub(crate) struct TextLines<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Number of the line read last.
    line: usize,
}

impl<'a> TextLines<'a> {
    /// The lines of `bytes` from byte `start` on; the first of them is line
    /// number `first_line`.
    pub(crate) fn new(bytes: &'a [u8], start: usize, first_line: usize) -> Self {
        Self {
            bytes,
            pos: start.min(bytes.len()),
            line: first_line.saturating_sub(1),
        }
    }

    /// Byte offset of the next unread line.
    pub(crate) fn offset(&self) -> usize {
        self.pos
    }

    /// The next line that holds more than whitespace, with its number and
    /// without its `\n` (a `\r` before it stays: whitespace splitting drops it);
    /// `Ok(None)` at the end, `Err(line)` for a line that is not UTF-8.
    pub(crate) fn next_non_blank(&mut self) -> Result<Option<(usize, &'a str)>, usize> {
        while self.pos < self.bytes.len() {
            let rest = &self.bytes[self.pos..];
            let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
            self.pos += (end + 1).min(rest.len());
            self.line += 1;
            let text = std::str::from_utf8(&rest[..end]).map_err(|_| self.line)?;
            if !text.trim().is_empty() {
                return Ok(Some((self.line, text)));
            }
        }
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_lines_and_skips_blank_ones() {
        let text = b"skip\nfirst\r\n\n  \nsecond";
        let mut lines = TextLines::new(text, 5, 2);
        assert_eq!(lines.next_non_blank(), Ok(Some((2, "first\r"))));
        assert_eq!(lines.offset(), 12);
        assert_eq!(lines.next_non_blank(), Ok(Some((5, "second"))));
        assert_eq!(lines.offset(), text.len());
        assert_eq!(lines.next_non_blank(), Ok(None));
        let mut bad = TextLines::new(b"ok\n\xff\xfe\n", 0, 1);
        assert_eq!(bad.next_non_blank(), Ok(Some((1, "ok"))));
        assert_eq!(bad.next_non_blank(), Err(2));
        assert_eq!(TextLines::new(b"x", 9, 1).next_non_blank(), Ok(None));
    }
}
