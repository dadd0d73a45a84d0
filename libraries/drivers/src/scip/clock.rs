//! The sensor's clock: a 24-bit millisecond timer (spec C-42-03320B §6
//! 4-character encoding, §8.6 `TM`) that wraps every 2^24 ms (about 4.66 h),
//! unwrapped here, and mapped to the host's wall clock by `TM1` round trips.
//! Scan stamps fall back to arrival-based times when the mapping is nonsense.

use crate::device::{DeviceStats, HostTime};

/// The timer's modulus, 2^24 ms.
pub const WRAP_MS: i64 = 1 << 24;

/// Unwraps successive 24-bit readings into one monotonic millisecond count.
/// A step of less than half the modulus backwards is taken as a reading that
/// went slightly back (reordering), not as a wrap.
#[derive(Debug, Clone, Default)]
pub struct DeviceClock {
    last: Option<(u32, i64)>,
}

impl DeviceClock {
    /// Forgets the history (the sensor may have rebooted).
    pub fn reset(&mut self) {
        self.last = None;
    }

    /// The unwrapped milliseconds of a raw 24-bit reading.
    pub fn unwrap(&mut self, raw: u32) -> i64 {
        let raw = raw & (WRAP_MS as u32 - 1);
        let unwrapped = match self.last {
            None => i64::from(raw),
            Some((last_raw, last)) => {
                let forward = (i64::from(raw) - i64::from(last_raw)).rem_euclid(WRAP_MS);
                let step = if forward >= WRAP_MS / 2 {
                    forward - WRAP_MS
                } else {
                    forward
                };
                last + step
            }
        };
        self.last = Some((raw, unwrapped));
        unwrapped
    }
}

/// One `TM1` round trip.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Sample {
    rtt_ns: u64,
    offset_ns: i128,
}

/// Estimates the offset from sensor milliseconds to host wall-clock
/// nanoseconds from `TM1` round trips: the round trip with the smallest
/// round-trip time wins, and the sensor is taken to have read its timer at the
/// midpoint of that round trip.
#[derive(Debug, Clone, Default)]
pub struct ClockSync {
    best: Option<Sample>,
}

impl ClockSync {
    /// Adds a round trip: `sent` when `TM1` was written, `replied` when its
    /// reply arrived, `device_ms` the (unwrapped) timer in the reply.
    pub fn add(&mut self, device_ms: i64, sent: HostTime, replied: HostTime) {
        let rtt_ns = replied.since(sent);
        let midpoint = i128::from(sent.unix_ns) + i128::from(rtt_ns / 2);
        let sample = Sample {
            rtt_ns,
            offset_ns: midpoint - i128::from(device_ms) * 1_000_000,
        };
        if self.best.is_none_or(|best| sample.rtt_ns < best.rtt_ns) {
            self.best = Some(sample);
        }
    }

    /// Host wall-clock ns = sensor ms * 1e6 + this, once a round trip is in.
    pub fn offset_ns(&self) -> Option<i128> {
        self.best.map(|s| s.offset_ns)
    }

    /// The smallest round-trip time seen.
    pub fn best_rtt_ns(&self) -> Option<u64> {
        self.best.map(|s| s.rtt_ns)
    }
}

/// How much later than the sweep and the line's transfer time a scan may
/// arrive (USB latency, the host's scheduling) before its mapped stamp is
/// taken for a clock gone wrong (a drifted or reset sensor clock).
pub const MAX_STAMP_LAG_NS: u64 = 100_000_000;

/// How far a mapped first ray may lie after `arrival - sweep`: the sensor's
/// 1 ms stamp resolution and the rear-centre assumption's slack (to which
/// half the sync's round trip and the clocks' drift since it are added).
pub const MAX_STAMP_LEAD_NS: u64 = 5_000_000;

/// How fast the sensor's crystal may drift from the host's clock, in parts
/// per million: the window widens by this much of the time since the sync.
pub const MAX_DRIFT_PPM: u64 = 100;

/// Stamps scans on the host's wall clock.
#[derive(Debug, Clone, Default)]
pub struct ScanStamper {
    offset_ns: Option<i128>,
    fallen_back: bool,
    /// Half the sync's best round trip: the offset's own uncertainty.
    half_rtt_ns: u64,
    /// When the offset was measured (host wall clock; `u64::MAX`: no drift
    /// allowance).
    synced_unix_ns: u64,
}

/// What the stamper needs to know about one scan.
#[derive(Debug, Clone, Copy)]
pub struct ScanTiming {
    /// The scan's timestamp, unwrapped sensor milliseconds.
    pub device_ms: i64,
    /// From the instant the timestamp marks to the first ray.
    pub first_ray_delay_ns: u64,
    /// From the first ray to the last.
    pub sweep_ns: u64,
    /// The reply's time on the line (0 over USB).
    pub transfer_ns: u64,
    /// How long a complete scan may wait in the sensor before it is sent
    /// (a polled scan: up to a revolution; streamed: 0).
    pub held_ns: u64,
    /// When the scan's last byte arrived.
    pub arrival: HostTime,
}

impl ScanStamper {
    /// Starts a new mapping (`None` when the sync failed), with no allowance
    /// for the sync's round trip or drift (see [`set_sync`](Self::set_sync)).
    pub fn set_offset(&mut self, offset_ns: Option<i128>) {
        self.offset_ns = offset_ns;
        self.fallen_back = false;
        self.half_rtt_ns = 0;
        self.synced_unix_ns = u64::MAX;
    }

    /// [`set_offset`](Self::set_offset) from a sync whose best round trip
    /// took `rtt_ns`, finished at `unix_ns`: the plausibility window widens by
    /// half that round trip and by [`MAX_DRIFT_PPM`] of the time since.
    pub fn set_sync(&mut self, offset_ns: Option<i128>, rtt_ns: u64, unix_ns: u64) {
        self.set_offset(offset_ns);
        self.half_rtt_ns = rtt_ns / 2;
        self.synced_unix_ns = unix_ns;
    }

    /// Whether stamps come from arrival times (no sync, or a mismatch).
    pub fn is_fallen_back(&self) -> bool {
        self.offset_ns.is_none() || self.fallen_back
    }

    /// The first ray's wall-clock time: sensor time + offset + first-ray
    /// delay. The last ray cannot come after the scan's arrival, nor much
    /// before it: with `slack` = half the sync's round trip + drift since
    /// it, a mapped first ray later than `arrival - sweep +`
    /// [`MAX_STAMP_LEAD_NS`] `+ slack` or earlier than `arrival - sweep -
    /// transfer - held -` [`MAX_STAMP_LAG_NS`] `- slack` counts
    /// `clock_mismatch` and switches to arrival stamps (arrival - sweep -
    /// transfer) until the next [`set_offset`](Self::set_offset).
    pub fn stamp(&mut self, timing: &ScanTiming, stats: &mut DeviceStats) -> u64 {
        if let Some(mapped) = self.mapped(timing) {
            if self.plausible(mapped, timing) {
                return mapped as u64;
            }
            stats.count("clock_mismatch");
            self.fallen_back = true;
        }
        timing
            .arrival
            .unix_ns
            .saturating_sub(timing.sweep_ns.saturating_add(timing.transfer_ns))
    }

    fn mapped(&self, timing: &ScanTiming) -> Option<i128> {
        let offset = self.offset_ns.filter(|_| !self.fallen_back)?;
        Some(
            i128::from(timing.device_ms) * 1_000_000
                + offset
                + i128::from(timing.first_ray_delay_ns),
        )
    }

    fn plausible(&self, mapped: i128, timing: &ScanTiming) -> bool {
        let since_sync = timing.arrival.unix_ns.saturating_sub(self.synced_unix_ns);
        let drift = since_sync / 1_000_000 * MAX_DRIFT_PPM;
        let slack = i128::from(self.half_rtt_ns) + i128::from(drift);
        let expected = i128::from(timing.arrival.unix_ns) - i128::from(timing.sweep_ns);
        let latest = expected + i128::from(MAX_STAMP_LEAD_NS) + slack;
        let earliest = expected
            - i128::from(timing.transfer_ns)
            - i128::from(timing.held_ns)
            - i128::from(MAX_STAMP_LAG_NS)
            - slack;
        mapped >= 0 && mapped <= latest && mapped >= earliest
    }
}
