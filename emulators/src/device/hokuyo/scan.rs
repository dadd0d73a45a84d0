//! Measuring a scan: one ray per step cast into the world at the step's own
//! time, with the model's noise, dropouts and error codes, merged into
//! clusters and encoded for MD/MS/ME data lines (further echoes of
//! multi-echo scans: `echo.rs`).

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use super::codec::encode_into;
use super::command::{DataEncoding, ScanRequest};
use super::model::ModelSpec;
use super::timing::Rotation;
use crate::device::{RayReturn, RaySource};

/// Intensity reported for a surface of reflectance 1.0 (ME/GE); the UTM-30LX
/// reports unit-less intensities of this order for bright surfaces.
const INTENSITY_FULL_SCALE: f64 = 10_000.0;

/// Largest value 2-character encoding carries (12 bits, spec §6.1, p. 6).
const TWO_CHAR_MAX: u32 = (1 << 12) - 1;

/// Largest value 3-character encoding carries (18 bits, spec §6.2, p. 7).
const THREE_CHAR_MAX: u32 = (1 << 18) - 1;

/// One output value: a range in mm (below DMIN: an error code) and the
/// intensity of the same step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Measurement {
    pub(crate) range_mm: u32,
    pub(crate) intensity: u32,
}

/// Turns ray returns into the sensor's readings: noise, dropouts, limits.
pub(crate) struct Sampler {
    rng: Pcg64,
    noise_scale: f64,
    dropout_probability: f64,
}

impl Sampler {
    pub(crate) fn new(seed: u64, noise_scale: f64, dropout_probability: f64) -> Self {
        let finite_or_zero = |x: f64| if x.is_finite() { x } else { 0.0 };
        Sampler {
            rng: Pcg64::seed_from_u64(seed),
            noise_scale: finite_or_zero(noise_scale).max(0.0),
            dropout_probability: finite_or_zero(dropout_probability).clamp(0.0, 1.0),
        }
    }

    /// The reading of one ray that returned `ray`.
    fn read(&mut self, spec: &ModelSpec, ray: Option<RayReturn>) -> Measurement {
        if self.dropout_probability > 0.0 && self.rng.random::<f64>() < self.dropout_probability {
            return error(spec.errors.dropout);
        }
        let Some(ray) = ray.filter(|r| r.range.is_finite() && r.range >= 0.0) else {
            return error(spec.errors.no_return);
        };
        let true_mm = ray.range * 1000.0;
        if true_mm < f64::from(spec.dmin) {
            return error(spec.errors.too_near);
        }
        let noisy_mm = true_mm + self.noise_mm(spec, true_mm);
        // Clamped to DMIN..DMAX before the (saturating) conversion.
        let range_mm = noisy_mm
            .round()
            .clamp(f64::from(spec.dmin), f64::from(spec.dmax)) as u32;
        let reflectance = if ray.reflectance.is_finite() {
            ray.reflectance
        } else {
            0.0
        };
        let intensity = (reflectance.clamp(0.0, 1.0) * INTENSITY_FULL_SCALE).round() as u32;
        Measurement {
            range_mm,
            intensity,
        }
    }

    fn noise_mm(&mut self, spec: &ModelSpec, range_mm: f64) -> f64 {
        if self.noise_scale == 0.0 {
            return 0.0;
        }
        self.noise_scale * spec.accuracy.sigma_mm(range_mm) * self.standard_normal()
    }

    /// Box-Muller.
    fn standard_normal(&mut self) -> f64 {
        let u1 = 1.0 - self.rng.random::<f64>();
        let u2 = self.rng.random::<f64>();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

fn error(code: u32) -> Measurement {
    Measurement {
        range_mm: code,
        intensity: 0,
    }
}

/// The angle of `step` in radians, counter-clockwise from the sensor's +x
/// (spec §5: AFRT is the front; urg_c `urg_step2rad()`: 2π per ARES steps).
pub(crate) fn step_angle(spec: &ModelSpec, step: u32) -> f64 {
    let from_front = f64::from(step) - f64::from(spec.afrt);
    from_front * std::f64::consts::TAU / f64::from(spec.ares)
}

/// Where a scan is measured: the world, the model and the motor.
pub(crate) struct ScanSetup<'a> {
    pub(crate) rays: &'a dyn RaySource,
    pub(crate) spec: &'a ModelSpec,
    pub(crate) rotation: Rotation,
}

/// Measures revolution `revolution` over `request`'s steps into `out`, one
/// value per cluster: the smallest valid range of the cluster, or, if none
/// is valid, the smallest error code (spec §8.1, p. 10: "step having minimum
/// measurement value (excluding error) in the cluster").
pub(crate) fn measure_scan(
    setup: &ScanSetup<'_>,
    sampler: &mut Sampler,
    revolution: u64,
    request: &ScanRequest,
    out: &mut Vec<Measurement>,
) {
    out.clear();
    let max_range = f64::from(setup.spec.dmax) / 1000.0;
    let mut cluster: Option<Measurement> = None;
    let mut in_cluster = 0;
    for step in request.start..=request.end {
        let time = setup.rotation.step_time(revolution, step);
        let ray = setup
            .rays
            .cast(step_angle(setup.spec, step), time, max_range);
        let reading = sampler.read(setup.spec, ray);
        cluster = Some(cluster.map_or(reading, |best| closer(setup.spec, best, reading)));
        in_cluster += 1;
        if in_cluster >= request.cluster {
            out.extend(cluster.take());
            in_cluster = 0;
        }
    }
    out.extend(cluster);
}

/// Of two readings, the one a cluster reports.
fn closer(spec: &ModelSpec, a: Measurement, b: Measurement) -> Measurement {
    let valid = |m: &Measurement| m.range_mm >= spec.dmin;
    match (valid(&a), valid(&b)) {
        (true, false) => a,
        (false, true) => b,
        _ if b.range_mm < a.range_mm => b,
        _ => a,
    }
}

/// Appends the encoded values (before cutting into 64-character lines).
pub(crate) fn encode_values(values: &[Measurement], encoding: DataEncoding, out: &mut Vec<u8>) {
    for value in values {
        encode_value(value, encoding, out);
    }
}

/// Appends one encoded value. A range MS cannot carry (above 4095 mm) is
/// sent as 0, an error code.
pub(crate) fn encode_value(value: &Measurement, encoding: DataEncoding, out: &mut Vec<u8>) {
    match encoding {
        DataEncoding::TwoChar => {
            let range = if value.range_mm > TWO_CHAR_MAX {
                0
            } else {
                value.range_mm
            };
            encode_into(range, 2, out);
        }
        DataEncoding::ThreeChar => encode_into(value.range_mm.min(THREE_CHAR_MAX), 3, out),
        DataEncoding::WithIntensity => {
            encode_into(value.range_mm.min(THREE_CHAR_MAX), 3, out);
            encode_into(value.intensity.min(THREE_CHAR_MAX), 3, out);
        }
    }
}
