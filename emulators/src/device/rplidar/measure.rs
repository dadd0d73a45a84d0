//! Turns rays cast into the world into RPLIDAR samples: range noise,
//! dropouts, the minimum range, quality from reflectance, and the
//! triangulation parallax that express capsules carry as dθ.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use super::model::ModelSpec;
use super::options::RplidarOptions;
use crate::device::RaySource;

/// Baseline of the parallax model: a sample's direction lies atan(this /
/// range) behind the encoder angle. 2 cm puts the largest offset, at the
/// 0.15 m minimum range, at 7.5°, inside the 7.875° a 6-bit q3 dθ holds.
const PARALLAX_BASELINE_M: f64 = 0.02;
/// Largest parallax offset, the largest dθ (63 / 8 degrees).
const MAX_PARALLAX_DEG: f64 = 63.0 / 8.0;
/// Largest standard-node quality (6 bits).
const MAX_QUALITY: f64 = 63.0;

/// One sample as the device measured it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Sample {
    /// Millimetres; 0 = no measurement.
    pub distance_mm: f64,
    /// 0..=63; 0 with no measurement.
    pub quality: u8,
}

impl Sample {
    const NONE: Sample = Sample {
        distance_mm: 0.0,
        quality: 0,
    };
}

/// The device's measuring front end.
pub(crate) struct Measurer {
    rng: Pcg64,
    noise: f64,
    dropout: f64,
    compensate: bool,
    min_range_m: f64,
    max_range_m: f64,
}

/// The REP-103 ray angle (radians, counter-clockwise) of a clockwise device
/// angle in degrees.
pub(crate) fn ray_angle(clockwise_deg: f64) -> f64 {
    -clockwise_deg.to_radians()
}

impl Measurer {
    pub(crate) fn new(spec: &ModelSpec, options: &RplidarOptions) -> Self {
        Self {
            rng: Pcg64::seed_from_u64(options.seed),
            noise: finite_or(options.noise, 0.0).max(0.0),
            dropout: finite_or(options.dropout, 0.0).clamp(0.0, 1.0),
            compensate: options.angle_compensation,
            min_range_m: spec.min_range_m,
            max_range_m: spec.max_range_m,
        }
    }

    /// Degrees (≥ 0) by which the sample taken at encoder angle `encoder_deg`
    /// lies behind it: atan(baseline / range) of the surface the encoder
    /// direction sees, 0 when it sees none or compensation is off.
    pub(crate) fn parallax_deg(&self, rays: &dyn RaySource, encoder_deg: f64, t: f64) -> f64 {
        if !self.compensate {
            return 0.0;
        }
        match rays.cast(ray_angle(encoder_deg), t, self.max_range_m) {
            Some(hit) if hit.range > 0.0 => PARALLAX_BASELINE_M
                .atan2(hit.range)
                .to_degrees()
                .min(MAX_PARALLAX_DEG),
            _ => 0.0,
        }
    }

    /// Measures along clockwise `angle_deg` at `t`.
    pub(crate) fn measure(&mut self, rays: &dyn RaySource, angle_deg: f64, t: f64) -> Sample {
        let dropped = self.rng.random::<f64>() < self.dropout;
        let noise = self.gaussian();
        let Some(hit) = rays.cast(ray_angle(angle_deg), t, self.max_range_m) else {
            return Sample::NONE;
        };
        let range = hit.range + noise * self.noise * hit.range;
        let quality = self.quality(hit.reflectance, range);
        if dropped || quality == 0 || !(self.min_range_m..=self.max_range_m).contains(&range) {
            return Sample::NONE;
        }
        Sample {
            distance_mm: range * 1000.0,
            quality,
        }
    }

    /// Quality 0..=63: 63 × reflectance, halved at the maximum range.
    fn quality(&self, reflectance: f64, range: f64) -> u8 {
        let falloff = 1.0 - 0.5 * (range / self.max_range_m).clamp(0.0, 1.0);
        let quality = (MAX_QUALITY * finite_or(reflectance, 0.0).clamp(0.0, 1.0) * falloff).round();
        // In 0..=63 by the clamps above.
        quality as u8
    }

    /// A standard normal draw (Box–Muller).
    fn gaussian(&mut self) -> f64 {
        let u1 = self.rng.random::<f64>().max(f64::MIN_POSITIVE);
        let u2 = self.rng.random::<f64>();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

fn finite_or(value: f64, fallback: f64) -> f64 {
    if value.is_finite() {
        value
    } else {
        fallback
    }
}
