//! [`SpeedMonitor`]: the largest speed scale at which every link keeps the
//! protective separation distance, and the joint speeds it assumes.

use super::lever::LeverArms;
use super::motion::ArmMotion;
use super::protective::{protective, MotionNow, Protective, Timing};
use crate::{ArmModel, GuardError};

/// Bisection steps: the scale is found to `2^-40`, always from below.
const STEPS: u32 = 40;

/// Relative tolerance of a measured joint speed over its limit (encoder
/// differentiation noise) before the joint state counts as over the limit.
pub const OVER_LIMIT_TOLERANCE: f64 = 0.05;

/// The scale chosen for one pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedScale {
    /// In [0, 1]: the fraction of each joint's velocity limit the arm may move at.
    pub scale: f64,
    /// The link whose separation keeps the scale below 1 (`None` at 1).
    pub limiting_link: Option<usize>,
    /// That link's `S_p` at the scale (metres, `C` included), or the stop
    /// distance at scale 1. At scale 0, what it needs to stop, or, when
    /// stopping now keeps the separation but no speed above 0 does, what the
    /// slowest motion would need.
    pub protective_distance: f64,
}

impl SpeedScale {
    /// What a verdict without speed monitoring says: full speed or none.
    pub fn binary(clear: bool, stop_distance: f64) -> Self {
        Self {
            scale: if clear { 1.0 } else { 0.0 },
            limiting_link: None,
            protective_distance: stop_distance,
        }
    }
}

/// Speed and separation monitoring for one arm.
#[derive(Debug, Clone)]
pub struct SpeedMonitor {
    motion: ArmMotion,
    levers: LeverArms,
    /// The actuated joints' names, for reasons.
    names: Vec<String>,
}

/// A joint whose measured speed is over its limit: the arm is not obeying
/// the guard, or its joint state is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct OverLimit {
    pub joint: usize,
    pub speed: f64,
    pub limit: f64,
}

impl SpeedMonitor {
    pub fn new(arm: &ArmModel, motion: ArmMotion) -> Result<Self, GuardError> {
        motion.validate(arm)?;
        Ok(Self {
            levers: LeverArms::new(arm)?,
            motion,
            names: arm.actuated_joints().map(|j| j.name().to_owned()).collect(),
        })
    }

    /// The name of actuated joint `joint` (`?` when out of range).
    pub fn joint_name(&self, joint: usize) -> &str {
        self.names.get(joint).map_or("?", String::as_str)
    }

    pub fn motion(&self) -> &ArmMotion {
        &self.motion
    }

    /// How far back a published scale can still drive the arm, seen from a
    /// decision on a joint state at most `horizon` old: the joint state's
    /// age, the verdict's horizon, the reaction time and the longest stop
    /// (from the highest speed a joint state may report).
    pub fn window(&self, horizon: f64) -> f64 {
        2.0 * horizon
            + self.motion.reaction_time
            + self.motion.longest_stop(1.0 + OVER_LIMIT_TOLERANCE)
    }

    /// Links this monitor bounds.
    pub fn links(&self) -> usize {
        self.levers.links()
    }

    /// Per actuated joint, the fastest it may be moving until a new verdict
    /// takes effect: its measured speed or `in_force` times its limit,
    /// whichever is faster (without measurements, `in_force` times the
    /// limit). A measured
    /// speed over the limit (beyond [`OVER_LIMIT_TOLERANCE`]) is returned as
    /// an error: the arm is not where the guard can bound it.
    pub fn current_speeds(
        &self,
        measured: Option<&[f64]>,
        in_force: f64,
    ) -> Result<Vec<f64>, OverLimit> {
        let mut speeds = Vec::with_capacity(self.motion.joints.len());
        for (joint, motion) in self.motion.joints.iter().enumerate() {
            let allowed = in_force * motion.max_velocity;
            let speed = measured.and_then(|m| m.get(joint)).map_or(0.0, |v| v.abs());
            if !(speed <= motion.max_velocity * (1.0 + OVER_LIMIT_TOLERANCE)) {
                return Err(OverLimit {
                    joint,
                    speed,
                    limit: motion.max_velocity,
                });
            }
            speeds.push(speed.max(allowed));
        }
        Ok(speeds)
    }

    /// `S_p - C` of every link at `scale`.
    fn needs(&self, now: &MotionNow, timing: &Timing, scale: f64) -> Vec<Protective> {
        (0..self.levers.links())
            .map(|link| protective(&self.motion, &self.levers, link, now, timing, scale))
            .collect()
    }

    /// The link with the least margin `clearance - stop - S_p` at `scale`, and
    /// that margin and `S_p`.
    fn tightest(
        &self,
        clearances: &[f64],
        stop_distance: f64,
        now: &MotionNow,
        timing: &Timing,
        scale: f64,
    ) -> (usize, f64, f64) {
        let needs = self.needs(now, timing, scale);
        let mut best = (0, f64::INFINITY, stop_distance);
        for (link, need) in needs.iter().enumerate() {
            let clearance = clearances.get(link).copied().unwrap_or(0.0);
            let sp = stop_distance + need.total();
            let margin = clearance - sp;
            // NaN margins count as the tightest: never a reason to move.
            if !(margin >= best.1) {
                best = (link, margin, sp);
            }
        }
        best
    }

    /// The largest scale in [0, 1] (to within `2^-40`, from below) at which
    /// every link's clearance (`clearances[link]`, after the guard's motion
    /// allowance) is at least the stop distance plus `S_p - C`. Scale 0 when
    /// even stopping now leaves some link short: the guard must stop.
    pub fn scale(
        &self,
        clearances: &[f64],
        stop_distance: f64,
        now: &MotionNow,
        timing: &Timing,
    ) -> SpeedScale {
        // Lengths that do not match the arm would drop links or joints from
        // the bound: never a reason to move.
        if clearances.len() != self.levers.links() || now.speeds.len() != self.motion.joints.len() {
            return SpeedScale::binary(false, stop_distance);
        }
        let at = |s: f64| self.tightest(clearances, stop_distance, now, timing, s);
        let (link, margin, sp) = at(0.0);
        if !(margin >= 0.0) {
            return SpeedScale {
                scale: 0.0,
                limiting_link: Some(link),
                protective_distance: sp,
            };
        }
        if at(1.0).1 >= 0.0 {
            return SpeedScale {
                scale: 1.0,
                limiting_link: None,
                protective_distance: stop_distance,
            };
        }
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..STEPS {
            let mid = 0.5 * (lo + hi);
            if at(mid).1 >= 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let (link, _, sp_hi) = at(hi);
        // Stopping now keeps the separation but no speed above 0 does (a
        // measured stop is never shorter than its slowest sample): scale 0,
        // with what the slowest motion would need.
        let sp = if lo == 0.0 { sp_hi } else { at(lo).2 };
        SpeedScale {
            scale: lo,
            limiting_link: Some(link),
            protective_distance: sp,
        }
    }

    /// The largest `S_p` (stop distance included) any link needs at `scale`.
    pub fn needed_at(
        &self,
        clearances: &[f64],
        stop_distance: f64,
        now: &MotionNow,
        timing: &Timing,
        scale: f64,
    ) -> f64 {
        self.needs(now, timing, scale)
            .iter()
            .zip(clearances)
            .map(|(need, _)| stop_distance + need.total())
            .fold(stop_distance, f64::max)
    }

    /// The largest `S_p` any link can need (full speed everywhere): the
    /// clearance worth computing exactly for scale 1 to be reachable.
    pub fn largest_need(&self, stop_distance: f64, timing: &Timing) -> f64 {
        let full: Vec<f64> = self.motion.joints.iter().map(|j| j.max_velocity).collect();
        let now = MotionNow {
            speeds: &full,
            joint_state_age: 0.0,
        };
        self.needs(&now, timing, 1.0)
            .iter()
            .map(Protective::total)
            .fold(0.0, f64::max)
            + stop_distance
    }
}
