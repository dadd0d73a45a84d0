//! Test scenes for the blender (shared by tests/blend.rs, benches/blend.rs and
//! examples/blend_measures.rs): analytic children with an open boundary
//! (hemisphere, half-cylinder with closed ends, sphere cap from the simulator) and
//! parents (plane, sphere, the simulator's terrain and table top).
#![allow(dead_code)]

use std::f64::consts::{PI, TAU};

/// Deterministic uniform numbers in [0, 1) (SplitMix64).
pub struct Jitter(u64);

impl Jitter {
    pub fn new(seed: u64) -> Self {
        Self(seed ^ 0x9e37_79b9_7f4a_7c15)
    }
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn f32s(x: f64, y: f64, z: f64) -> [f32; 3] {
    [x as f32, y as f32, z as f32]
}

/// Jittered grid on the plane z = `height` over `[-half, half]^2`, about `count` points.
pub fn plane(half: f64, count: usize, height: f64, seed: u64) -> Vec<[f32; 3]> {
    let side = (count as f64).sqrt().ceil() as usize;
    let step = 2.0 * half / side as f64;
    let mut rng = Jitter::new(seed);
    let mut out = Vec::with_capacity(side * side);
    for i in 0..side {
        for j in 0..side {
            let x = -half + (i as f64 + 0.2 + 0.6 * rng.next()) * step;
            let y = -half + (j as f64 + 0.2 + 0.6 * rng.next()) * step;
            out.push(f32s(x, y, height));
        }
    }
    out
}

/// Upper hemisphere of radius `r` centred at the origin (open rim at z = 0),
/// Fibonacci-spaced, `count` points.
pub fn hemisphere(r: f64, count: usize) -> Vec<[f32; 3]> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - (i as f64 + 0.5) / count as f64; // (0, 1]
            let s = (1.0 - z * z).sqrt();
            let t = golden * i as f64;
            f32s(r * s * t.cos(), r * s * t.sin(), r * z)
        })
        .collect()
}

/// Upper half of a cylinder of radius `r` along x, length `len`, centred at the
/// origin, with its two ends closed by half discs: the only open boundary is the
/// rectangle in z = 0. About `count` points, uniform by area.
pub fn half_cylinder(r: f64, len: f64, count: usize, seed: u64) -> Vec<[f32; 3]> {
    let shell = PI * r * len;
    let caps = PI * r * r; // two half discs
    let n_shell = (count as f64 * shell / (shell + caps)) as usize;
    let mut rng = Jitter::new(seed);
    let mut out = Vec::with_capacity(count);
    let rows = ((n_shell as f64) * len / (PI * r)).sqrt().ceil() as usize;
    let cols = (n_shell / rows.max(1)).max(1);
    for i in 0..rows {
        for j in 0..cols {
            let x = -0.5 * len + (i as f64 + 0.5 + 0.4 * (rng.next() - 0.5)) * len / rows as f64;
            let a = (j as f64 + 0.5 + 0.4 * (rng.next() - 0.5)) * PI / cols as f64;
            out.push(f32s(x, r * a.cos(), r * a.sin()));
        }
    }
    let per_cap = (count - out.len().min(count)) / 2;
    for end in [-0.5 * len, 0.5 * len] {
        let golden = PI * (3.0 - 5f64.sqrt());
        for i in 0..per_cap {
            // Fibonacci half disc (y, z >= 0.02 r so the rim stays the rectangle's).
            let rad = r * ((i as f64 + 0.5) / per_cap as f64).sqrt();
            let t = (golden * i as f64).rem_euclid(TAU);
            let (y, z) = (rad * t.cos(), rad * t.sin().abs());
            if z > 0.02 * r {
                out.push(f32s(end, y, z));
            }
        }
    }
    out
}

/// Annulus `inner <= |p| <= outer` in z = 0: a disc with a hole, for boundary tests.
pub fn disc_with_hole(inner: f64, outer: f64, count: usize, seed: u64) -> Vec<[f32; 3]> {
    plane(outer, count, 0.0, seed)
        .into_iter()
        .filter(|p| {
            let r = f64::from(p[0]).hypot(f64::from(p[1]));
            (inner..=outer).contains(&r)
        })
        .collect()
}

/// Points on a sphere of radius `r` centred at `centre`, from the simulator's
/// moving-spheres scene (surface only, frozen at its centre).
pub fn sim_sphere(r: f32, centre: [f64; 3], count: usize, seed: u64) -> Vec<[f32; 3]> {
    let fixed = shroud_sim::LissajousPath {
        centre,
        amplitude: [0.0; 3],
        angular_speed: [0.0; 3],
        phase: [0.0; 3],
    };
    shroud_sim::MovingSpheres {
        points: count,
        radii: [r, r],
        paths: [fixed, fixed],
        seed,
        surface_only: true,
        split: 1.0,
    }
    .generate(0.0)
    .expect("valid sphere scene")
}

/// A sphere cap from the simulator: the sphere of radius `r` at the origin cut
/// below z = -`cut` r, so it opens downward with a circular rim.
pub fn sim_cap(r: f32, cut: f64, count: usize, seed: u64) -> Vec<[f32; 3]> {
    sim_sphere(r, [0.0; 3], count, seed)
        .into_iter()
        .filter(|p| f64::from(p[2]) > -cut * f64::from(r))
        .collect()
}

/// The simulator's terrain (hills and cliffs over 8 x 6).
pub fn sim_terrain(count: usize, seed: u64) -> Vec<[f32; 3]> {
    shroud_sim::Terrain {
        points: count,
        seed,
        ..Default::default()
    }
    .generate()
    .expect("valid terrain")
}

/// The simulator's table top (boxes and a cylinder on an 8 x 6 table).
pub fn sim_table(count: usize, seed: u64) -> Vec<[f32; 3]> {
    shroud_sim::TableTop {
        points: count,
        seed,
        ..Default::default()
    }
    .generate()
    .expect("valid table top")
}
