//! Turns the boresight ray into a Benewake reading: noisy range, a signal
//! strength that falls with range and rises with reflectance, and the
//! model's invalid-reading rule.
//!
//! Strength model (this emulator's, fitted to the datasheets' ranges):
//! `k · reflectance / (r² + 1 m²)`, with `k` chosen so that a 10 %
//! reflectance target at the model's "@10 %" range reads exactly the
//! model's minimum reliable strength; a 90 % target then stays reliable to
//! about three times that range, as the datasheets' "@90 %" ranges say.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use super::model::ModelSpec;
use super::options::BenewakeOptions;
use crate::device::RaySource;

/// Relative standard deviation of the strength.
const STRENGTH_JITTER: f64 = 0.02;
/// Reflectance of the "@10 %" datasheet target.
const TEN_PERCENT: f64 = 0.1;

/// One measurement before formatting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Reading {
    /// Metres, if the reading is reliable (saturated to the model's output
    /// limit).
    pub range_m: Option<f64>,
    pub strength: u16,
}

pub(crate) struct Ranger {
    rng: Pcg64,
    noise: f64,
}

impl Ranger {
    pub(crate) fn new(options: &BenewakeOptions) -> Self {
        let noise = if options.noise.is_finite() {
            options.noise.max(0.0)
        } else {
            0.0
        };
        Self {
            rng: Pcg64::seed_from_u64(options.seed),
            noise,
        }
    }

    /// Measures along the sensor's +x axis at `t`.
    pub(crate) fn measure(&mut self, spec: &ModelSpec, rays: &dyn RaySource, t: f64) -> Reading {
        let range_noise = self.gaussian();
        let strength_noise = self.gaussian();
        let hit = rays
            .cast(0.0, t, spec.cast_range_m)
            .filter(|h| h.range.is_finite());
        let Some(hit) = hit else {
            // Nothing returns: the strength is the noise floor, well below
            // the reliable level.
            let floor = self.rng.random_range(0..=spec.invalid.min_strength / 4);
            return Reading {
                range_m: None,
                strength: floor,
            };
        };
        let range = (hit.range + range_noise * self.noise * hit.range.max(1.0)).max(0.0);
        let ideal = strength_scale(spec) * hit.reflectance.clamp(0.0, 1.0) / (range * range + 1.0);
        let strength = saturate(
            ideal * (1.0 + STRENGTH_JITTER * strength_noise),
            spec.max_strength,
        );
        let max_m = f64::from(spec.max_output_cm) / 100.0;
        Reading {
            range_m: is_reliable(spec, strength).then(|| range.min(max_m)),
            strength,
        }
    }

    /// A standard normal draw (Box–Muller).
    fn gaussian(&mut self) -> f64 {
        let u1 = self.rng.random::<f64>().max(f64::MIN_POSITIVE);
        let u2 = self.rng.random::<f64>();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// `k` of the strength model.
fn strength_scale(spec: &ModelSpec) -> f64 {
    let r10 = spec.range_at_10pct_m;
    f64::from(spec.invalid.min_strength) * (r10 * r10 + 1.0) / TEN_PERCENT
}

fn is_reliable(spec: &ModelSpec, strength: u16) -> bool {
    let saturated = spec.invalid.saturation_invalid && strength == u16::MAX;
    strength >= spec.invalid.min_strength && !saturated
}

fn saturate(value: f64, max: u16) -> u16 {
    if value.is_nan() {
        0
    } else {
        value.round().clamp(0.0, f64::from(max)) as u16
    }
}
