//! The 84-byte capsule shared by legacy express (0x82) and dense (0x85)
//! scans: framing, checksum, start angle, and the pairing of each capsule
//! with the next one, whose start angle closes its angular span.
//!
//! Layout (`sl_lidar_response_capsule_measurement_nodes_t`, protocol PDF
//! Figure 4-12):
//! ```text
//! b0: 0xA << 4 | checksum[3:0]     b1: 0x5 << 4 | checksum[7:4]
//! b2..3: start_angle_q6, u16 LE; bit 15 = S (the first capsule after a
//!        start), bits 0..14 = the angle of the capsule's first sample
//! b4..83: the samples (per layout)
//! checksum = XOR of b2..b83
//! ```
//! Decoding follows `UnpackerHandler_CapsuleNode::onData` and
//! `_onScanNodeCapsuleData` (`handler_capsules.cpp`): a capsule's samples
//! are spread over `next.start − this.start` (plus 360° if negative); a
//! checksum failure loses the capsule held for pairing as well; a capsule
//! with S set restarts the scan and pairs with nothing before it. Each
//! rejected sync byte (or rejected b0/b1 pair) counts one `resync`.
//!
//! Revolutions: "a new scan starts at a measurement point whose raw angle is
//! smaller than previous one" (protocol PDF §4 express scan, Figure 4-14),
//! where the raw angle is the interpolated angle before any per-sample
//! correction. Only consecutive samples are compared: after a loss the next
//! boundary cannot be seen until two samples in a row have arrived.

use super::angle::TURN_Q16;
use super::device::{DeviceStats, HostTime};
use super::protocol::CAPSULE_LEN;
use super::sample::{Sample, StreamEvent};
use super::timing::SampleClock;

/// Sync nibbles of b0 and b1 (`SL_LIDAR_RESP_MEASUREMENT_EXP_SYNC_1/2`).
const SYNC_NIBBLES: [u8; 2] = [0xA, 0x5];
/// Bit 15 of the start angle (`SL_LIDAR_RESP_MEASUREMENT_EXP_SYNCBIT`).
const START_FLAG: u16 = 0x8000;

/// One capsule's bytes.
pub type Capsule = [u8; CAPSULE_LEN];

/// What the framer found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Framed {
    Capsule(Box<Capsule>),
    /// 84 bytes in sync whose checksum does not match.
    BadChecksum,
    /// A byte that cannot start (or continue the sync of) a capsule.
    Slid,
}

/// Whether a capsule's XOR of bytes 2..84 matches its two checksum nibbles.
pub fn checksum_ok(capsule: &Capsule) -> bool {
    let [b0, b1, body @ ..] = capsule;
    let sent = (b0 & 0x0F) | (b1 << 4);
    body.iter().fold(0u8, |acc, b| acc ^ b) == sent
}

/// The start angle in q6 degrees and the S flag.
pub fn start_of(capsule: &Capsule) -> (u16, bool) {
    let [_, _, lo, hi, ..] = *capsule;
    let raw = u16::from_le_bytes([lo, hi]);
    (raw & !START_FLAG, raw & START_FLAG != 0)
}

/// The angle from one capsule's start to the next one's, in q8 degrees,
/// computed as the SDK does (q6 start angles shifted to q8, +360° when the
/// next start is smaller).
pub fn span_q8(start_q6: u16, next_start_q6: u16) -> i64 {
    let (a, b) = (i64::from(start_q6) << 2, i64::from(next_start_q6) << 2);
    if a > b {
        b - a + (360 << 8)
    } else {
        b - a
    }
}

/// Cuts a byte stream into capsules (bounded: one capsule buffer).
#[derive(Debug, Clone)]
pub struct CapsuleFramer {
    buf: Capsule,
    len: usize,
}

impl Default for CapsuleFramer {
    fn default() -> Self {
        Self {
            buf: [0; CAPSULE_LEN],
            len: 0,
        }
    }
}

impl CapsuleFramer {
    /// Takes one byte. A byte rejected as b1 is examined again as a b0.
    pub fn push(&mut self, byte: u8) -> Option<Framed> {
        if self.len == 1 && byte >> 4 != SYNC_NIBBLES[1] {
            self.len = 0;
            if byte >> 4 != SYNC_NIBBLES[0] {
                // Both the held b0 and this byte are lost; one event each
                // would only repeat the loss, so report one.
                return Some(Framed::Slid);
            }
            self.store(byte);
            return Some(Framed::Slid);
        }
        if self.len == 0 && byte >> 4 != SYNC_NIBBLES[0] {
            return Some(Framed::Slid);
        }
        self.store(byte);
        if self.len < CAPSULE_LEN {
            return None;
        }
        self.len = 0;
        if checksum_ok(&self.buf) {
            Some(Framed::Capsule(Box::new(self.buf)))
        } else {
            Some(Framed::BadChecksum)
        }
    }

    fn store(&mut self, byte: u8) {
        if let Some(slot) = self.buf.get_mut(self.len) {
            *slot = byte;
            self.len += 1;
        }
    }
}

/// One sample as a layout decodes it, before timing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RawSample {
    /// The interpolated angle (q16 degrees, unwrapped), which decides
    /// revolution boundaries.
    pub raw_q16: i64,
    /// The sample's heading after the layout's correction (q16, unwrapped).
    pub heading_q16: i64,
    /// Millimetres, q2.
    pub distance_q2: u32,
}

/// What differs between capsule kinds: how many samples a capsule holds and
/// how they decode.
pub trait CapsuleLayout {
    /// Samples per capsule.
    const SAMPLES: usize;
    /// Decodes `capsule`'s samples, given its start (q16) and the span to the
    /// next capsule's start (q8, as [`span_q8`]), into `out`.
    fn decode(capsule: &Capsule, start_q16: i64, span_q8: i64, out: &mut Vec<RawSample>);
    /// Whether a span is believable for this layout (see [`DenseLayout`]);
    /// a capsule whose span is not is lost.
    ///
    /// [`DenseLayout`]: super::dense::DenseLayout
    fn span_plausible(_span_q8: i64, _clock: &SampleClock) -> bool {
        true
    }
}

/// Capsule stream decoder: frames capsules, pairs each with the next, and
/// reports samples, losses (counted `resync` / `bad_checksum` /
/// `capsule_gap`) and restarts.
#[derive(Debug, Clone)]
pub struct CapsuleStream<L> {
    clock: SampleClock,
    framer: CapsuleFramer,
    /// The last good capsule and when its last byte arrived, waiting for its
    /// successor.
    held: Option<(Box<Capsule>, u64)>,
    /// The raw angle of the last sample reported, wrapped to one turn.
    last_raw_q16: Option<i64>,
    scratch: Vec<RawSample>,
    layout: std::marker::PhantomData<L>,
}

impl<L: CapsuleLayout> CapsuleStream<L> {
    pub fn new(clock: SampleClock) -> Self {
        Self {
            clock,
            framer: CapsuleFramer::default(),
            held: None,
            last_raw_q16: None,
            scratch: Vec::with_capacity(L::SAMPLES),
            layout: std::marker::PhantomData,
        }
    }

    pub fn feed(
        &mut self,
        bytes: &[u8],
        now: HostTime,
        stats: &mut DeviceStats,
        events: &mut Vec<StreamEvent>,
    ) {
        for &byte in bytes {
            match self.framer.push(byte) {
                None => {}
                Some(Framed::Capsule(c)) => self.on_capsule(c, now.unix_ns, stats, events),
                Some(Framed::BadChecksum) => self.lose("bad_checksum", stats, events),
                Some(Framed::Slid) => self.lose("resync", stats, events),
            }
        }
    }

    fn lose(&mut self, kind: &'static str, stats: &mut DeviceStats, events: &mut Vec<StreamEvent>) {
        stats.count(kind);
        self.held = None;
        self.last_raw_q16 = None;
        events.push(StreamEvent::Loss);
    }

    fn on_capsule(
        &mut self,
        capsule: Box<Capsule>,
        arrival_ns: u64,
        stats: &mut DeviceStats,
        events: &mut Vec<StreamEvent>,
    ) {
        let (start_q6, restart) = start_of(&capsule);
        if restart {
            self.held = None;
            self.last_raw_q16 = None;
            events.push(StreamEvent::Restart);
        }
        if let Some((prev, prev_arrival)) = self.held.take() {
            let span = span_q8(start_of(&prev).0, start_q6);
            if L::span_plausible(span, &self.clock) {
                self.emit(&prev, prev_arrival, span, events);
            } else {
                stats.count("capsule_gap");
                self.last_raw_q16 = None;
                events.push(StreamEvent::Loss);
            }
        }
        self.held = Some((capsule, arrival_ns));
    }

    fn emit(
        &mut self,
        capsule: &Capsule,
        arrival_ns: u64,
        span: i64,
        events: &mut Vec<StreamEvent>,
    ) {
        let start_q16 = i64::from(start_of(capsule).0) << 10;
        self.scratch.clear();
        L::decode(capsule, start_q16, span, &mut self.scratch);
        for (index, raw) in self.scratch.iter().enumerate() {
            let wrapped = raw.raw_q16.rem_euclid(TURN_Q16);
            let starts_revolution = self.last_raw_q16.is_some_and(|last| wrapped < last);
            self.last_raw_q16 = Some(wrapped);
            events.push(StreamEvent::Sample(Sample {
                heading_q16: raw.heading_q16,
                distance_q2: raw.distance_q2,
                quality: None,
                time_ns: self
                    .clock
                    .sample_time(arrival_ns, CAPSULE_LEN, L::SAMPLES, index),
                starts_revolution,
            }));
        }
    }
}
