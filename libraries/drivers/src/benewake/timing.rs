//! The driver's timing model: how long a frame spends on the wire (what a
//! stamp is back-dated by) and how long a silence kills the stream.

use std::time::Duration;

use super::frame::FRAME_LEN;

/// Bits per byte on an 8N1 line: start, 8 data, stop.
const BITS_PER_BYTE: u64 = 10;
/// A stream is dead after this many frame periods without a frame (or the
/// configured floor, whichever is longer).
const SILENT_PERIODS: u64 = 10;

/// Nanoseconds a 9-byte frame takes on an 8N1 line at `baud` (781 250 ns at
/// 115200). 0 when `baud` is 0.
///
/// The frame carries no device time. Told only when a read returned, the
/// driver stamps a reading at the arrival of its last byte minus this (and
/// minus this again for each frame that followed it in the same read). Told
/// the read's window too ([`ReadWindow`](crate::device::ReadWindow)),
/// it bounds the reading's time instead
/// ([`FrameTiming`](crate::assembly::lateness::FrameTiming)): the
/// host's read latency is then inside the bound, and the device's own
/// integration and averaging time before it sends (TF-Luna averages 500 Hz
/// measurements down to its output rate, manual §5.5) is part of the
/// configured link latency.
pub fn frame_transmission_ns(baud: u32) -> u64 {
    if baud == 0 {
        return 0;
    }
    let bits = FRAME_LEN as u64 * BITS_PER_BYTE;
    bits * 1_000_000_000 / u64::from(baud)
}

/// The silence after which the stream is declared dead: max(10 frame periods,
/// `floor`). A `rate_hz` of `None` (the device's own rate, unknown) or 0
/// (trigger mode) gives `floor`.
pub fn stream_timeout_ns(floor: Duration, rate_hz: Option<u16>) -> u64 {
    let floor = duration_ns(floor);
    match rate_hz {
        Some(hz) if hz > 0 => floor.max(SILENT_PERIODS * 1_000_000_000 / u64::from(hz)),
        _ => floor,
    }
}

/// `d` in nanoseconds, saturating at `u64::MAX`.
pub fn duration_ns(d: Duration) -> u64 {
    u64::try_from(d.as_nanos()).unwrap_or(u64::MAX)
}
