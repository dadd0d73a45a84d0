//! A decoded scan of a planar lidar or a single-beam rangefinder: rays in the
//! sensor's plane, each with its own time, before any mount places them in 3D.

use super::time::HostTime;

/// One ray of a range sensor, in the sensor's frame (REP-103): it leaves the
/// origin in the x-y plane at `angle` radians counter-clockwise from +x.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Radians, counter-clockwise from the sensor's +x (forward) axis.
    pub angle: f32,
    /// Metres to the return. `NaN` when the device reported no valid return
    /// (below its minimum range, an error code, too weak, saturated): such rays
    /// are kept so that a scan always has every ray the device sent, and never
    /// become points.
    pub range: f32,
    /// The device's raw return strength (unscaled), if it sends one.
    pub intensity: Option<f32>,
    /// Nanoseconds from the scan's first ray to this one (>= 0), from the
    /// device's timing model (scan speed, sample period).
    pub offset_ns: u32,
}

impl Ray {
    /// Whether this ray is a measurement (finite, positive range).
    pub fn is_valid(&self) -> bool {
        self.range.is_finite() && self.range > 0.0
    }
}

/// How well a scan's time is known, when the device sends none and the
/// driver dates it from when its bytes were read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StampBound {
    /// The driver does not bound it: the device has a clock of its own, or
    /// the driver was not told when the bytes were read. The stamp is taken
    /// as exact.
    #[default]
    Untracked,
    /// The first ray was measured within `[earliest_ns, latest_ns]` on the
    /// host's wall clock; `stamp_ns` is the driver's best estimate inside.
    Within { earliest_ns: u64, latest_ns: u64 },
    /// What the host saw contradicts the device's timing model (more frames
    /// than the device sends in the time the host could see them arrive),
    /// or says nothing (no earlier read to compare with): the scan's time
    /// has no bound.
    Unbounded,
}

/// One complete scan (a revolution, a sweep of the field of view, or one
/// reading of a single-beam sensor), as a driver delivers it. A scan that lost
/// any of its bytes is never delivered: it is counted as an error instead.
#[derive(Debug, Clone, PartialEq)]
pub struct RangeScan {
    /// The driver's scan counter (wraps).
    pub sequence: u32,
    /// The first ray's time on the host's wall clock, ns since the Unix epoch,
    /// from the device's clock mapped to the host's (or back-dated from the
    /// arrival of its bytes by the device's timing model).
    pub stamp_ns: u64,
    /// When the scan's last byte was handed to the driver, or earlier (a
    /// driver that learns a scan is complete only from later bytes, as an
    /// RPLIDAR from the next capsule, dates it from its last sample): a
    /// cloud's age in shroud counts from here, so this is never later than
    /// the data's arrival.
    pub received: HostTime,
    /// Rays in the order the device measured them.
    pub rays: Vec<Ray>,
    /// How far `stamp_ns` can be from the time the first ray was measured.
    pub stamp_bound: StampBound,
}

impl RangeScan {
    /// How many rays hold a measurement.
    pub fn valid_rays(&self) -> usize {
        self.rays.iter().filter(|r| r.is_valid()).count()
    }

    /// Whether the device sent a strength with every ray.
    pub fn has_intensity(&self) -> bool {
        !self.rays.is_empty() && self.rays.iter().all(|r| r.intensity.is_some())
    }
}
