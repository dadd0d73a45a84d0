//! Clocks: wall time for message stamps (comparable across processes on one
//! machine), monotonic time for rates.

use std::sync::OnceLock;
use std::time::{Instant, SystemTime, UNIX_EPOCH};

/// Nanoseconds since the Unix epoch (0 if the clock is before 1970).
pub fn unix_ns() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_nanos() as u64)
        .unwrap_or(0)
}

/// Nanoseconds since the first call in this process.
pub fn monotonic_ns() -> u64 {
    static START: OnceLock<Instant> = OnceLock::new();
    START.get_or_init(Instant::now).elapsed().as_nanos() as u64
}

/// When a sample was published, on its publisher's wall clock (nanoseconds
/// since the Unix epoch): its zenoh timestamp. Every shroud session stamps
/// what it publishes (timestamping is on in [`ZenohArgs::config`]); a sample
/// from a session that does not is stamped by the first shroud session it
/// reaches, so its time before that is not counted.
///
/// [`ZenohArgs::config`]: super::ZenohArgs::config
pub fn sample_published_ns(sample: &zenoh::sample::Sample) -> Option<u64> {
    let time = sample.timestamp()?.get_time().to_duration();
    u64::try_from(time.as_nanos()).ok()
}
