//! When each sample was measured, back-dated from the arrival of its bytes by
//! the SDK's delay model (`_getSampleDelayOffsetInLegacyMode` in
//! `handler_normalnode.cpp`, `_getSampleDelayOffsetInExpressMode` and
//! `_getSampleDelayOffsetInDenseMode` in `handler_capsules.cpp`):
//!
//! delay = sample duration (the device's filter)
//!       + half a sample duration (the sample's centre)
//!       + the packet's transmission time (10 bits a byte at the baud rate)
//!       + (samples in the packet − 1 − index) × sample duration (the later
//!         samples that were grouped into the same packet).
//!
//! The SDK's `linkage_delay_uS` is always 0 and is left out.

/// The timing of one scan mode on one link.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SampleClock {
    sample_ns: u64,
    baud: u64,
}

impl SampleClock {
    /// `sample_us_q8`: the sample duration in µs, q8 (as `GET_LIDAR_CONF`
    /// reports it; multiply `GET_SAMPLERATE` values by 256). A baud rate of 0
    /// is taken as 1 (no division by zero; the delay is then huge, which
    /// shows).
    pub fn new(sample_us_q8: u32, baud: u32) -> Self {
        Self {
            sample_ns: u64::from(sample_us_q8) * 1000 / 256,
            baud: u64::from(baud.max(1)),
        }
    }

    /// Nanoseconds per sample.
    pub fn sample_ns(&self) -> u64 {
        self.sample_ns
    }

    /// The wall-clock time of sample `index` of `group` samples carried in a
    /// packet of `packet_len` bytes whose last byte arrived at `arrival_ns`.
    pub fn sample_time(
        &self,
        arrival_ns: u64,
        packet_len: usize,
        group: usize,
        index: usize,
    ) -> u64 {
        let transmission = (packet_len as u64).saturating_mul(10_000_000_000) / self.baud;
        let later_samples = group.saturating_sub(index.saturating_add(1)) as u64;
        let delay = self
            .sample_ns
            .saturating_add(self.sample_ns / 2)
            .saturating_add(transmission)
            .saturating_add(later_samples.saturating_mul(self.sample_ns));
        arrival_ns.saturating_sub(delay)
    }
}
