//! What the integrator chooses: which rangefinders are on the bus (model,
//! id, mount), how long a cycle may take and how long a silence may last.

use super::error::BenewakeCanError;
use super::model::BenewakeCanModel;
use crate::assembly::MountPose;
use crate::can::{MAX_EXTENDED_ID, MAX_STANDARD_ID};

/// At most this many rangefinders on one driver.
pub const MAX_RANGEFINDERS: usize = 16;
/// A cycle waits this long for the sensors that have not reported (the
/// models' default rate is 100 Hz: five periods).
pub const DEFAULT_CYCLE_TIMEOUT_NS: u64 = 50_000_000;
/// No frame from any rangefinder for this long is a silent bus.
pub const DEFAULT_SILENCE_TIMEOUT_NS: u64 = 1_000_000_000;

/// One rangefinder on the bus.
#[derive(Debug, Clone, PartialEq)]
pub struct RangefinderConfig {
    /// A name for status and counters (`front`, `left`, ...), unique.
    pub name: String,
    pub model: BenewakeCanModel,
    /// Its send id (the model's default: [`BenewakeCanModel::default_id`]).
    pub id: u32,
    pub extended: bool,
    /// Its pose in the robot's frame; the beam is its +x (REP-103).
    pub mount: MountPose,
}

impl RangefinderConfig {
    /// A rangefinder of `model` on the model's default id.
    pub fn new(name: &str, model: BenewakeCanModel, mount: MountPose) -> Self {
        let (id, extended) = model.default_id();
        Self {
            name: name.to_owned(),
            model,
            id,
            extended,
            mount,
        }
    }
}

/// How to run the rangefinders of one bus.
#[derive(Debug, Clone, PartialEq)]
pub struct BenewakeCanConfig {
    /// 1..=16 rangefinders with distinct (id, extended) and names.
    pub sensors: Vec<RangefinderConfig>,
    pub cycle_timeout_ns: u64,
    pub silence_timeout_ns: u64,
}

impl BenewakeCanConfig {
    /// `sensors` with the default timeouts.
    pub fn new(sensors: Vec<RangefinderConfig>) -> Self {
        Self {
            sensors,
            cycle_timeout_ns: DEFAULT_CYCLE_TIMEOUT_NS,
            silence_timeout_ns: DEFAULT_SILENCE_TIMEOUT_NS,
        }
    }

    /// Checks counts, ids, names, mounts and timeouts; the error names the
    /// offending sensor or setting.
    pub fn validate(&self) -> Result<(), BenewakeCanError> {
        let n = self.sensors.len();
        if n == 0 || n > MAX_RANGEFINDERS {
            return Err(BenewakeCanError::SensorCount {
                found: n,
                limit: MAX_RANGEFINDERS,
            });
        }
        for (k, s) in self.sensors.iter().enumerate() {
            let max = if s.extended {
                MAX_EXTENDED_ID
            } else {
                MAX_STANDARD_ID
            };
            if s.id > max {
                return Err(BenewakeCanError::BadId {
                    sensor: s.name.clone(),
                    id: s.id,
                    max,
                });
            }
            if s.name.is_empty() {
                return Err(BenewakeCanError::BadSetting {
                    name: "name",
                    reason: format!("sensor {k} has an empty name"),
                });
            }
            if !(s.mount.translation.is_finite() && s.mount.rotation.is_finite()) {
                return Err(BenewakeCanError::BadSetting {
                    name: "mount",
                    reason: format!("sensor {} has a non-finite mount", s.name),
                });
            }
            for earlier in &self.sensors[..k] {
                if (earlier.id, earlier.extended) == (s.id, s.extended) {
                    return Err(BenewakeCanError::DuplicateId {
                        first: earlier.name.clone(),
                        second: s.name.clone(),
                        id: s.id,
                        extended: s.extended,
                    });
                }
                if earlier.name == s.name {
                    return Err(BenewakeCanError::BadSetting {
                        name: "name",
                        reason: format!("two sensors are named {}", s.name),
                    });
                }
            }
        }
        if self.cycle_timeout_ns == 0 {
            return Err(BenewakeCanError::BadSetting {
                name: "cycle_timeout",
                reason: "must be more than 0".into(),
            });
        }
        if self.silence_timeout_ns == 0 {
            return Err(BenewakeCanError::BadSetting {
                name: "silence_timeout",
                reason: "must be more than 0".into(),
            });
        }
        Ok(())
    }
}
