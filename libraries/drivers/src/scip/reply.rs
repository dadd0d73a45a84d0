//! Groups lines into SCIP replies (spec C-42-03320B §7): an echo line, then
//! the status line and any data lines, ended by an empty line. Bounded: a
//! reply longer than [`MAX_REPLY_LINES`] is dropped to its end.

use super::line::LineEvent;

/// The most lines a reply may hold after its echo: an `NE` scan of 10000
/// steps (0..=9999) with 3 echoes each is 3 x (3 + 3) characters and two `&`
/// per step, 200000 characters in 64-character lines (3125 lines), plus
/// status and timestamp. At most 3200 lines of at most 256 bytes: the buffer
/// stays under 1 MB.
pub const MAX_REPLY_LINES: usize = 3200;

/// One reply as received; nothing is checked yet.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Reply {
    /// The first line: the echo of the command the sensor answers.
    pub echo: Vec<u8>,
    /// The lines after the echo (status first), each with its sum character.
    pub lines: Vec<Vec<u8>>,
    /// An oversize line was dropped from this reply.
    pub damaged: bool,
}

impl Reply {
    /// Whether every byte is printable ASCII, as all SCIP text is. Bytes read
    /// at a wrong baud rate usually are not.
    pub fn is_printable(&self) -> bool {
        std::iter::once(&self.echo)
            .chain(&self.lines)
            .flatten()
            .all(|b| (0x20..0x7F).contains(b))
    }
}

/// What the assembler produced.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Assembled {
    Reply(Reply),
    /// A reply exceeded [`MAX_REPLY_LINES`] and was dropped.
    Overflow,
}

/// Streaming reply assembler, fed by a line splitter.
#[derive(Debug, Default)]
pub struct ReplyAssembler {
    current: Option<Reply>,
    overflowing: bool,
}

impl ReplyAssembler {
    pub fn new() -> Self {
        Self::default()
    }

    /// Forgets a partial reply.
    pub fn reset(&mut self) {
        *self = Self::default();
    }

    /// Takes one line event; returns the reply it completes, if any. Empty
    /// lines between replies are ignored.
    pub fn push(&mut self, event: LineEvent) -> Option<Assembled> {
        match event {
            LineEvent::Line(line) if line.is_empty() => self.finish(),
            LineEvent::Line(line) => {
                self.add(line, false);
                None
            }
            LineEvent::Oversize => {
                self.add(Vec::new(), true);
                None
            }
        }
    }

    fn add(&mut self, line: Vec<u8>, oversize: bool) {
        if self.overflowing {
            return;
        }
        let Some(reply) = self.current.as_mut() else {
            self.current = Some(Reply {
                echo: line,
                lines: Vec::new(),
                damaged: oversize,
            });
            return;
        };
        if reply.lines.len() >= MAX_REPLY_LINES {
            self.current = None;
            self.overflowing = true;
            return;
        }
        reply.damaged |= oversize;
        if !oversize {
            reply.lines.push(line);
        }
    }

    fn finish(&mut self) -> Option<Assembled> {
        if std::mem::take(&mut self.overflowing) {
            return Some(Assembled::Overflow);
        }
        self.current.take().map(Assembled::Reply)
    }
}
