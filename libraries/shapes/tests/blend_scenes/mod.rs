//! Test scenes for the blender (shared by tests/blend.rs, benches/blend.rs and
//! examples/blend_measures.rs): analytic children with an open boundary
//! (hemisphere, half-cylinder with closed ends, sphere cap from the simulator) and
//! parents (plane, sphere, the simulator's terrain and table top).
#![allow(dead_code)]

// Not every includer uses every part.
#[allow(unused_imports)]
pub use shroud_sim::parts::{half_cylinder, hemisphere, Jitter};

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
            let x = -half + (i as f64 + 0.2 + 0.6 * rng.uniform()) * step;
            let y = -half + (j as f64 + 0.2 + 0.6 * rng.uniform()) * step;
            out.push(f32s(x, y, height));
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
        floor: None,
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
