//! Turns a rangefinder's boresight ray into a reading: noisy range and a
//! signal strength that falls with range and rises with reflectance.
//!
//! Strength model (the emulator's, as its serial Benewake emulator's):
//! `k · reflectance / (r² + 1 m²)`, with `k` chosen so that a 10 %
//! reflectance target at the model's "@10 %" range reads exactly the
//! model's minimum reliable strength.

use super::model::CanModelSpec;
use rand::Rng;
use rand_pcg::Pcg64;
use shroud_sim::world::RaySource;

/// Standard deviation of the range noise: 1 cm up to 2 m, 0.5 % beyond.
const NOISE_FRACTION: f64 = 0.005;
const NOISE_FLOOR_RANGE_M: f64 = 2.0;
/// Relative standard deviation of the strength.
const STRENGTH_JITTER: f64 = 0.02;
/// Reflectance of the "@10 %" datasheet target.
const TEN_PERCENT: f64 = 0.1;

/// One measurement before encoding.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Reading {
    /// Metres, when the reading is reliable.
    pub range_m: Option<f64>,
    pub strength: u16,
}

/// The standard deviation of the range noise at `range_m`.
pub fn range_noise_m(range_m: f64) -> f64 {
    NOISE_FRACTION * range_m.max(NOISE_FLOOR_RANGE_M)
}

/// Measures along the +x axis of `rays` (none: nothing to hit) at `t`.
pub(crate) fn measure(
    spec: &CanModelSpec,
    rays: Option<&dyn RaySource>,
    t: f64,
    rng: &mut Pcg64,
) -> Reading {
    let range_noise = gaussian(rng);
    let strength_noise = gaussian(rng);
    let hit = rays
        .and_then(|rays| rays.cast(0.0, t, spec.cast_range_m))
        .filter(|h| h.range.is_finite() && h.range >= 0.0);
    let Some(hit) = hit else {
        // Nothing returns: the strength is the noise floor, below the
        // reliable level.
        let floor = rng.random_range(0..=spec.min_strength / 4);
        return Reading {
            range_m: None,
            strength: floor,
        };
    };
    let range = (hit.range + range_noise * range_noise_m(hit.range)).max(0.0);
    let r10 = spec.range_at_10pct_m;
    let scale = f64::from(spec.min_strength) * (r10 * r10 + 1.0) / TEN_PERCENT;
    let ideal = scale * hit.reflectance.clamp(0.0, 1.0) / (range * range + 1.0);
    let raw = ideal * (1.0 + STRENGTH_JITTER * strength_noise);
    let strength = if raw.is_nan() {
        0
    } else {
        raw.round().clamp(0.0, f64::from(spec.max_strength)) as u16
    };
    Reading {
        range_m: (strength >= spec.min_strength).then_some(range),
        strength,
    }
}

/// A standard normal draw (Box–Muller).
fn gaussian(rng: &mut Pcg64) -> f64 {
    let u1 = 1.0 - rng.random::<f64>();
    let u2 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}
