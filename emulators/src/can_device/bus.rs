//! The device's side of a CAN bus: how long a frame occupies the wire, and a
//! transmit queue that sends one frame at a time with CAN's arbitration (of
//! the frames waiting when the bus frees, the lowest identifier goes first).

use shroud_drivers::can::CanFrame;
use std::collections::VecDeque;

/// Frames held for sending at most; further ones are dropped (counted), as a
/// controller's full mailbox would.
pub(crate) const QUEUE_CAPACITY: usize = 1024;

/// Seconds `frame` occupies a bus running at `bitrate` bit/s: SOF, id,
/// control, data, CRC, ACK, end of frame and the 3-bit intermission (ISO
/// 11898-1: 47 + 8·len bits with an 11-bit id, 67 + 8·len with a 29-bit id),
/// plus one stuff bit per ten stuffable bits, a typical payload's share (the
/// worst case is one per four).
pub(crate) fn frame_seconds(frame: &CanFrame, bitrate: u32) -> f64 {
    let data_bits = 8.0 * f64::from(frame.len.min(8)) * f64::from(u8::from(!frame.remote));
    let (fixed, stuffable) = if frame.extended {
        (67.0, 54.0)
    } else {
        (47.0, 34.0)
    };
    let bits = fixed + data_bits + (stuffable + data_bits) / 10.0;
    bits / f64::from(bitrate.max(1))
}

/// The arbitration priority of a frame: lower wins. A standard frame beats an
/// extended one with the same 11 leading id bits (its IDE bit is dominant).
fn priority(frame: &CanFrame) -> (u32, bool, u32) {
    if frame.extended {
        (frame.id >> 18, true, frame.id & 0x3_FFFF)
    } else {
        (frame.id, false, 0)
    }
}

/// A frame waiting to be sent, and when it became ready.
#[derive(Debug, Clone, Copy)]
struct Waiting {
    ready: f64,
    frame: CanFrame,
}

/// The device's transmitter. Two queues: a *stream* sent strictly in order
/// (a measurement cycle, whose frames must not be reordered), of which only
/// the head competes, and *single* frames (periodic status, replies) that each
/// compete on their own.
#[derive(Debug)]
pub(crate) struct Transmitter {
    bitrate: u32,
    /// When the frame on the wire ends.
    bus_free: f64,
    stream: VecDeque<Waiting>,
    singles: Vec<Waiting>,
    /// Frames refused because the queues were full.
    pub(crate) dropped: u64,
}

impl Transmitter {
    pub(crate) fn new(bitrate: u32) -> Self {
        Self {
            bitrate,
            bus_free: 0.0,
            stream: VecDeque::new(),
            singles: Vec::new(),
            dropped: 0,
        }
    }

    fn full(&mut self) -> bool {
        let full = self.stream.len() + self.singles.len() >= QUEUE_CAPACITY;
        if full {
            self.dropped = self.dropped.saturating_add(1);
        }
        full
    }

    /// Queues a frame of the in-order stream, ready at `ready`.
    pub(crate) fn push_stream(&mut self, ready: f64, frame: CanFrame) {
        if !self.full() {
            self.stream.push_back(Waiting { ready, frame });
        }
    }

    /// Queues a frame that arbitrates on its own, ready at `ready`.
    pub(crate) fn push_single(&mut self, ready: f64, frame: CanFrame) {
        if !self.full() {
            self.singles.push(Waiting { ready, frame });
        }
    }

    /// Sends every frame whose transmission ends by `now`, appending it with
    /// its end time to `out`.
    pub(crate) fn send_until(&mut self, now: f64, out: &mut Vec<(f64, CanFrame)>) {
        while let Some((start, pick)) = self.next() {
            let frame = match pick {
                Pick::Stream => self.stream.front().map(|w| w.frame),
                Pick::Single(i) => self.singles.get(i).map(|w| w.frame),
            };
            let Some(frame) = frame else {
                return;
            };
            let end = start + frame_seconds(&frame, self.bitrate);
            if end > now {
                return;
            }
            match pick {
                Pick::Stream => {
                    self.stream.pop_front();
                }
                Pick::Single(i) => {
                    self.singles.remove(i);
                }
            }
            self.bus_free = end;
            out.push((end, frame));
        }
    }

    /// When the next frame starts and which one it is: the bus is free and
    /// at least one frame is ready; of those ready then, the highest priority
    /// wins (the stream's head first on a tie, then the oldest single).
    fn next(&self) -> Option<(f64, Pick)> {
        let heads = self
            .stream
            .front()
            .map(|w| (Pick::Stream, w))
            .into_iter()
            .chain(
                self.singles
                    .iter()
                    .enumerate()
                    .map(|(i, w)| (Pick::Single(i), w)),
            );
        let earliest = heads.clone().map(|(_, w)| w.ready).reduce(f64::min)?;
        let start = earliest.max(self.bus_free);
        let (pick, _) = heads
            .filter(|(_, w)| w.ready <= start)
            .min_by_key(|(_, w)| priority(&w.frame))?;
        Some((start, pick))
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Pick {
    Stream,
    Single(usize),
}
