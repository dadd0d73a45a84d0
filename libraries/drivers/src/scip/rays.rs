//! Turns decoded scan values into rays: angles, ranges in metres, per-ray
//! times. Everything that depends only on the geometry and the request is
//! computed once per stream ([`ScanPlan`]). Every echo of a multi-echo step
//! becomes its own ray with the step's angle and time.

use super::command::{ScanRequest, MAX_ECHOES};
use super::params::ScipGeometry;
use super::scan_data::ScanData;
use crate::device::Ray;

/// The rays' fixed layout for one geometry and request.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanPlan {
    angles: Vec<f32>,
    offsets_ns: Vec<u32>,
    dmin_mm: u32,
    dmax_mm: u32,
    first_ray_delay_ns: u64,
}

impl ScanPlan {
    /// Ray `i` covers steps `start + i*cluster ..` and takes the angle and
    /// time of the cluster's first step: urg_node `src/urg_c_wrapper.cpp`
    /// (`getAngleMin()` = the start step's angle, `getAngleIncrement()` =
    /// cluster steps per ray, `getTimeIncrement()` = cluster steps' time).
    /// A step takes 60e9 / (`SCAN` * `ARES`) ns.
    pub fn new(geometry: &ScipGeometry, request: &ScanRequest) -> Self {
        let cluster = u32::from(request.cluster.max(1));
        let steps = (0..request.value_count() as u32)
            .map(|i| (u32::from(request.start) + i * cluster, i * cluster));
        let step_ns = geometry.step_ns();
        let (angles, offsets_ns) = steps
            .map(|(step, from_first)| {
                let offset = (f64::from(from_first) * step_ns).round();
                (
                    geometry.angle(step) as f32,
                    offset.min(f64::from(u32::MAX)) as u32,
                )
            })
            .unzip();
        Self {
            angles,
            offsets_ns,
            dmin_mm: geometry.dmin_mm,
            dmax_mm: geometry.dmax_mm,
            first_ray_delay_ns: first_ray_delay_ns(geometry, request.start),
        }
    }

    /// How many steps (clusters) a scan has: its rays, or for multi-echo
    /// scans its first echoes.
    pub fn ray_count(&self) -> usize {
        self.angles.len()
    }

    /// Nanoseconds from the instant the sensor's scan timestamp marks to the
    /// first ray; see [`first_ray_delay_ns`].
    pub fn first_ray_delay_ns(&self) -> u64 {
        self.first_ray_delay_ns
    }

    /// Nanoseconds from the first ray to the last.
    pub fn sweep_ns(&self) -> u64 {
        self.offsets_ns.last().copied().map_or(0, u64::from)
    }

    /// The rays of `data`, or `None` when it has the wrong number of values
    /// (the decoder already checks this; a scan is never delivered with a
    /// hole). Each value is a ray; a multi-echo step's echoes follow each
    /// other with the step's angle and offset, first echo first. Ranges below
    /// `DMIN` (error codes) or above `DMAX` become NaN.
    pub fn rays(&self, data: &ScanData) -> Option<Vec<Ray>> {
        let slots = self.slot_of_values(data)?;
        if data
            .intensities
            .as_ref()
            .is_some_and(|i| i.len() != data.ranges.len())
        {
            return None;
        }
        let rays = slots
            .iter()
            .zip(&data.ranges)
            .enumerate()
            .map(|(k, (&slot, &mm))| {
                Some(Ray {
                    angle: *self.angles.get(slot)?,
                    range: self.metres(mm),
                    intensity: match &data.intensities {
                        Some(values) => Some(*values.get(k)? as f32),
                        None => None,
                    },
                    offset_ns: *self.offsets_ns.get(slot)?,
                })
            });
        rays.collect()
    }

    /// The step slot of every value of `data`, or `None` when the counts
    /// disagree with the plan (or a step claims 0 or more than 3 echoes).
    fn slot_of_values(&self, data: &ScanData) -> Option<Vec<usize>> {
        let echo_range = 1..=MAX_ECHOES as u8;
        let slots: Vec<usize> = match &data.echoes {
            None if data.ranges.len() == self.ray_count() => (0..self.ray_count()).collect(),
            Some(counts)
                if counts.len() == self.ray_count()
                    && counts.iter().all(|n| echo_range.contains(n)) =>
            {
                counts
                    .iter()
                    .enumerate()
                    .flat_map(|(slot, &n)| std::iter::repeat_n(slot, usize::from(n)))
                    .collect()
            }
            _ => return None,
        };
        (slots.len() == data.ranges.len()).then_some(slots)
    }

    fn metres(&self, mm: u32) -> f32 {
        if mm < self.dmin_mm || mm > self.dmax_mm {
            f32::NAN
        } else {
            mm as f32 / 1000.0
        }
    }
}

/// Nanoseconds from the instant a scan's timestamp marks to its first ray
/// (step `start`). Assumption: the sensor's timestamp marks the moment the
/// beam passes the rear centre, angle ±π, i.e. step `AFRT - ARES/2`, as
/// urg_node assumes (`src/urg_c_wrapper.cpp` `getAngularTimeOffset()`:
/// "Hokuyo's timestamps start from the rear center of the device"). The beam
/// turns counter-clockwise (spec C-42-03320B §5), so it reaches `start` after
/// `(start - AFRT + ARES/2) mod ARES` steps.
pub fn first_ray_delay_ns(geometry: &ScipGeometry, start: u16) -> u64 {
    let ares = i64::from(geometry.ares);
    let rear = i64::from(geometry.afrt) - ares / 2;
    let steps = (i64::from(start) - rear).rem_euclid(ares);
    (steps as f64 * geometry.step_ns()).round() as u64
}
