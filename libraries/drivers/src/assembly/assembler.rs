//! The scan-to-cloud assembler: places each ray through the mount at its own
//! time and cuts the stream of points into clouds.

use super::error::AssemblyError;
use super::joint_track::JointTrack;
use super::lateness::{stamp_uncertainty_ns, turn_displacement_m};
use super::motion::{MountMotion, MovingMount};
use super::pose::MountPose;
use super::window::CloudWindow;
use crate::device::{HostTime, RangeScan, StampBound};
use crate::Scan;
use glam::DVec3;
use std::collections::VecDeque;

/// Rays (of all scans) kept waiting for joint samples that cover them: about
/// a second of the fastest lidar here (a UTM-30LX sends 43 000 rays a
/// second), so the wait is bounded by `max_joint_wait_ns`, not by this.
const MAX_WAITING_RAYS: usize = 65_536;

/// The largest position error (metres) a placed reading may have, unless
/// configured otherwise: a quarter metre, the order of a robot's safety
/// margin; a reading less sure of its place is dropped.
pub const DEFAULT_MAX_POSITION_ERROR_M: f64 = 0.25;

/// How scans become clouds.
#[derive(Debug, Clone, PartialEq)]
pub struct AssemblyConfig {
    pub mount: MovingMount,
    pub window: CloudWindow,
    /// A cloud reaching this many points is published at once.
    pub max_points: usize,
    /// Longest two joint samples may be apart and still be interpolated.
    pub max_joint_gap_ns: u64,
    /// Longest a scan waits (on the monotonic clock) for joint samples
    /// covering its last ray before it is dropped.
    pub max_joint_wait_ns: u64,
    /// A reading whose position error bound (from the uncertainty of its
    /// time, [`StampBound`], and the mount's motion) exceeds this many
    /// metres is dropped and counted (the status counter `readings_late_beyond_bound`).
    pub max_position_error_m: f64,
}

impl AssemblyConfig {
    /// Each scan its own cloud, from a mount that does not move.
    pub fn fixed(mount: MovingMount) -> Self {
        Self {
            mount,
            window: CloudWindow::Scans(1),
            max_points: 4_000_000,
            max_joint_gap_ns: 200_000_000,
            max_joint_wait_ns: 500_000_000,
            max_position_error_m: DEFAULT_MAX_POSITION_ERROR_M,
        }
    }
}

/// A cloud ready to publish.
#[derive(Debug, Clone, PartialEq)]
pub struct AssembledCloud {
    /// Points in the robot's frame; `stamp_ns` is the earliest ray's time,
    /// `sequence` counts clouds.
    pub cloud: Scan,
    /// When the last byte of the cloud's first scan reached the host: the
    /// cloud's age in shroud is counted from here.
    pub first_received: HostTime,
    /// When the last byte of its last scan did.
    pub last_received: HostTime,
    /// Scans that contributed rays.
    pub scans: u32,
    /// The largest position error bound of its points, metres (0 when every
    /// point's time was taken as exact).
    pub position_error_m: f64,
}

/// What the assembler counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct AssemblyStats {
    pub scans: u64,
    pub clouds: u64,
    pub points: u64,
    /// Rays without a measurement (the device's invalid readings).
    pub invalid_rays: u64,
    /// Scans dropped because the joint samples did not cover their rays
    /// (too old, a gap, or none arrived in time).
    pub mount_angle_missing: u64,
    /// Joint samples refused (non-finite, or not later than the last).
    pub joint_samples_refused: u64,
    /// Valid readings dropped: their time has no bound
    /// (the status counter `readings_late_unbounded`).
    pub readings_late_unbounded: u64,
    /// Valid readings dropped: their position error bound exceeds the
    /// configured maximum (the status counter `readings_late_beyond_bound`).
    pub readings_late_beyond_bound: u64,
}

/// The cloud being filled.
#[derive(Debug, Default)]
struct Partial {
    key: Option<u64>,
    points: Vec<[f32; 3]>,
    intensity: Vec<f32>,
    all_intensity: bool,
    stamp_ns: Option<u64>,
    first_received: Option<HostTime>,
    last_received: HostTime,
    scans: u32,
    last_scan: Option<u64>,
    position_error_m: f64,
}

/// Turns range scans into clouds ([`AssemblyConfig`]).
#[derive(Debug)]
pub struct CloudAssembler {
    config: AssemblyConfig,
    track: JointTrack,
    waiting: VecDeque<RangeScan>,
    waiting_rays: usize,
    /// Waiting scans still to go through before a flushed cloud completes.
    flush_after: usize,
    partial: Partial,
    scans_seen: u64,
    stats: AssemblyStats,
}

impl CloudAssembler {
    pub fn new(config: AssemblyConfig) -> Result<Self, AssemblyError> {
        if config.window == CloudWindow::Sweep && !config.mount.sweeps() {
            return Err(AssemblyError::Invalid(
                "a cloud per sweep needs a moving mount (a sweep profile or a joint)".into(),
            ));
        }
        let axis = config.mount.axis;
        if !(axis.is_finite() && (axis.length() - 1.0).abs() < 1e-6) {
            return Err(AssemblyError::Invalid(format!(
                "the mount's axis {axis} must have unit length"
            )));
        }
        if config.max_points == 0 {
            return Err(AssemblyError::Invalid("max_points must be positive".into()));
        }
        if !(config.max_position_error_m > 0.0) {
            return Err(AssemblyError::Invalid(format!(
                "the largest position error {} m must be positive",
                config.max_position_error_m
            )));
        }
        Ok(Self {
            track: JointTrack::new(config.max_joint_gap_ns),
            config,
            waiting: VecDeque::new(),
            waiting_rays: 0,
            flush_after: 0,
            partial: Partial::default(),
            scans_seen: 0,
            stats: AssemblyStats::default(),
        })
    }

    pub fn stats(&self) -> &AssemblyStats {
        &self.stats
    }

    /// Whether the mount's angle comes from joint samples.
    pub fn needs_joints(&self) -> bool {
        matches!(self.config.mount.motion, MountMotion::Joint { .. })
    }

    /// Adds a joint sample of the mount (its time on the wall clock, its
    /// angle in radians), then places the scans it lets through.
    pub fn push_joint(&mut self, unix_ns: u64, angle: f64, out: &mut Vec<AssembledCloud>) {
        if !self.track.push(unix_ns, angle) {
            self.stats.joint_samples_refused += 1;
        }
        self.place_waiting(out);
    }

    /// Adds a scan; completed clouds are appended to `out`.
    pub fn push_scan(&mut self, scan: RangeScan, out: &mut Vec<AssembledCloud>) {
        self.stats.scans += 1;
        self.waiting_rays += scan.rays.len();
        self.waiting.push_back(scan);
        while self.waiting_rays > MAX_WAITING_RAYS && self.waiting.len() > 1 {
            self.pop_waiting();
            self.stats.mount_angle_missing += 1;
            self.after_waiting(out);
        }
        self.place_waiting(out);
    }

    /// Publishes the cloud being filled now, however far its window is: when
    /// the device went away, so that its scans are not merged with scans
    /// from after the reconnect.
    pub fn flush(&mut self, out: &mut Vec<AssembledCloud>) {
        // Scans still waiting for joint samples belong to the cloud too: it is
        // completed once the last of them is placed or dropped.
        self.flush_after = self.waiting.len();
        if self.flush_after == 0 {
            self.complete(out);
        }
    }

    /// Points in the cloud being filled (lost if the assembler is dropped).
    pub fn pending_points(&self) -> usize {
        self.partial.points.len()
    }

    fn pop_waiting(&mut self) -> Option<RangeScan> {
        let scan = self.waiting.pop_front()?;
        self.waiting_rays -= scan.rays.len();
        Some(scan)
    }

    /// After a waiting scan was placed or dropped: completes a flushed cloud
    /// once the scans that were waiting at the flush are all through.
    fn after_waiting(&mut self, out: &mut Vec<AssembledCloud>) {
        if self.flush_after > 0 {
            self.flush_after -= 1;
            if self.flush_after == 0 {
                self.complete(out);
            }
        }
    }

    /// Drops scans that have waited longer than allowed for joint samples.
    pub fn expire(&mut self, now: HostTime, out: &mut Vec<AssembledCloud>) {
        let limit = self.config.max_joint_wait_ns;
        while self
            .waiting
            .front()
            .is_some_and(|s| now.since(s.received) > limit)
        {
            self.pop_waiting();
            self.stats.mount_angle_missing += 1;
            self.after_waiting(out);
        }
    }

    /// Places waiting scans in order, as long as the mount's angle is known
    /// over each one's rays.
    fn place_waiting(&mut self, out: &mut Vec<AssembledCloud>) {
        while let Some(scan) = self.waiting.front() {
            match self.coverage(scan) {
                Coverage::Wait => return,
                Coverage::Lost => {
                    self.pop_waiting();
                    self.stats.mount_angle_missing += 1;
                    self.after_waiting(out);
                }
                Coverage::Known => {
                    if let Some(scan) = self.pop_waiting() {
                        self.place(&scan, out);
                    }
                    self.after_waiting(out);
                }
            }
        }
    }

    fn coverage(&self, scan: &RangeScan) -> Coverage {
        if !self.needs_joints() {
            return Coverage::Known;
        }
        // A reading of uncertain time needs the angle over all of its bound.
        let (first, last) = match scan.stamp_bound {
            StampBound::Within {
                earliest_ns,
                latest_ns,
            } => (scan.stamp_ns.min(earliest_ns), scan.stamp_ns.max(latest_ns)),
            _ => (scan.stamp_ns, scan.stamp_ns),
        };
        let last = last.saturating_add(scan.rays.last().map_or(0, |r| r.offset_ns as u64));
        match (self.track.earliest_ns(), self.track.latest_ns()) {
            (Some(early), Some(_)) if early > first => Coverage::Lost,
            (Some(_), Some(late)) if late >= last => Coverage::Known,
            _ => Coverage::Wait,
        }
    }

    /// Places every ray of `scan`, completing clouds where the window says.
    fn place(&mut self, scan: &RangeScan, out: &mut Vec<AssembledCloud>) {
        let index = self.scans_seen;
        self.scans_seen += 1;
        let intensity = scan.has_intensity();
        let mut rays = Vec::with_capacity(scan.rays.len());
        for ray in &scan.rays {
            let time = scan.stamp_ns.saturating_add(ray.offset_ns as u64);
            let Some((angle, sweep)) = self.config.mount.angle_at(time, &self.track) else {
                // A gap in the joint samples inside the scan: the scan is lost whole.
                self.stats.mount_angle_missing += 1;
                return;
            };
            rays.push((ray, time, angle, sweep));
        }
        // A fixed mount (and a unit between joint samples) keeps its angle
        // from ray to ray: its pose is composed once, not per ray.
        let mut pose: Option<(f64, MountPose)> = None;
        for (ray, time, angle, sweep) in rays {
            let key = match self.config.window {
                CloudWindow::Sweep => sweep,
                CloudWindow::Scans(n) => index / n as u64,
                CloudWindow::Time(ns) => time / ns,
            };
            if self.partial.key.is_some_and(|k| k != key) {
                self.complete(out);
            }
            if !ray.is_valid() {
                self.stats.invalid_rays += 1;
                continue;
            }
            let local = DVec3::new(
                ray.range as f64 * (ray.angle as f64).cos(),
                ray.range as f64 * (ray.angle as f64).sin(),
                0.0,
            );
            let at = match pose {
                Some((a, p)) if a == angle => p,
                _ => self.config.mount.pose_at_angle(angle),
            };
            pose = Some((angle, at));
            let placed = at.apply(local);
            let point = placed.as_vec3();
            if !point.is_finite() {
                self.stats.invalid_rays += 1;
                continue;
            }
            let Some(turn) = self.angle_uncertainty(scan.stamp_bound, ray.offset_ns, time) else {
                self.stats.readings_late_unbounded += 1;
                continue;
            };
            let error = turn_displacement_m(self.lever_m(placed), turn);
            if !(error <= self.config.max_position_error_m) {
                self.stats.readings_late_beyond_bound += 1;
                continue;
            }
            self.add_point(
                key,
                point.to_array(),
                ray.intensity,
                intensity,
                time,
                index,
                scan,
                error,
            );
            if self.partial.points.len() >= self.config.max_points {
                self.complete(out);
            }
        }
        if let CloudWindow::Scans(n) = self.config.window {
            if (index + 1).is_multiple_of(n as u64) {
                self.complete(out);
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn add_point(
        &mut self,
        key: u64,
        point: [f32; 3],
        value: Option<f32>,
        scan_has_intensity: bool,
        time: u64,
        index: u64,
        scan: &RangeScan,
        position_error_m: f64,
    ) {
        let p = &mut self.partial;
        p.position_error_m = p.position_error_m.max(position_error_m);
        if p.key.is_none() {
            p.key = Some(key);
            p.all_intensity = true;
        }
        p.all_intensity &= scan_has_intensity;
        if p.last_scan != Some(index) {
            p.last_scan = Some(index);
            p.scans += 1;
            p.first_received.get_or_insert(scan.received);
            p.last_received = scan.received;
        }
        p.stamp_ns = Some(p.stamp_ns.map_or(time, |s| s.min(time)));
        p.points.push(point);
        p.intensity.push(value.unwrap_or(0.0));
    }

    /// Hands the cloud being filled to `out` (if it has points) and starts
    /// the next.
    fn complete(&mut self, out: &mut Vec<AssembledCloud>) {
        let p = std::mem::take(&mut self.partial);
        let (Some(stamp_ns), Some(first_received)) = (p.stamp_ns, p.first_received) else {
            return;
        };
        let mut cloud = Scan::new(self.stats.clouds as u32, stamp_ns, p.points);
        if p.all_intensity {
            cloud.intensity = Some(p.intensity);
        }
        self.stats.clouds += 1;
        self.stats.points += cloud.points.len() as u64;
        out.push(AssembledCloud {
            cloud,
            first_received,
            last_received: p.last_received,
            scans: p.scans,
            position_error_m: p.position_error_m,
        });
    }

    /// How far (radians) the mount may have turned between the time a ray
    /// is placed at and the time it was measured, given its scan's
    /// [`StampBound`]; `None` when that is unknown.
    fn angle_uncertainty(&self, bound: StampBound, offset_ns: u32, time: u64) -> Option<f64> {
        let bound = match bound {
            StampBound::Within {
                earliest_ns,
                latest_ns,
            } => StampBound::Within {
                earliest_ns: earliest_ns.saturating_add(offset_ns as u64),
                latest_ns: latest_ns.saturating_add(offset_ns as u64),
            },
            other => other,
        };
        let dt_ns = stamp_uncertainty_ns(bound, time)?;
        match (&self.config.mount.motion, bound) {
            (MountMotion::Fixed, _) => Some(0.0),
            (_, StampBound::Untracked) => Some(0.0),
            // The profile's speed bound over the whole uncertainty.
            (MountMotion::Profile(p), _) => Some(p.max_speed() * dt_ns as f64 * 1e-9),
            // The joint's observed motion over the ray's time bound.
            (
                MountMotion::Joint { .. },
                StampBound::Within {
                    earliest_ns,
                    latest_ns,
                },
            ) => self.track.max_deviation(time, earliest_ns, latest_ns),
            (MountMotion::Joint { .. }, StampBound::Unbounded) => None,
        }
    }

    /// Distance (m) of a placed point from the mount's turning axis: the
    /// radius of the circle an error in the mount's angle moves it along.
    fn lever_m(&self, point: glam::DVec3) -> f64 {
        let base = &self.config.mount.base;
        let axis = base.rotation * self.config.mount.axis;
        (point - base.translation).cross(axis).length()
    }
}

enum Coverage {
    /// The samples cover the scan's rays.
    Known,
    /// Samples covering the scan's last ray may still come.
    Wait,
    /// They never will: the scan began before the oldest sample kept.
    Lost,
}
