//! ROS 2 times (`builtin_interfaces/Time`: signed seconds and nanoseconds)
//! and shroud's stamps (nanoseconds since the Unix epoch).

use shroud_ros2::Time;

const NS_PER_S: u64 = 1_000_000_000;

/// `ns` as a ROS time; seconds past `i32::MAX` (in 2038) saturate.
pub fn time_of_ns(ns: u64) -> Time {
    Time {
        sec: i32::try_from(ns / NS_PER_S).unwrap_or(i32::MAX),
        nanosec: (ns % NS_PER_S) as u32,
    }
}

/// A ROS time as nanoseconds since the epoch: `None` for a time before it
/// or nanoseconds of a second or more (not a normalised time).
pub fn ns_of_time(time: &Time) -> Option<u64> {
    let sec = u64::try_from(time.sec).ok()?;
    (u64::from(time.nanosec) < NS_PER_S).then(|| sec * NS_PER_S + u64::from(time.nanosec))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stamps_round_trip_and_bad_times_are_refused() {
        let ns = 1_764_000_000_123_456_789;
        assert_eq!(ns_of_time(&time_of_ns(ns)), Some(ns));
        assert_eq!(
            ns_of_time(&Time {
                sec: -1,
                nanosec: 0
            }),
            None
        );
        let unnormalised = Time {
            sec: 1,
            nanosec: 1_000_000_000,
        };
        assert_eq!(ns_of_time(&unnormalised), None);
        assert_eq!(time_of_ns(u64::MAX).sec, i32::MAX);
    }
}
