//! How the guard judges clearances: the stop threshold, the largest clearance
//! worth computing exactly, how deep near cells are subdivided, and how fast
//! obstacles may move.

use super::error::GuardError;
use serde::{Deserialize, Serialize};

/// Deepest refinement: `4^MAX_REFINE_DEPTH` sub-patches per cell at most.
pub const MAX_REFINE_DEPTH: u32 = 6;

/// Guard settings (metres, in the world units of the surrogate and the arm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GuardConfig {
    /// `stop` is raised when any shape's clearance is below this (`>= 0`).
    pub stop_distance: f64,
    /// Clearances are capped here: a reported `max_report` means "at least
    /// `max_report`". Larger values look at more cells (`> 0`, `>= stop_distance`).
    pub max_report: f64,
    /// Cells whose coarse bound is below `stop_distance` are subdivided into
    /// 2x2, 4x4, ... Bézier sub-patches, up to `4^refine_depth` per cell
    /// (`0..=MAX_REFINE_DEPTH`; 0 keeps the coarse cell bounds), until the
    /// shape is known to be clear of `stop_distance` or not. Clearances below
    /// `stop_distance` are therefore valid lower bounds but not the tightest.
    pub refine_depth: u32,
    /// Bound on the speed of anything in the scene (m/s, `>= 0`): the guard
    /// reduces a surrogate's clearances by this times the surrogate's age
    /// plus the [`Self::horizon`], so that a stop is decided against where an
    /// obstacle can be until the arm stops moving on the verdict.
    pub max_obstacle_speed: f64,
    /// How long after the decision (seconds, `>= 0`, at most
    /// [`MAX_HORIZON`]) the arm may still move on a `clear`: a verdict
    /// consumer's deadman deadline, counted from when it sent the joint
    /// state, must not exceed it (the arm node refuses a longer `--deadline`).
    pub horizon: f64,
}

/// The longest horizon an arm file may give: a verdict vouching for more
/// than this is not a guard's but a planner's.
pub const MAX_HORIZON: f64 = 1.0;

impl Default for GuardConfig {
    fn default() -> Self {
        Self {
            stop_distance: 0.05,
            max_report: 0.2,
            refine_depth: 3,
            max_obstacle_speed: 0.0,
            horizon: 0.1,
        }
    }
}

impl GuardConfig {
    pub fn validate(&self) -> Result<(), GuardError> {
        let bad = |m: String| Err(GuardError::BadConfig(m));
        if !(self.stop_distance.is_finite() && self.stop_distance >= 0.0) {
            return bad(format!(
                "stop_distance must be finite and >= 0, got {}",
                self.stop_distance
            ));
        }
        if !(self.max_report.is_finite() && self.max_report > 0.0) {
            return bad(format!(
                "max_report must be finite and > 0, got {}",
                self.max_report
            ));
        }
        if self.max_report < self.stop_distance {
            return bad(format!(
                "max_report ({}) must be >= stop_distance ({})",
                self.max_report, self.stop_distance
            ));
        }
        if !(self.max_obstacle_speed.is_finite() && self.max_obstacle_speed >= 0.0) {
            return bad(format!(
                "max_obstacle_speed must be finite and >= 0, got {}",
                self.max_obstacle_speed
            ));
        }
        if !(self.horizon.is_finite() && (0.0..=MAX_HORIZON).contains(&self.horizon)) {
            return bad(format!(
                "horizon must be in [0, {MAX_HORIZON}] seconds, got {}",
                self.horizon
            ));
        }
        if self.refine_depth > MAX_REFINE_DEPTH {
            return bad(format!(
                "refine_depth {} exceeds the maximum {MAX_REFINE_DEPTH}",
                self.refine_depth
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_bad_values_are_refused() {
        assert!(GuardConfig::default().validate().is_ok());
        let with = |f: fn(&mut GuardConfig)| {
            let mut c = GuardConfig::default();
            f(&mut c);
            c.validate()
        };
        assert!(with(|c| c.stop_distance = -0.1).is_err());
        assert!(with(|c| c.stop_distance = f64::NAN).is_err());
        assert!(with(|c| c.max_report = 0.0).is_err());
        assert!(with(|c| c.max_report = f64::INFINITY).is_err());
        assert!(with(|c| c.max_report = 0.01).is_err());
        assert!(with(|c| c.refine_depth = MAX_REFINE_DEPTH + 1).is_err());
        assert!(with(|c| c.max_obstacle_speed = -1.0).is_err());
        assert!(with(|c| c.max_obstacle_speed = f64::INFINITY).is_err());
        assert!(with(|c| c.horizon = -0.1).is_err());
        assert!(with(|c| c.horizon = f64::NAN).is_err());
        assert!(with(|c| c.horizon = MAX_HORIZON * 2.0).is_err());
        assert!(with(|c| c.stop_distance = 0.0).is_ok());
    }
}
