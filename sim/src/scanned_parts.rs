//! Irregular scans of parts for the blender's boundary detection (paper 001,
//! issue 12): analytic surfaces sampled uniformly at random by area (not on a
//! grid), some with noise or uneven density, plus shapes a blend must refuse
//! with a reason (a closed sphere, a band with two rims). A (shape, radius,
//! count, seed) tuple names one cloud on every platform.

use crate::sampling::{stream_rng, SceneRng};
use rand::Rng;
use std::f64::consts::TAU;

/// Elevation of the caps' rim above their base plane: 3 degrees, the issue's
/// hemisphere (its rim is almost vertical, the hard case for tangent planes).
const RIM_ELEVATION_DEG: f64 = 3.0;

/// A detected loop follows the rim when all its points lie this close to it,
/// as a fraction of the radius (about four spacings of a 6,000-point cap).
pub const RIM_TOLERANCE: f64 = 0.15;

/// Standard deviation of the noisy cap's Gaussian noise, a fraction of the radius.
const NOISE_FRACTION: f64 = 0.01;

/// Density of the lopsided cap at x = -r relative to x = +r.
const THIN_SIDE_DENSITY: f64 = 0.15;

/// An open (or, for [`ScannedShape::ClosedSphere`], closed) surface of size
/// `radius`, sampled at random.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScannedShape {
    /// Sphere cap from 3 degrees above the equator to the pole, uniform by area;
    /// one circular rim of radius `r cos 3°` at `z = r sin 3°`.
    Hemisphere,
    /// `z = r (1 - (x² + y²) / r²)` over the disc of radius r, uniform by area;
    /// its rim is the circle of radius r in z = 0.
    Paraboloid,
    /// The flat disc of radius r in z = 0.
    Disc,
    /// [`ScannedShape::Hemisphere`] with isotropic Gaussian noise of 1 % of r.
    NoisyCap,
    /// [`ScannedShape::Hemisphere`] 6.7 times denser at x = +r than at x = -r
    /// (density linear in x).
    LopsidedCap,
    /// The side of a cylinder of radius r and height r: two rims of equal length.
    Band,
    /// The whole sphere of radius r: no rim at all.
    ClosedSphere,
}

/// Every shape, in the order the boundary sweep prints them.
pub const SCANNED_SHAPES: [ScannedShape; 7] = [
    ScannedShape::Hemisphere,
    ScannedShape::Paraboloid,
    ScannedShape::Disc,
    ScannedShape::NoisyCap,
    ScannedShape::LopsidedCap,
    ScannedShape::Band,
    ScannedShape::ClosedSphere,
];

impl ScannedShape {
    pub fn name(self) -> &'static str {
        match self {
            Self::Hemisphere => "hemisphere",
            Self::Paraboloid => "paraboloid",
            Self::Disc => "disc",
            Self::NoisyCap => "noisy cap",
            Self::LopsidedCap => "lopsided cap",
            Self::Band => "band",
            Self::ClosedSphere => "closed sphere",
        }
    }

    /// How many open boundary loops (rims) the surface has.
    pub fn rims(self) -> usize {
        match self {
            Self::Band => 2,
            Self::ClosedSphere => 0,
            _ => 1,
        }
    }

    /// `count` points of the shape of size `radius`, drawn from `seed`.
    pub fn sample(self, radius: f64, count: usize, seed: u64) -> Vec<[f32; 3]> {
        let mut rng = stream_rng(seed, &[0x5ca4_ed00 + self as u64]);
        let mut out = Vec::with_capacity(count);
        while out.len() < count {
            if let Some(p) = self.draw(&mut rng) {
                out.push(p.map(|c| (c * radius) as f32));
            }
        }
        out
    }

    /// Distance from `p` to the nearest rim of the shape of size `radius`
    /// (infinite for the closed sphere): how well a detected loop follows it.
    pub fn rim_distance(self, p: [f64; 3], radius: f64) -> f64 {
        let [x, y, z] = p.map(|c| c / radius);
        let ring = x.hypot(y);
        let to_circle = |rho: f64, height: f64| (ring - rho).hypot(z - height) * radius;
        let elevation = RIM_ELEVATION_DEG.to_radians();
        match self {
            Self::Hemisphere | Self::NoisyCap | Self::LopsidedCap => {
                to_circle(elevation.cos(), elevation.sin())
            }
            Self::Paraboloid | Self::Disc => to_circle(1.0, 0.0),
            Self::Band => to_circle(1.0, 0.0).min(to_circle(1.0, 1.0)),
            Self::ClosedSphere => f64::INFINITY,
        }
    }

    /// Whether every one of `points` lies within [`RIM_TOLERANCE`] of a rim of
    /// the shape of size `radius` (false for none).
    pub fn follows_rim(self, points: impl IntoIterator<Item = [f64; 3]>, radius: f64) -> bool {
        let mut any = false;
        let all = points.into_iter().all(|p| {
            any = true;
            self.rim_distance(p, radius) <= RIM_TOLERANCE * radius
        });
        any && all
    }

    /// One candidate point of the unit-size shape, `None` when rejected (the
    /// rejection keeps the paraboloid uniform by area and makes the lopsided cap
    /// uneven).
    fn draw(self, rng: &mut SceneRng) -> Option<[f64; 3]> {
        match self {
            Self::Hemisphere => Some(cap_point(rng)),
            Self::Paraboloid => paraboloid_point(rng),
            Self::Disc => {
                let (rho, angle) = (rng.random::<f64>().sqrt(), TAU * rng.random::<f64>());
                Some([rho * angle.cos(), rho * angle.sin(), 0.0])
            }
            Self::NoisyCap => {
                let p = cap_point(rng);
                Some(p.map(|c| c + NOISE_FRACTION * gaussian(rng)))
            }
            Self::LopsidedCap => {
                let p = cap_point(rng);
                let density = THIN_SIDE_DENSITY + (1.0 - THIN_SIDE_DENSITY) * 0.5 * (1.0 + p[0]);
                (rng.random::<f64>() < density).then_some(p)
            }
            Self::Band => {
                let angle = TAU * rng.random::<f64>();
                Some([angle.cos(), angle.sin(), rng.random::<f64>()])
            }
            Self::ClosedSphere => Some(sphere_zone(rng, -1.0)),
        }
    }
}

/// Uniform by area on the unit sphere above height `low` (Archimedes: the
/// height is uniform).
fn sphere_zone(rng: &mut SceneRng, low: f64) -> [f64; 3] {
    let z = low + (1.0 - low) * rng.random::<f64>();
    let (sin, cos) = (TAU * rng.random::<f64>()).sin_cos();
    let ring = (1.0 - z * z).max(0.0).sqrt();
    [ring * cos, ring * sin, z]
}

/// The unit cap from the rim elevation to the pole.
fn cap_point(rng: &mut SceneRng) -> [f64; 3] {
    sphere_zone(rng, RIM_ELEVATION_DEG.to_radians().sin())
}

/// A point uniform in the unit disc lifted onto `z = 1 - rho²`, kept with
/// probability proportional to the area element `sqrt(1 + 4 rho²)` (at most
/// `sqrt 5`), so the accepted points are uniform by area.
fn paraboloid_point(rng: &mut SceneRng) -> Option<[f64; 3]> {
    let (rho, angle) = (rng.random::<f64>().sqrt(), TAU * rng.random::<f64>());
    let stretch = (1.0 + 4.0 * rho * rho).sqrt() / 5f64.sqrt();
    (rng.random::<f64>() < stretch).then(|| [rho * angle.cos(), rho * angle.sin(), 1.0 - rho * rho])
}

/// A standard normal number (Box-Muller).
fn gaussian(rng: &mut SceneRng) -> f64 {
    let u = 1.0 - rng.random::<f64>(); // (0, 1]: the log is finite
    (-2.0 * u.ln()).sqrt() * (TAU * rng.random::<f64>()).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_are_seeded_and_lie_near_their_surface() {
        for shape in SCANNED_SHAPES {
            let a = shape.sample(0.3, 2_000, 7);
            assert_eq!(a, shape.sample(0.3, 2_000, 7), "{}", shape.name());
            assert_ne!(a, shape.sample(0.3, 2_000, 8), "{}", shape.name());
            assert_eq!(a.len(), 2_000);
            let low = a.iter().map(|p| p[2]).fold(f32::INFINITY, f32::min);
            let expected_low = if shape == ScannedShape::ClosedSphere {
                -0.3
            } else {
                0.0
            };
            assert!((low - expected_low).abs() < 0.03, "{}: {low}", shape.name());
        }
    }

    #[test]
    fn the_lopsided_cap_is_denser_on_its_positive_side() {
        let pts = ScannedShape::LopsidedCap.sample(1.0, 20_000, 1);
        let positive = pts.iter().filter(|p| p[0] > 0.0).count();
        // Density 0.575 + 0.425 x on the cap: the side x > 0 holds
        // 1/2 + 0.425 E[max(x, 0)] / 0.575 = 0.68 of the points (E = 1/4).
        assert!(positive as f64 > 0.65 * pts.len() as f64, "{positive}");
    }

    #[test]
    fn rim_distance_is_zero_on_the_rim() {
        let e = RIM_ELEVATION_DEG.to_radians();
        let on = [2.0 * e.cos(), 0.0, 2.0 * e.sin()];
        assert!(ScannedShape::Hemisphere.rim_distance(on, 2.0) < 1e-12);
        assert!((ScannedShape::Disc.rim_distance([0.0; 3], 2.0) - 2.0).abs() < 1e-12);
        assert!(ScannedShape::Band.rim_distance([0.0, 1.0, 1.0], 1.0) < 1e-12);
    }
}
