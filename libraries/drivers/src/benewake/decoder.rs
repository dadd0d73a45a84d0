//! The streaming decoder of one port's byte stream, which carries data frames
//! (`59 59 ...`, 9 bytes) and command replies (`5A len ...`) interleaved: the
//! device keeps streaming while it answers. Chunks may split anywhere; the
//! buffer never holds more than one command frame's worth of bytes.

use super::command::{COMMAND_HEADER, MAX_COMMAND_FRAME_LEN};
use super::frame::{DataFrame, FrameError, FRAME_HEADER, FRAME_LEN};
use super::reply::CommandFrame;

/// Longest run of skipped bytes counted as one `garbage` error: a line that
/// carries nothing but noise (a wrong baud rate) keeps counting.
const GARBAGE_RUN_LIMIT: usize = 64;

/// What the decoder found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Packet {
    /// A checksum-valid data frame.
    Data(DataFrame),
    /// A checksum-valid `5A` frame (a reply to a command).
    Reply(CommandFrame),
}

/// Input the decoder rejected; each is one count of [`DecodeError::kind`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum DecodeError {
    /// `59 59` and nine bytes whose checksum failed: the decoder slides one
    /// byte and hunts again; the bytes it then skips belong to this error.
    #[error("data frame with a bad checksum")]
    BadChecksum,
    /// Bytes that start no valid frame, counted once per run (and again every
    /// 64 bytes of a longer run). A `5A` whose length or checksum does not fit
    /// is garbage too: a lone 0x5A in data cannot be told from a damaged reply.
    #[error("bytes that start no frame")]
    Garbage,
    /// Bytes skipped before the first frame after a reset: the tail of
    /// whatever the device was sending when the port opened.
    #[error("partial frame at the start of the stream")]
    PartialFrame,
}

impl DecodeError {
    /// The stable counter name: `bad_checksum`, `garbage`, `partial_frame`.
    pub fn kind(self) -> &'static str {
        match self {
            Self::BadChecksum => "bad_checksum",
            Self::Garbage => "garbage",
            Self::PartialFrame => "partial_frame",
        }
    }
}

/// One decoded item, in stream order.
pub type Decoded = Result<Packet, DecodeError>;

/// What the bytes at the head of the buffer are.
enum Head {
    /// Not enough bytes to decide.
    NeedMore,
    /// A whole packet of this many bytes.
    Packet(Packet, usize),
    /// A data frame with a bad checksum.
    BadChecksum,
    /// The first byte starts nothing.
    Skip,
}

/// Streaming decoder; see the module docs.
#[derive(Debug, Clone)]
pub struct Decoder {
    buf: [u8; MAX_COMMAND_FRAME_LEN],
    len: usize,
    /// A packet was found since the last reset.
    synced: bool,
    /// Bytes skipped in the current run, already reported once.
    run: usize,
    /// The current run of skipped bytes follows a bad checksum (already
    /// counted as that error).
    after_error: bool,
    skipped_bytes: u64,
}

impl Default for Decoder {
    fn default() -> Self {
        Self::new()
    }
}

impl Decoder {
    pub fn new() -> Self {
        Self {
            buf: [0; MAX_COMMAND_FRAME_LEN],
            len: 0,
            synced: false,
            run: 0,
            after_error: false,
            skipped_bytes: 0,
        }
    }

    /// Forgets partial input (the port was reopened). `skipped_bytes` is kept.
    pub fn reset(&mut self) {
        *self = Self {
            skipped_bytes: self.skipped_bytes,
            ..Self::new()
        };
    }

    /// Bytes skipped while hunting for frames, since creation.
    pub fn skipped_bytes(&self) -> u64 {
        self.skipped_bytes
    }

    /// Bytes buffered towards an incomplete frame (at most 16).
    pub fn buffered(&self) -> usize {
        self.len
    }

    /// Decodes `bytes`, appending what it completes to `out` in stream order.
    pub fn feed(&mut self, bytes: &[u8], out: &mut Vec<Decoded>) {
        for &byte in bytes {
            self.push(byte, out);
        }
    }

    fn push(&mut self, byte: u8, out: &mut Vec<Decoded>) {
        if self.len == self.buf.len() {
            // Unreachable (a full buffer always decides), but never overflow.
            self.skip(out);
        }
        if let Some(slot) = self.buf.get_mut(self.len) {
            *slot = byte;
            self.len += 1;
        }
        self.drain(out);
    }

    /// Decides about the head of the buffer until it needs more bytes.
    fn drain(&mut self, out: &mut Vec<Decoded>) {
        loop {
            match self.head() {
                Head::NeedMore => return,
                Head::Packet(packet, n) => {
                    self.synced = true;
                    self.run = 0;
                    self.after_error = false;
                    self.consume(n);
                    out.push(Ok(packet));
                }
                Head::BadChecksum => {
                    self.synced = true;
                    self.run = 0;
                    self.after_error = true;
                    self.consume(1);
                    out.push(Err(DecodeError::BadChecksum));
                }
                Head::Skip => self.skip(out),
            }
        }
    }

    fn head(&self) -> Head {
        let bytes = &self.buf[..self.len];
        match bytes.first() {
            None => Head::NeedMore,
            Some(&FRAME_HEADER) => data_head(bytes),
            Some(&COMMAND_HEADER) => reply_head(bytes),
            Some(_) => Head::Skip,
        }
    }

    /// Drops the first byte, reporting the start of a run of garbage.
    fn skip(&mut self, out: &mut Vec<Decoded>) {
        if self.run == 0 && !self.after_error {
            out.push(Err(if self.synced {
                DecodeError::Garbage
            } else {
                DecodeError::PartialFrame
            }));
        }
        self.run += 1;
        if self.run >= GARBAGE_RUN_LIMIT {
            self.run = 0;
            self.after_error = false;
            self.synced = true;
        }
        self.skipped_bytes = self.skipped_bytes.saturating_add(1);
        self.consume(1);
    }

    fn consume(&mut self, n: usize) {
        let n = n.min(self.len);
        self.buf.copy_within(n..self.len, 0);
        self.len -= n;
    }
}

/// The head starts with 0x59: a data frame if the second byte is 0x59 too.
fn data_head(bytes: &[u8]) -> Head {
    match bytes.get(1) {
        None => return Head::NeedMore,
        Some(&FRAME_HEADER) => {}
        Some(_) => return Head::Skip,
    }
    let Some(frame) = bytes.get(..FRAME_LEN) else {
        return Head::NeedMore;
    };
    let Ok(frame) = <&[u8; FRAME_LEN]>::try_from(frame) else {
        return Head::Skip;
    };
    match DataFrame::parse(frame) {
        Ok(data) => Head::Packet(Packet::Data(data), FRAME_LEN),
        Err(FrameError::BadChecksum { .. }) => Head::BadChecksum,
        Err(FrameError::BadHeader) => Head::Skip,
    }
}

/// The head starts with 0x5A: a reply if its length byte is plausible and the
/// checksum holds once all of it is in.
fn reply_head(bytes: &[u8]) -> Head {
    let Some(&len) = bytes.get(1) else {
        return Head::NeedMore;
    };
    if !CommandFrame::valid_length(len) {
        return Head::Skip;
    }
    let Some(frame) = bytes.get(..usize::from(len)) else {
        return Head::NeedMore;
    };
    match CommandFrame::parse(frame) {
        Ok(reply) => Head::Packet(Packet::Reply(reply), frame.len()),
        Err(_) => Head::Skip,
    }
}
