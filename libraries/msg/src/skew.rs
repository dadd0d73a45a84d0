//! Device stamps against the receiving node's clock: a stamp far from it is a
//! named fault. Stamps are kept for the record; ages are measured on the
//! nodes' own clocks (`pipeline_ns`), never on a device's word.

use std::fmt;

/// Default tolerance between a device stamp and the receiving node's wall clock.
pub const DEFAULT_MAX_SKEW_NS: u64 = 5_000_000_000;

/// A stamp `skew_ns` ahead of (positive) or behind the receiving clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StampSkew {
    pub skew_ns: i128,
}

impl std::error::Error for StampSkew {}

impl fmt::Display for StampSkew {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "stamp is {:.3} s {} this node's clock",
            (self.skew_ns as f64 / 1e9).abs(),
            if self.skew_ns > 0 {
                "ahead of"
            } else {
                "behind"
            }
        )
    }
}

/// `Err` when `stamp_ns` is further than `max_skew_ns` from `wall_ns`
/// (`u64::MAX`: never).
pub fn check_stamp_skew(stamp_ns: u64, wall_ns: u64, max_skew_ns: u64) -> Result<(), StampSkew> {
    let skew_ns = stamp_ns as i128 - wall_ns as i128;
    if skew_ns.unsigned_abs() > u128::from(max_skew_ns) {
        return Err(StampSkew { skew_ns });
    }
    Ok(())
}

/// A message that seems to have been published in the receiver's future by
/// more than the clocks may disagree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("published {ahead_ns} ns in the future of this node's clock (allowed clock offset {allowed_ns} ns)")]
pub struct ClockAhead {
    pub ahead_ns: u64,
    pub allowed_ns: u64,
}

/// Default bound on how far two nodes' wall clocks disagree: one host, one
/// clock (a millisecond covers a clock slewed by NTP while a message is in
/// flight). Across hosts, the synchronisation's own bound (PTP, NTP).
pub const DEFAULT_MAX_CLOCK_OFFSET_NS: u64 = 1_000_000;

/// The transit of a message published at `published_ns` on the sender's wall
/// clock and received at `received_ns` on the receiver's, as an upper bound:
/// the measured time (never below 0) plus `max_offset_ns`, the bound on how
/// far the two clocks disagree. Whatever held the message up (the network, a
/// queue, a receiver that was frozen before its callback ran) is in it.
pub fn counted_transit(
    published_ns: u64,
    received_ns: u64,
    max_offset_ns: u64,
) -> Result<u64, ClockAhead> {
    if published_ns > received_ns.saturating_add(max_offset_ns) {
        return Err(ClockAhead {
            ahead_ns: published_ns - received_ns,
            allowed_ns: max_offset_ns,
        });
    }
    Ok(received_ns
        .saturating_sub(published_ns)
        .saturating_add(max_offset_ns))
}

/// Seconds on a command line (`inf` for no check) as nanoseconds.
pub fn max_skew_ns_from_secs(seconds: f64) -> Option<u64> {
    if seconds.is_nan() || seconds <= 0.0 {
        return None;
    }
    Some(if seconds.is_finite() {
        (seconds * 1e9) as u64
    } else {
        u64::MAX
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transit_counts_the_offset_and_refuses_the_future() {
        assert_eq!(counted_transit(100, 350, 10), Ok(260));
        // Slightly ahead, within the offset: counted as 0 plus the offset.
        assert_eq!(counted_transit(105, 100, 10), Ok(10));
        assert_eq!(
            counted_transit(200, 100, 10),
            Err(ClockAhead {
                ahead_ns: 100,
                allowed_ns: 10
            })
        );
        assert_eq!(counted_transit(0, u64::MAX, u64::MAX), Ok(u64::MAX));
    }

    #[test]
    fn skew_is_symmetric_and_bounded() {
        let wall = 1_000 * 1_000_000_000u64;
        assert!(check_stamp_skew(wall, wall, 0).is_ok());
        assert!(check_stamp_skew(wall + 5, wall, 5).is_ok());
        let ahead = check_stamp_skew(wall + 6, wall, 5).unwrap_err();
        assert_eq!(ahead.skew_ns, 6);
        assert!(ahead.to_string().contains("ahead of"));
        let behind = check_stamp_skew(0, wall, 5).unwrap_err();
        assert!(behind.to_string().contains("1000.000 s behind"), "{behind}");
        assert!(check_stamp_skew(0, u64::MAX, u64::MAX).is_ok());
        assert!(check_stamp_skew(u64::MAX, 0, u64::MAX - 1).is_err());
    }

    #[test]
    fn seconds_convert_with_inf_as_off() {
        assert_eq!(max_skew_ns_from_secs(1.5), Some(1_500_000_000));
        assert_eq!(max_skew_ns_from_secs(f64::INFINITY), Some(u64::MAX));
        for bad in [0.0, -1.0, f64::NAN] {
            assert_eq!(max_skew_ns_from_secs(bad), None);
        }
    }
}
