//! What one data frame means for a given model and unit: a range in metres or
//! the reason it is not one, plus strength and temperature.

use super::config::DistanceUnit;
use super::frame::{DataFrame, TfminiDistanceMode};
use super::model::BenewakeModel;
use super::validity::Validity;
use crate::device::Ray;

/// One data frame, interpreted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// The frame as received.
    pub frame: DataFrame,
    /// Metres, `NaN` unless `validity` is [`Validity::Valid`].
    pub range_m: f32,
    /// The raw strength (TF-Luna: Amp).
    pub strength: u16,
    /// Whether the range is a measurement.
    pub validity: Validity,
    /// Chip temperature in °C (every model but the original TFmini).
    pub temperature_c: Option<f32>,
    /// The original TFmini's distance mode (byte 6); `None` on other models.
    pub distance_mode: Option<TfminiDistanceMode>,
}

impl Reading {
    /// Interprets `frame` from a `model` whose output unit is `unit`. The
    /// strength rules come first ([`BenewakeModel::strength_verdict`]), then
    /// the range check: 0 or more than the model's maximum is out of range.
    pub fn classify(frame: DataFrame, model: BenewakeModel, unit: DistanceUnit) -> Self {
        let validity = model
            .strength_verdict(frame.strength)
            .unwrap_or_else(|| range_verdict(frame.distance, model, unit));
        let range_m = match validity {
            Validity::Valid => f32::from(frame.distance) / unit.per_metre(),
            _ => f32::NAN,
        };
        Self {
            frame,
            range_m,
            strength: frame.strength,
            validity,
            temperature_c: model.has_temperature().then(|| frame.temperature_c()),
            distance_mode: (!model.has_temperature()).then(|| frame.tfmini_distance_mode()),
        }
    }

    /// The reading as the single ray of a scan: straight ahead (angle 0),
    /// offset 0, intensity = raw strength, range `NaN` when invalid.
    pub fn ray(&self) -> Ray {
        Ray {
            angle: 0.0,
            range: self.range_m,
            intensity: Some(f32::from(self.strength)),
            offset_ns: 0,
        }
    }
}

/// 0 and anything past the model's maximum (in the output unit) is out of
/// range.
fn range_verdict(distance: u16, model: BenewakeModel, unit: DistanceUnit) -> Validity {
    let max_cm = u32::from(model.max_range_cm());
    let max = match unit {
        DistanceUnit::Centimetre => max_cm,
        DistanceUnit::Millimetre => max_cm * 10,
    };
    if distance == 0 || u32::from(distance) > max {
        Validity::OutOfRange
    } else {
        Validity::Valid
    }
}
