//! Cuts the host's byte stream into command lines. A command ends with LF,
//! CR or both (spec §7, p. 9), so CR and LF each end a line and the empty
//! line between CR and LF is dropped.

/// Longest line kept; the longest valid command (MD with a 16-character
/// string) has 32 characters.
pub(crate) const MAX_LINE: usize = 128;

/// A complete command line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Line {
    /// The line without its terminator, cut at [`MAX_LINE`] bytes.
    pub(crate) bytes: Vec<u8>,
    /// Whether bytes beyond [`MAX_LINE`] were dropped.
    pub(crate) overflowed: bool,
}

/// Accumulates bytes until a terminator; holds at most [`MAX_LINE`] bytes.
#[derive(Debug, Default)]
pub(crate) struct LineFramer {
    pending: Vec<u8>,
    overflowed: bool,
}

impl LineFramer {
    /// Takes one byte; returns the line it completes, if any (empty lines
    /// are not returned).
    pub(crate) fn push(&mut self, byte: u8) -> Option<Line> {
        if byte == b'\n' || byte == b'\r' {
            return self.take();
        }
        if self.pending.len() < MAX_LINE {
            self.pending.push(byte);
        } else {
            self.overflowed = true;
        }
        None
    }

    /// Forgets a partial line (the sensor rebooted).
    pub(crate) fn clear(&mut self) {
        self.pending.clear();
        self.overflowed = false;
    }

    /// Bytes held of the current partial line.
    #[cfg(test)]
    pub(crate) fn held(&self) -> usize {
        self.pending.len()
    }

    fn take(&mut self) -> Option<Line> {
        if self.pending.is_empty() && !self.overflowed {
            return None;
        }
        let line = Line {
            bytes: std::mem::take(&mut self.pending),
            overflowed: self.overflowed,
        };
        self.overflowed = false;
        Some(line)
    }
}
