//! Time on the sensor: its 24-bit millisecond clock and the revolutions of
//! its motor.

/// The clock wraps every 2^24 ms (spec p. 12: "24bit internal timer with
/// 1msec resolution").
const CLOCK_MASK: i64 = (1 << 24) - 1;

/// Slack for float rounding when finding whole revolutions.
const EPSILON: f64 = 1e-9;

/// The sensor's millisecond clock: `base_ms` at emulator time `zero`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DeviceClock {
    base_ms: u32,
    zero: f64,
}

impl DeviceClock {
    pub(crate) fn new(base_ms: u32, zero: f64) -> Self {
        DeviceClock { base_ms, zero }
    }

    /// The 24-bit clock value at time `t` (seconds).
    pub(crate) fn ms_at(&self, t: f64) -> u32 {
        // Whole microseconds first, so 0.3 s reads 300 ms, not 299.
        let micros = ((t - self.zero) * 1e6).round() as i64;
        let ms = i64::from(self.base_ms).wrapping_add(micros.div_euclid(1000));
        // Masked to 24 bits, so it fits in u32.
        (ms & CLOCK_MASK) as u32
    }
}

/// The motor: revolution `k` starts at `epoch + k * period`; step `s` of it
/// is measured at `start + period * s / ares` (steps are equally spaced in
/// time, step 0 first).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rotation {
    epoch: f64,
    pub(crate) period: f64,
    ares: u32,
    /// When, after a revolution's start, its scan is ready to send: once the
    /// last measured step (AMAX) is done.
    ready_offset: f64,
}

impl Rotation {
    pub(crate) fn new(epoch: f64, period: f64, ares: u32, amax: u32) -> Self {
        let ready_offset = period * f64::from(amax.saturating_add(1)) / f64::from(ares.max(1));
        Rotation {
            epoch,
            period,
            ares,
            ready_offset,
        }
    }

    /// When revolution `k` starts.
    pub(crate) fn start(&self, k: u64) -> f64 {
        self.epoch + k as f64 * self.period
    }

    /// When step `step` of revolution `k` is measured.
    pub(crate) fn step_time(&self, k: u64, step: u32) -> f64 {
        self.start(k) + self.period * f64::from(step) / f64::from(self.ares.max(1))
    }

    /// When revolution `k`'s scan is ready to send.
    pub(crate) fn ready_time(&self, k: u64) -> f64 {
        self.start(k) + self.ready_offset
    }

    /// The first revolution that starts at or after `t`.
    pub(crate) fn first_starting_at_or_after(&self, t: f64) -> u64 {
        let revolutions = (t - self.epoch) / self.period;
        // Saturating float-to-int: negative → 0, huge → u64::MAX.
        (revolutions - EPSILON).ceil().max(0.0) as u64
    }

    /// The last revolution whose scan is ready at `t` (revolution 0 if none
    /// is ready yet).
    pub(crate) fn latest_ready_at(&self, t: f64) -> u64 {
        let revolutions = (t - self.epoch - self.ready_offset) / self.period;
        (revolutions + EPSILON).floor().max(0.0) as u64
    }
}
