//! A brute-force soundness harness for shroud's collision guard (issue 23):
//! random scenes of moving solids scanned by random sensors at their own
//! times, each cloud fitted and combined by shroud's real fitter and guard,
//! and every verdict checked against exact geometry computed here.
//!
//! The truth never comes from shroud's fit, envelope or clearance code:
//! [`solids`] and [`truth`] compute distances from the shapes' definitions,
//! [`rays`] casts the sensors' rays exactly. A verdict is *optimistic* when
//! it is `clear` while some arm shape comes closer to a solid or the floor,
//! over the decision's horizon, than the stop distance less the sampling
//! margin (the largest gap between neighbouring rays at a sensor's maximum
//! range: the guard can only promise distance to what was sampled).

pub mod arms;
pub mod rays;
pub mod report;
pub mod run;
pub mod scene;
pub mod sensors;
pub mod separation;
pub mod solids;
pub mod truth;

pub use arms::{ArmKind, Arms, URDF_ARM};
pub use report::{Finding, FindingClass, SoundnessReport, VerdictCounts};
pub use run::{minimise, run, run_case, scene_seed};
pub use scene::{SensorSetup, SoundnessScene};
pub use sensors::{EmptyRayIndex, FieldOfView, Projection, Scan, Sensor};
pub use solids::{Body, Solid};

use shroud_guard::{GuardError, UnobservedPolicy};

/// Why a soundness run could not run (never why a verdict was wrong: those
/// are counted in the report).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SoundnessError {
    /// A parameter is out of its range.
    #[error("soundness parameter `{parameter}` {reason}, got {value}")]
    BadParameter {
        parameter: &'static str,
        reason: &'static str,
        value: f64,
    },
    /// The arms or the guard refused their configuration.
    #[error("guard: {0}")]
    Guard(#[from] GuardError),
}

/// What a run draws and how the guard is set up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoundnessParams {
    /// The guard's stop distance (m).
    pub stop_distance: f64,
    /// Bound on every solid's speed, and the guard's `max_obstacle_speed`
    /// (m/s).
    pub max_obstacle_speed: f64,
    /// The guard's horizon (s): truth is the minimum over [decision,
    /// decision + horizon].
    pub horizon: f64,
    /// The guard's max age (s).
    pub max_age: f64,
    /// Verdicts per scene: arm configurations x `timings_per_pose`.
    pub verdicts_per_case: usize,
    /// Decision times per arm configuration.
    pub timings_per_pose: usize,
    /// Most rays one sensor casts.
    pub max_rays: usize,
    /// Fewest points a cloud needs to be fitted.
    pub min_points: usize,
    /// Probability that a view is fitted as a sandwich (else upper only).
    pub sandwich_share: f64,
    /// Probability that a solid is black (returns no range).
    pub black_share: f64,
    /// Sensors cast parallel rays along their look direction (the sensor
    /// the guard's views assume) instead of rays from a point.
    pub parallel_rays: bool,
    /// Clouds state their sensor's field of view (a perspective sensor's
    /// cone or frustum and range), as a depth camera's driver can; the guard
    /// then counts space outside it as unseen. Off: the clouds say nothing
    /// and kept triangles at the edge of a view vouch for space the sensor
    /// never looked at.
    pub state_field_of_view: bool,
    /// Clouds list the directions in which their perspective sensor's rays
    /// returned nothing (`shroud_geometry::cloud::dark_cones`), as a driver
    /// that knows its ray grid can; the guard then counts them as unseen, so
    /// that a black solid between returns from the floor is not vouched for.
    pub state_no_return: bool,
    /// Besides its whole view, each cloud that states its field of view is
    /// fitted in `sectors x sectors` overlapping sectors
    /// (`shroud_geometry::cloud::sector`), each along its own axis, as fit
    /// nodes with `sectors` settings do; 0: the whole view only.
    pub sectors: usize,
    /// How far a sector reaches, in its grid cell's angular half-diagonals.
    pub sector_reach: f64,
    /// The guard's policy for unseen space. `Stop` is the guarantee under
    /// test; `Ignore` (unsound with views of different clouds) is the
    /// negative control that shows the harness catches optimism.
    pub unobserved: UnobservedPolicy,
}

impl Default for SoundnessParams {
    fn default() -> Self {
        Self {
            stop_distance: 0.1,
            max_obstacle_speed: 0.25,
            horizon: 0.1,
            max_age: 0.5,
            verdicts_per_case: 100,
            timings_per_pose: 4,
            max_rays: 30_000,
            min_points: 50,
            sandwich_share: 0.5,
            black_share: 0.15,
            parallel_rays: false,
            state_field_of_view: true,
            state_no_return: true,
            sectors: 4,
            sector_reach: 1.5,
            unobserved: UnobservedPolicy::Stop,
        }
    }
}

impl SoundnessParams {
    pub fn validate(&self) -> Result<(), SoundnessError> {
        let bad = |parameter, reason, value| {
            Err(SoundnessError::BadParameter {
                parameter,
                reason,
                value,
            })
        };
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if !positive(self.stop_distance) {
            return bad(
                "stop_distance",
                "must be finite and > 0",
                self.stop_distance,
            );
        }
        if !(self.max_obstacle_speed.is_finite() && self.max_obstacle_speed >= 0.0) {
            return bad(
                "max_obstacle_speed",
                "must be finite and >= 0",
                self.max_obstacle_speed,
            );
        }
        if !(self.horizon.is_finite() && (0.0..=shroud_guard::MAX_HORIZON).contains(&self.horizon))
        {
            return bad("horizon", "must lie in [0, 1] s", self.horizon);
        }
        if !(positive(self.max_age) && self.max_age <= 10.0) {
            return bad("max_age", "must lie in (0, 10] s", self.max_age);
        }
        if self.verdicts_per_case == 0 || self.verdicts_per_case > 1_000_000 {
            return bad(
                "verdicts_per_case",
                "must lie in [1, 1e6]",
                self.verdicts_per_case as f64,
            );
        }
        if self.timings_per_pose == 0 || self.timings_per_pose > self.verdicts_per_case {
            return bad(
                "timings_per_pose",
                "must lie in [1, verdicts_per_case]",
                self.timings_per_pose as f64,
            );
        }
        if !(100..=1_000_000).contains(&self.max_rays) {
            return bad("max_rays", "must lie in [100, 1e6]", self.max_rays as f64);
        }
        if self.min_points == 0 {
            return bad("min_points", "must be at least 1", 0.0);
        }
        if !(0.0..=1.0).contains(&self.sandwich_share) {
            return bad("sandwich_share", "must lie in [0, 1]", self.sandwich_share);
        }
        if !(0.0..=1.0).contains(&self.black_share) {
            return bad("black_share", "must lie in [0, 1]", self.black_share);
        }
        if self.sectors > shroud_geometry::cloud::MAX_SECTOR_GRID {
            return bad("sectors", "must lie in [0, 8]", self.sectors as f64);
        }
        if self.sector_reach.is_nan() || self.sector_reach < 1.0 {
            return bad("sector_reach", "must be >= 1", self.sector_reach);
        }
        if self.sectors > 0 && self.unobserved == UnobservedPolicy::Ignore {
            // As the guard node refuses it: a sector says nothing outside
            // its cone, which only the Stop policy counts.
            return bad(
                "sectors",
                "need the Stop policy for unseen space",
                self.sectors as f64,
            );
        }
        Ok(())
    }
}
