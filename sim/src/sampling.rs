//! Seeded random streams and the rejection-free samplers shared by all scenes.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::TAU;

/// The generator behind every scene: PCG (MCG variant), fast and reproducible
/// across platforms, so a seed names the same cloud everywhere.
pub(crate) type SceneRng = Pcg64Mcg;

/// SplitMix64 finaliser: spreads nearby inputs (seed 1 vs 2, adjacent time bits)
/// over unrelated generator states.
fn mix64(value: u64) -> u64 {
    let mut z = value.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A generator determined by the user seed and a list of stream keys (scene tag,
/// time bits, sphere index), so each part of a scene draws independent numbers.
pub(crate) fn stream_rng(seed: u64, keys: &[u64]) -> SceneRng {
    let state = keys.iter().fold(mix64(seed), |acc, &k| mix64(acc ^ k));
    SceneRng::seed_from_u64(state)
}

/// Bits of a time value with `-0.0` folded onto `0.0`, so both give the same frame.
pub(crate) fn time_key(time: f64) -> u64 {
    (time + 0.0).to_bits()
}

/// Uniform in `[lo, hi)`.
pub(crate) fn uniform(rng: &mut SceneRng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.random::<f64>()
}

/// Uniform in `[-amplitude, amplitude)`. Always draws one number, even for zero
/// amplitude, so toggling noise does not shift the rest of the stream.
pub(crate) fn symmetric(rng: &mut SceneRng, amplitude: f64) -> f64 {
    amplitude * (2.0 * rng.random::<f64>() - 1.0)
}

/// Uniform direction on the unit sphere by Archimedes' hat-box theorem (z uniform
/// in [-1, 1], azimuth uniform): no rejection loop and only one sqrt and sin_cos.
pub(crate) fn unit_direction(rng: &mut SceneRng) -> [f64; 3] {
    let z = 2.0 * rng.random::<f64>() - 1.0;
    let (sin, cos) = (TAU * rng.random::<f64>()).sin_cos();
    let ring = (1.0 - z * z).max(0.0).sqrt();
    [ring * cos, ring * sin, z]
}

/// A point at `distance` from `centre` along a uniform direction, as f32.
fn at_distance(rng: &mut SceneRng, centre: [f64; 3], distance: f64) -> [f32; 3] {
    let d = unit_direction(rng);
    [
        (centre[0] + distance * d[0]) as f32,
        (centre[1] + distance * d[1]) as f32,
        (centre[2] + distance * d[2]) as f32,
    ]
}

/// Uniform in the solid ball: the radius is `radius * cbrt(u)` because the volume
/// inside distance r grows like r^3.
pub(crate) fn in_ball(rng: &mut SceneRng, centre: [f64; 3], radius: f64) -> [f32; 3] {
    let distance = radius * rng.random::<f64>().cbrt();
    at_distance(rng, centre, distance)
}

/// Uniform on the sphere surface.
pub(crate) fn on_sphere(rng: &mut SceneRng, centre: [f64; 3], radius: f64) -> [f32; 3] {
    at_distance(rng, centre, radius)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let a: Vec<f64> = (0..4).map(|_| stream_rng(7, &[1]).random()).collect();
        let b: Vec<f64> = (0..4).map(|_| stream_rng(7, &[1]).random()).collect();
        assert_eq!(a, b);
        let x: f64 = stream_rng(7, &[1]).random();
        let y: f64 = stream_rng(7, &[2]).random();
        let z: f64 = stream_rng(8, &[1]).random();
        assert!(x != y && x != z);
    }

    #[test]
    fn negative_zero_time_is_zero_time() {
        assert_eq!(time_key(-0.0), time_key(0.0));
        assert_ne!(time_key(1.0), time_key(0.0));
    }

    #[test]
    fn directions_are_unit_and_balanced() {
        let mut rng = stream_rng(3, &[]);
        let mut sum = [0.0f64; 3];
        let n = 20_000;
        for _ in 0..n {
            let d = unit_direction(&mut rng);
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            assert!((len - 1.0).abs() < 1e-12);
            (0..3).for_each(|k| sum[k] += d[k]);
        }
        assert!(sum.iter().all(|s| (s / n as f64).abs() < 0.03), "{sum:?}");
    }

    #[test]
    fn ball_points_fill_the_volume() {
        let mut rng = stream_rng(5, &[]);
        let n = 20_000;
        let inner = (0..n)
            .map(|_| in_ball(&mut rng, [0.0; 3], 1.0))
            .filter(|p| p.iter().map(|c| c * c).sum::<f32>().sqrt() < 0.5)
            .count();
        // A ball of half the radius holds 1/8 of the volume.
        let fraction = inner as f64 / n as f64;
        assert!((fraction - 0.125).abs() < 0.01, "{fraction}");
    }
}
