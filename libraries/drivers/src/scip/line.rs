//! Splits the sensor's byte stream into lines. SCIP terminates lines with LF;
//! urg_c `serial_readline()` also ends a line at CR, and a CR LF pair is one
//! terminator here. Lines are bounded: a longer one is skipped to its end and
//! reported once as oversize.

/// The longest line kept, in bytes without its terminator. SCIP data lines are
/// 64 characters plus a sum (spec C-42-03320B §8.1); echoes are at most 15
/// characters plus a 17-character tag; parameter lines are short texts.
pub const MAX_LINE_LEN: usize = 256;

/// What a splitter produced.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum LineEvent {
    /// A complete line without its terminator (may be empty).
    Line(Vec<u8>),
    /// A line longer than [`MAX_LINE_LEN`] ended; its bytes were dropped.
    Oversize,
}

/// Streaming line splitter: feed bytes in any chunks.
#[derive(Debug, Default)]
pub struct LineSplitter {
    line: Vec<u8>,
    oversize: bool,
    after_cr: bool,
}

impl LineSplitter {
    pub fn new() -> Self {
        Self::default()
    }

    /// Forgets a partial line (after the port's input was flushed).
    pub fn reset(&mut self) {
        *self = Self::default();
    }

    /// Takes one byte; returns the line it completes, if any.
    pub fn push(&mut self, byte: u8) -> Option<LineEvent> {
        let after_cr = std::mem::replace(&mut self.after_cr, byte == b'\r');
        match byte {
            b'\n' if after_cr => None,
            b'\n' | b'\r' => Some(self.finish()),
            _ => {
                if self.line.len() < MAX_LINE_LEN {
                    self.line.push(byte);
                } else {
                    self.oversize = true;
                }
                None
            }
        }
    }

    fn finish(&mut self) -> LineEvent {
        if std::mem::take(&mut self.oversize) {
            self.line.clear();
            LineEvent::Oversize
        } else {
            LineEvent::Line(std::mem::take(&mut self.line))
        }
    }
}
