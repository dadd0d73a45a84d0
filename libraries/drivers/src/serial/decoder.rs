//! The streaming serial decoder: bytes in any chunking -> scans. It hunts for the
//! sync word, validates the header CRC-16 before trusting a length, checks the
//! frame CRC-32, and resynchronises one byte past any bad frame, so a valid
//! frame right after garbage or a truncated frame is still found.

use super::assembler::ScanAssembler;
use super::crc32_trailer;
use super::header::{FrameHeader, HEADER_LEN, SYNC, TRAILER_LEN};
use super::payload::read_payload;
use crate::{DecoderStats, IngestError, Scan};

/// Limits of a [`SerialScanDecoder`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DecoderConfig {
    /// A scan growing past this many points is dropped ([`IngestError::Oversize`]).
    pub max_scan_points: usize,
}

impl Default for DecoderConfig {
    fn default() -> Self {
        Self {
            max_scan_points: 4_000_000,
        }
    }
}

/// Streaming decoder of the serial range-sensor protocol (`docs/sensor-protocols.md` §1).
///
/// Every error it returns is also counted in [`SerialScanDecoder::stats`]. One
/// corruption costs one error: bytes skipped while resynchronising after a bad
/// frame are not reported again as garbage (they are in `skipped_bytes`), and
/// the rest of a scan that lost a frame is discarded quietly.
#[derive(Debug)]
pub struct SerialScanDecoder {
    buf: Vec<u8>,
    start: usize,
    stats: DecoderStats,
    assembler: ScanAssembler,
    /// Bytes skipped since the last frame or error, not yet reported.
    garbage: usize,
    /// Whether skipped bytes belong to an already reported bad frame.
    after_error: bool,
}

impl Default for SerialScanDecoder {
    fn default() -> Self {
        Self::new(DecoderConfig::default())
    }
}

impl SerialScanDecoder {
    pub fn new(config: DecoderConfig) -> Self {
        Self {
            buf: Vec::new(),
            start: 0,
            stats: DecoderStats::default(),
            assembler: ScanAssembler::new(config.max_scan_points),
            garbage: 0,
            after_error: false,
        }
    }

    pub fn stats(&self) -> &DecoderStats {
        &self.stats
    }

    /// Feeds bytes; returns the scans completed and the errors met, in stream order.
    pub fn push(&mut self, bytes: &[u8]) -> Vec<Result<Scan, IngestError>> {
        self.stats.input += bytes.len() as u64;
        if self.start > 0 && self.start * 2 >= self.buf.len() {
            self.buf.drain(..self.start);
            self.start = 0;
        }
        self.buf.extend_from_slice(bytes);
        let mut out = Vec::new();
        while self.step(&mut out) {}
        out
    }

    /// End of stream (or the device went away): reports a partial frame as
    /// truncated, leftover bytes as garbage, and a scan in progress as
    /// incomplete, then starts afresh.
    pub fn finish(&mut self) -> Vec<Result<Scan, IngestError>> {
        let mut out = Vec::new();
        let rest = self.buf.len() - self.start;
        if rest > 0 {
            self.stats.skipped_bytes += rest as u64;
            let avail = &self.buf[self.start..];
            let header = (avail.len() >= HEADER_LEN && avail.starts_with(&SYNC))
                .then(|| FrameHeader::parse(avail).ok())
                .flatten();
            if let Some(h) = header {
                self.report_garbage(&mut out);
                out.push(Err(self.stats.count(IngestError::Truncated {
                    got: rest,
                    expected: h.frame_len(),
                })));
                self.assembler
                    .abandon(h.sequence, &mut self.stats, &mut out);
            } else {
                self.garbage += rest;
            }
        }
        self.report_garbage(&mut out);
        self.assembler.finish(&mut self.stats, &mut out);
        self.buf.clear();
        self.start = 0;
        self.after_error = false;
        out
    }

    fn skip(&mut self, n: usize) {
        self.start += n;
        self.stats.skipped_bytes += n as u64;
        if !self.after_error {
            self.garbage += n;
        }
    }

    fn report_garbage(&mut self, out: &mut Vec<Result<Scan, IngestError>>) {
        if self.garbage > 0 {
            let bytes = std::mem::take(&mut self.garbage);
            out.push(Err(self.stats.count(IngestError::Garbage { bytes })));
        }
    }

    fn report_error(&mut self, error: IngestError, out: &mut Vec<Result<Scan, IngestError>>) {
        self.report_garbage(out);
        out.push(Err(self.stats.count(error)));
        self.after_error = true;
    }

    /// Makes one step of progress; false when more bytes are needed.
    fn step(&mut self, out: &mut Vec<Result<Scan, IngestError>>) -> bool {
        let avail = &self.buf[self.start..];
        match avail.windows(2).position(|w| w == SYNC) {
            Some(0) => {}
            Some(i) => {
                self.skip(i);
                return true;
            }
            None => {
                // Keep a trailing first sync byte: its partner may come next.
                let keep = usize::from(avail.last() == Some(&SYNC[0]));
                self.skip(avail.len() - keep);
                return false;
            }
        }
        if avail.len() < HEADER_LEN {
            return false;
        }
        let header = match FrameHeader::parse(avail) {
            Ok(h) => h,
            Err(e) => {
                self.report_error(e, out);
                self.skip(1);
                return true;
            }
        };
        let len = header.frame_len();
        if avail.len() < len {
            return false;
        }
        let body = len - TRAILER_LEN;
        let found = u32::from_le_bytes(avail[body..len].try_into().expect("4 bytes"));
        let computed = crc32_trailer(&avail[..body]);
        if found != computed {
            let error = match next_header(avail, len) {
                NextHeader::At(got) => IngestError::Truncated { got, expected: len },
                NextHeader::NeedMore => return false,
                NextHeader::None => IngestError::BadCrc { found, computed },
            };
            self.report_error(error, out);
            self.assembler
                .abandon(header.sequence, &mut self.stats, out);
            self.skip(1);
            return true;
        }
        let (mut points, mut intensity) = (Vec::new(), Vec::new());
        let decoded = read_payload(
            &header,
            &avail[HEADER_LEN..body],
            &mut points,
            &mut intensity,
        );
        self.report_garbage(out);
        self.after_error = false;
        self.start += len;
        self.stats.frames += 1;
        match decoded {
            Ok(()) => self
                .assembler
                .push(&header, points, intensity, &mut self.stats, out),
            Err(e) => {
                out.push(Err(self.stats.count(e)));
                self.assembler
                    .abandon(header.sequence, &mut self.stats, out);
            }
        }
        true
    }
}

enum NextHeader {
    At(usize),
    NeedMore,
    None,
}

/// Whether a valid header starts within the first `len` bytes of `avail`
/// (after the first byte): the sign that the frame there was cut short by the
/// next one. `NeedMore` if a sync word there cannot be checked yet.
fn next_header(avail: &[u8], len: usize) -> NextHeader {
    for i in 1..len {
        if avail[i] != SYNC[0] {
            continue;
        }
        match avail.get(i + 1) {
            None => return NextHeader::NeedMore,
            Some(&b) if b != SYNC[1] => continue,
            Some(_) => {}
        }
        if avail.len() < i + HEADER_LEN {
            return NextHeader::NeedMore;
        }
        if FrameHeader::parse(&avail[i..]).is_ok() {
            return NextHeader::At(i);
        }
    }
    NextHeader::None
}
