//! Surrogates for the query tests: hand-made ones (random coefficients, chosen
//! trims, tilted frames) and ones fitted to the simulator's clouds.

use crate::trim::{ALL, BOTTOM};
use crate::{
    fit_surrogate, Certificate, Domain, FitOptions, FitStats, SafeSurface, Side, Sides, Surrogate,
    TrimMask,
};
use glam::DVec3;
use rand::{Rng, SeedableRng};
use shroud_geometry::math::Frame;
use shroud_geometry::spline::UniformCubicSurface;

pub fn rng(seed: u64) -> rand_pcg::Pcg64 {
    rand_pcg::Pcg64::seed_from_u64(seed)
}

fn certificate(side: Side, direction: DVec3) -> Certificate {
    Certificate {
        side,
        direction: direction.to_array(),
        points_checked: 0,
        violations: 0,
        min_gap: 0.0,
        max_gap: 0.0,
        mean_gap: 0.0,
        corrected_points: 0,
    }
}

pub fn domain(cols: usize, rows: usize) -> Domain {
    Domain {
        u_min: -1.5,
        v_min: 0.7,
        u_step: 0.4,
        v_step: 0.3,
        cols,
        rows,
    }
}

/// A surrogate from its parts (coefficients row-major, `cols x rows`).
pub fn assemble(
    direction: [f64; 3],
    domain: Domain,
    trim: TrimMask,
    sides: [Option<Vec<f64>>; 2],
) -> Surrogate {
    let frame = Frame::from_direction(DVec3::from_array(direction)).unwrap();
    let [upper, lower] = sides;
    let safe = |side, c: Option<Vec<f64>>| {
        c.map(|c| SafeSurface {
            side,
            surface: UniformCubicSurface::new(domain.cols, domain.rows, c).unwrap(),
            certificate: certificate(side, frame.direction),
        })
    };
    Surrogate {
        frame,
        domain,
        trim,
        upper: safe(Side::Upper, upper),
        lower: safe(Side::Lower, lower),
        stats: FitStats::default(),
    }
}

pub fn random_coefficients(n: usize, seed: u64) -> Vec<f64> {
    let mut r = rng(seed);
    (0..n).map(|_| r.random_range(-1.0..1.0)).collect()
}

/// Upper surface with random coefficients in `[-1, 1]`, nothing trimmed.
pub fn random_surrogate(cols: usize, rows: usize, direction: [f64; 3], seed: u64) -> Surrogate {
    let trim = TrimMask::full(cols - 1, rows - 1);
    assemble(
        direction,
        domain(cols, rows),
        trim,
        [Some(random_coefficients(cols * rows, seed)), None],
    )
}

/// A random trim mask keeping each triangle with probability one half.
pub fn random_trim(cells_s: usize, cells_t: usize, seed: u64) -> TrimMask {
    let mut r = rng(seed);
    let mut trim = TrimMask::empty(cells_s, cells_t);
    trim.bits
        .iter_mut()
        .for_each(|b| *b = r.random_range(0..=ALL));
    trim
}

/// 3 x 3 grid (2 x 2 cells); cell (0, 0) keeps only its bottom triangle.
pub fn trimmed_surrogate() -> Surrogate {
    let mut trim = TrimMask::full(2, 2);
    trim.bits[0] = BOTTOM;
    assemble(
        [0.0, 0.0, -1.0],
        domain(3, 3),
        trim,
        [Some(random_coefficients(9, 11)), None],
    )
}

/// A surrogate fitted (and certified) to `points`.
pub fn fitted(points: &[[f32; 3]], sides: Sides, direction: [f64; 3], grid: usize) -> Surrogate {
    let options = FitOptions {
        cols: grid,
        rows: grid,
        direction,
        sides,
        ..FitOptions::default()
    };
    fit_surrogate(points, &options).unwrap()
}

pub fn terrain(points: usize) -> Vec<[f32; 3]> {
    shroud_sim::Terrain {
        points,
        ..Default::default()
    }
    .generate()
    .unwrap()
}

pub fn spheres(points: usize, time: f64) -> Vec<[f32; 3]> {
    shroud_sim::MovingSpheres {
        points,
        ..Default::default()
    }
    .generate(time)
    .unwrap()
}

pub fn to_dvec(p: &[f32; 3]) -> DVec3 {
    DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
}
