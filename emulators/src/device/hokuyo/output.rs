//! The sensor's transmit side: messages queued in order and released to the
//! host as the link carries them. Over USB a message is out as soon as it is
//! made; over RS-232 each byte takes 10 bit times (8N1) and messages wait
//! for the line. Holds at most [`OUTPUT_CAPACITY`] bytes not yet polled.

use std::collections::VecDeque;

/// Most bytes waiting for the host; beyond it new messages are dropped (a
/// host that stopped reading does not grow memory).
pub(crate) const OUTPUT_CAPACITY: usize = 1 << 20;

/// Bits on the wire per byte with 8N1 framing.
const BITS_PER_BYTE: f64 = 10.0;

struct Chunk {
    /// When the first byte starts on the wire.
    start: f64,
    /// Seconds per byte (0 over USB).
    byte_time: f64,
    bytes: Vec<u8>,
    /// Bytes already handed to the host.
    sent: usize,
}

/// The ordered output of the sensor.
pub(crate) struct OutputLine {
    chunks: VecDeque<Chunk>,
    /// Bytes queued and not yet handed to the host.
    pending: usize,
    /// When the line finishes what is queued.
    busy_until: f64,
    /// Current RS-232 bit rate; `None` over USB.
    baud: Option<u32>,
    /// A bit-rate change taking effect at a given time.
    baud_change: Option<(f64, u32)>,
}

impl OutputLine {
    pub(crate) fn new(baud: Option<u32>) -> Self {
        OutputLine {
            chunks: VecDeque::new(),
            pending: 0,
            busy_until: 0.0,
            baud,
            baud_change: None,
        }
    }

    /// The bit rate at the latest time given to [`Self::advance`].
    pub(crate) fn baud(&self) -> Option<u32> {
        self.baud
    }

    /// Applies a due bit-rate change.
    pub(crate) fn advance(&mut self, now: f64) {
        if let Some((at, baud)) = self.baud_change {
            if at <= now {
                self.baud = Some(baud);
                self.baud_change = None;
            }
        }
    }

    /// The bit rate in effect at `t` (a pending change counts once due).
    fn baud_at(&self, t: f64) -> Option<u32> {
        match self.baud_change {
            Some((at, baud)) if at <= t => Some(baud),
            _ => self.baud,
        }
    }

    /// Switches an RS-232 line to `baud` once everything queued so far has
    /// been sent (no-op over USB).
    pub(crate) fn change_baud_after_queued(&mut self, now: f64, baud: u32) {
        if self.baud.is_some() {
            self.baud_change = Some((self.busy_until.max(now), baud));
        }
    }

    /// When the line has sent everything queued.
    pub(crate) fn busy_until(&self) -> f64 {
        self.busy_until
    }

    /// Whether the line is still sending earlier output at `t`.
    pub(crate) fn is_busy_at(&self, t: f64) -> bool {
        self.baud.is_some() && self.busy_until > t
    }

    /// Whether `len` more bytes fit.
    pub(crate) fn has_room(&self, len: usize) -> bool {
        self.pending.saturating_add(len) <= OUTPUT_CAPACITY
    }

    /// Queues a message made at time `t`; returns false (and drops it) when
    /// it does not fit.
    pub(crate) fn send(&mut self, t: f64, bytes: Vec<u8>) -> bool {
        if bytes.is_empty() {
            return true;
        }
        if !self.has_room(bytes.len()) {
            return false;
        }
        let start = t.max(self.busy_until);
        let byte_time = self
            .baud_at(start)
            .map_or(0.0, |baud| BITS_PER_BYTE / f64::from(baud.max(1)));
        self.busy_until = start + byte_time * bytes.len() as f64;
        self.pending += bytes.len();
        self.chunks.push_back(Chunk {
            start,
            byte_time,
            bytes,
            sent: 0,
        });
        true
    }

    /// Appends to `out` every byte fully on the wire by `now`.
    pub(crate) fn drain(&mut self, now: f64, out: &mut Vec<u8>) {
        while let Some(chunk) = self.chunks.front_mut() {
            if chunk.start > now {
                break;
            }
            let done = if chunk.byte_time > 0.0 {
                ((now - chunk.start) / chunk.byte_time).floor().max(0.0) as usize
            } else {
                chunk.bytes.len()
            };
            let done = done.min(chunk.bytes.len());
            if let Some(ready) = chunk.bytes.get(chunk.sent..done) {
                out.extend_from_slice(ready);
                self.pending = self.pending.saturating_sub(ready.len());
            }
            chunk.sent = chunk.sent.max(done);
            if chunk.sent < chunk.bytes.len() {
                break;
            }
            self.chunks.pop_front();
        }
    }

    /// Bytes queued and not yet handed to the host.
    #[cfg(test)]
    pub(crate) fn pending(&self) -> usize {
        self.pending
    }
}
