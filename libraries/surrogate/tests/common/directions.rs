//! Fitting directions that stress the frame: random, axis-aligned (exact ties in
//! the frame's axis choice), and nearly parallel to the cloud's plane (a thin
//! projection with steep heights).

use super::clouds::{plane_basis, random_unit};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DirectionKind {
    /// A uniformly random unit vector.
    Random,
    /// `±x`, `±y` or `±z`.
    Axis,
    /// In the cloud's plane, tilted out of it by `tilt` (times a random sign).
    NearlyParallel { tilt: f64 },
}

/// A direction of the given kind for a cloud whose plane has unit normal `normal`.
pub fn direction(kind: DirectionKind, normal: [f64; 3], seed: u64) -> [f64; 3] {
    let mut rng = Pcg64::seed_from_u64(seed ^ 0xD1EC_7104);
    match kind {
        DirectionKind::Random => random_unit(&mut rng),
        DirectionKind::Axis => {
            let axis = rng.random_range(0..3);
            let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            let mut d = [0.0; 3];
            d[axis] = sign;
            d
        }
        DirectionKind::NearlyParallel { tilt } => {
            let (e1, e2) = plane_basis(normal);
            let a = rng.random_range(0.0..std::f64::consts::TAU);
            let sign = if rng.random_bool(0.5) { tilt } else { -tilt };
            [0, 1, 2].map(|k| a.cos() * e1[k] + a.sin() * e2[k] + sign * normal[k])
        }
    }
}
