//! How late a reading can be when its device sends no time, and what that
//! lateness does to where the reading is placed.
//!
//! A streaming rangefinder (a Benewake TFmini on a UART) sends one frame per
//! period and no clock of its own. The host sees only its reads: when each
//! was called, when it returned, and which bytes it returned. From these,
//! with the wire time of a frame (its bytes at the baud rate) and the
//! device's nominal period, a reading's measurement time is bounded:
//!
//! - latest: its frame's last byte was readable when the read returned, so
//!   the frame left the device at least its wire time earlier; each frame
//!   whose last byte came after it in the same read left still later, at
//!   least a period (and a wire time) after it, so a reading with `k` frames
//!   behind it in one read is at least `k` periods older than the read;
//! - earliest: the port's previous read took every byte readable when it
//!   was called, so this read's bytes became readable after that call; the
//!   read's last frame was measured at most its wire time plus the hidden
//!   latency (device processing, a USB adapter's buffering: what the host
//!   cannot see) before, and a frame with `k` frame slots behind it in the
//!   read (frames, and malformed frames that may have been one) at most `k`
//!   periods (at the slow end of the tolerance) before that.
//!
//! What the host cannot know: how long bytes sat in a buffer it never looks
//! at (the device's, an adapter's) beyond the configured hidden latency;
//! whether a read that returned one frame had waited for it or found it
//! waiting (so the interval is as wide as the gap between two reads); and
//! where inside the interval the reading really was. Without a period
//! (trigger mode, or unknown), a frame with others behind it in one read
//! has no bound, nor has any frame of a read not preceded by a known one.
//!
//! The reading is stamped at the middle of its interval: the estimate
//! whose worst-case error is smallest. A turning mount turns by at most its
//! angular speed times that error, which moves the point along a circle
//! about the turning axis.

use crate::device::{ReadWindow, StampBound};

/// How far a device's real frame period may be from its nominal one, as a
/// fraction. The Benewake manuals state the frame rate (the TFmini Plus
/// manual's frame-rate command, ID 0x03: 1-1000 Hz, 100 Hz by default) but
/// not its accuracy: 2 % covers an uncalibrated RC oscillator's drift.
pub const DEFAULT_PERIOD_TOLERANCE: f64 = 0.02;

/// What the host knows of a stream of frames that carry no device time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameTiming {
    /// Nanoseconds one frame takes on the wire: its bytes at the baud rate.
    pub wire_ns: u64,
    /// The device's nominal frame period, ns; `None` when it sends frames
    /// only when asked (trigger mode) or the period is unknown.
    pub period_ns: Option<u64>,
    /// How far the real period may be from the nominal, as a fraction.
    pub period_tolerance: f64,
    /// The longest a frame may wait unseen by the host: from its
    /// measurement to its first byte on the wire, plus from its last byte's
    /// arrival to the bytes being readable (a USB adapter's latency timer).
    pub hidden_latency_ns: u64,
}

impl FrameTiming {
    /// The shortest time between two frames: a period at the fast end of
    /// the tolerance, and never less than a frame's wire time (frames do
    /// not overlap on the wire).
    fn min_spacing_ns(&self) -> u64 {
        let period = self.period_ns.map_or(0, |p| {
            let fast = p as f64 * (1.0 - self.period_tolerance.clamp(0.0, 1.0));
            fast.max(0.0) as u64
        });
        period.max(self.wire_ns)
    }

    /// The longest time between two frames: a period at the slow end of the
    /// tolerance; `None` without a period.
    fn max_spacing_ns(&self) -> Option<u64> {
        let slow = |p: u64| (p as f64 * (1.0 + self.period_tolerance.max(0.0))).ceil() as u64;
        self.period_ns.map(slow)
    }

    /// When a frame was measured, on the host's wall clock: `window` is the
    /// read that returned its last byte; `behind` says what came after it
    /// in that read.
    pub fn interval(&self, window: ReadWindow, behind: Behind) -> StampBound {
        let Some(after) = window.after else {
            return StampBound::Unbounded;
        };
        let older_by = match (behind.slots, self.max_spacing_ns()) {
            (0, _) => 0,
            (slots, Some(spacing)) => slots.saturating_mul(spacing),
            (_, None) => return StampBound::Unbounded,
        };
        let latest = window
            .returned
            .unix_ns
            .checked_sub(self.wire_ns)
            .and_then(|t| t.checked_sub(behind.frames.saturating_mul(self.min_spacing_ns())));
        let earliest = after
            .unix_ns
            .saturating_sub(self.wire_ns)
            .saturating_sub(self.hidden_latency_ns)
            .saturating_sub(older_by);
        match latest {
            Some(latest) if latest >= earliest => StampBound::Within {
                earliest_ns: earliest,
                latest_ns: latest,
            },
            _ => StampBound::Unbounded,
        }
    }
}

/// What came after a frame in the read that returned it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Behind {
    /// Whole, valid frames: each left the device at least a period later.
    pub frames: u64,
    /// Frame slots: the frames, plus each malformed frame (a corrupted one
    /// was a frame too): at most a period each.
    pub slots: u64,
}

impl Behind {
    /// `n` valid frames and nothing else.
    pub const fn frames(n: u64) -> Self {
        Self {
            frames: n,
            slots: n,
        }
    }
}

/// The stamp inside `[earliest_ns, latest_ns]` whose worst-case error is
/// smallest: the middle.
pub fn best_estimate_ns(earliest_ns: u64, latest_ns: u64) -> u64 {
    earliest_ns + latest_ns.saturating_sub(earliest_ns) / 2
}

/// How far (ns) the true time can be from a stamp `at`, given its bound:
/// 0 for an untracked stamp (taken as exact), `None` for an unbounded one.
pub fn stamp_uncertainty_ns(bound: StampBound, at: u64) -> Option<u64> {
    match bound {
        StampBound::Untracked => Some(0),
        StampBound::Within {
            earliest_ns,
            latest_ns,
        } => Some(
            at.saturating_sub(earliest_ns)
                .max(latest_ns.saturating_sub(at)),
        ),
        StampBound::Unbounded => None,
    }
}

/// How far a point at `lever_m` metres from a turning axis moves when the
/// mount turns by up to `angle` radians either way: the chord of the arc,
/// `2 r sin(angle / 2)` (at most `r · angle`; a half turn or more can put
/// it anywhere on the circle, `2 r`).
pub fn turn_displacement_m(lever_m: f64, angle: f64) -> f64 {
    let angle = angle.abs().min(std::f64::consts::PI);
    2.0 * lever_m.abs() * (angle / 2.0).sin()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::device::HostTime;
    use proptest::prelude::*;

    const MS: u64 = 1_000_000;
    const T0: u64 = 1_700_000_000_000_000_000;

    /// A TFmini Plus at 115200 baud and 100 Hz, 1 ms of hidden latency.
    fn tfmini() -> FrameTiming {
        FrameTiming {
            wire_ns: 781_250,
            period_ns: Some(10 * MS),
            period_tolerance: DEFAULT_PERIOD_TOLERANCE,
            hidden_latency_ns: MS,
        }
    }

    fn at(unix_ns: u64) -> HostTime {
        HostTime::new(unix_ns - T0 + 5_000, unix_ns)
    }

    fn window(after: u64, returned: u64) -> ReadWindow {
        ReadWindow {
            after: Some(at(after)),
            returned: at(returned),
        }
    }

    #[test]
    fn a_frame_read_promptly_is_bounded_by_the_reads_around_it() {
        let bound = tfmini().interval(window(T0, T0 + MS), Behind::frames(0));
        assert_eq!(
            bound,
            StampBound::Within {
                earliest_ns: T0 - 781_250 - MS,
                latest_ns: T0 + MS - 781_250,
            }
        );
    }

    #[test]
    fn frames_waiting_behind_others_are_at_least_a_period_older_each() {
        // A read 30 ms after the previous returns three frames: the first
        // two were waiting, at least 2 and 1 periods (at the fast end of
        // the tolerance) before the last.
        let timing = tfmini();
        let w = window(T0, T0 + 30 * MS);
        let bounds = |k| match timing.interval(w, Behind::frames(k)) {
            StampBound::Within {
                earliest_ns,
                latest_ns,
            } => (earliest_ns, latest_ns),
            other => panic!("{other:?}"),
        };
        assert_eq!(bounds(0).1, T0 + 30 * MS - 781_250);
        assert_eq!(bounds(1).1, bounds(0).1 - 9_800_000);
        assert_eq!(bounds(2).1, bounds(0).1 - 19_600_000);
        // And at most a period at the slow end each before the last.
        assert_eq!(bounds(2).0, bounds(0).0 - 20_400_000);
        // A malformed frame behind it may have been one more period.
        let corrupted = Behind {
            frames: 1,
            slots: 2,
        };
        assert_eq!(
            timing.interval(w, corrupted),
            StampBound::Within {
                earliest_ns: bounds(2).0,
                latest_ns: bounds(1).1
            }
        );
    }

    #[test]
    fn what_the_host_cannot_date_has_no_bound() {
        let timing = tfmini();
        // No earlier read: nothing says since when the bytes waited.
        let first = ReadWindow::returned_at(at(T0));
        assert_eq!(
            timing.interval(first, Behind::frames(0)),
            StampBound::Unbounded
        );
        // Without a period, frames behind others are later by at least
        // their wire time, but nothing says by how much at most.
        let triggered = FrameTiming {
            period_ns: None,
            ..timing
        };
        let w = window(T0, T0 + 10 * MS);
        assert_eq!(
            triggered.interval(w, Behind::frames(2)),
            StampBound::Unbounded
        );
        assert!(matches!(
            triggered.interval(w, Behind::frames(0)),
            StampBound::Within { .. }
        ));
    }

    #[test]
    fn uncertainty_and_displacement() {
        let bound = StampBound::Within {
            earliest_ns: T0,
            latest_ns: T0 + 10 * MS,
        };
        let mid = best_estimate_ns(T0, T0 + 10 * MS);
        assert_eq!(mid, T0 + 5 * MS);
        assert_eq!(stamp_uncertainty_ns(bound, mid), Some(5 * MS));
        assert_eq!(stamp_uncertainty_ns(bound, T0 + 2 * MS), Some(8 * MS));
        assert_eq!(stamp_uncertainty_ns(StampBound::Untracked, T0), Some(0));
        assert_eq!(stamp_uncertainty_ns(StampBound::Unbounded, T0), None);
        let quarter = turn_displacement_m(2.0, std::f64::consts::FRAC_PI_2);
        assert!((quarter - 2.0 * 2f64.sqrt()).abs() < 1e-12);
        assert_eq!(turn_displacement_m(2.0, 10.0), 4.0);
        assert_eq!(turn_displacement_m(2.0, 0.0), 0.0);
    }

    proptest! {
        /// A device streaming at a period within the tolerance, with frames
        /// waiting up to the hidden latency before they can be read, and a
        /// host that reads whenever it likes: every frame's true time lies
        /// in its interval (or the interval says there is none), and the
        /// middle is never further from it than the stated uncertainty.
        #[test]
        fn the_true_time_is_inside_every_bound_given(
            period_us in 1_000u64..50_000,
            drift in -0.02f64..0.02,
            hidden_us in 0u64..5_000,
            reads in proptest::collection::vec(0u64..60_000, 1..40),
            delays in proptest::collection::vec(0.0f64..1.0, 40),
        ) {
            let timing = FrameTiming {
                wire_ns: 781_250,
                period_ns: Some(period_us * 1_000),
                period_tolerance: DEFAULT_PERIOD_TOLERANCE,
                hidden_latency_ns: hidden_us * 1_000,
            };
            let real_period = (period_us as f64 * 1_000.0 * (1.0 + drift)).max(781_250.0);
            // Frame k measured at T0 + k·period, readable after its wire
            // time and a share of the hidden latency.
            let measured = |k: usize| T0 + (k as f64 * real_period) as u64;
            let readable = |k: usize| {
                measured(k) + 781_250 + (delays[k % delays.len()] * hidden_us as f64 * 1_000.0) as u64
            };
            // Reads called at increasing times, each returning what is readable.
            let mut call = T0;
            let mut next = 0usize;
            let mut previous_call: Option<u64> = None;
            for gap in reads {
                let returned = call + gap * 1_000;
                // The kernel hands over what is readable at some instant
                // between the call and the return.
                let copied = call + gap * 500;
                let mut got = Vec::new();
                while readable(next) <= copied {
                    got.push(next);
                    next += 1;
                }
                let w = ReadWindow {
                    after: previous_call.map(at),
                    returned: at(returned),
                };
                for (i, k) in got.iter().enumerate() {
                    let behind = Behind::frames((got.len() - 1 - i) as u64);
                    if let StampBound::Within { earliest_ns, latest_ns } = timing.interval(w, behind) {
                        let truth = measured(*k);
                        prop_assert!(earliest_ns <= truth && truth <= latest_ns,
                            "frame {k}: {truth} not in [{earliest_ns}, {latest_ns}]");
                        let mid = best_estimate_ns(earliest_ns, latest_ns);
                        let within = StampBound::Within { earliest_ns, latest_ns };
                        let bound = stamp_uncertainty_ns(within, mid);
                        prop_assert!(bound.is_some_and(|b| truth.abs_diff(mid) <= b));
                    }
                }
                previous_call = Some(call);
                call = returned;
            }
        }
    }
}
