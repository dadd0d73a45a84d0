//! Adversarial point clouds, each reproducible from `(kind, points, seed)`: the
//! shapes that stress a safe fit (spikes, duplicates, extreme magnitudes and
//! offsets, holes, cliffs, thin projections, points on knot lines).

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::f64::consts::TAU;

/// The kinds of cloud the guarantee is attacked with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CloudKind {
    /// Uniform in a box of random extents.
    UniformBox,
    /// A few clusters of radius 1e-4 spread over a unit square.
    TightClusters,
    /// A thin layer with one point 1e3..1e12 above it and one as far below.
    Spikes,
    /// Four distinct points, each repeated many times.
    Duplicates,
    /// Every coordinate between 1e6 and 1e7.
    Huge,
    /// Every coordinate between -1e-6 and 1e-6.
    Tiny,
    /// A small wavy patch moved to (1e6, -1e6, 1e5).
    FarOffset,
    /// An annulus with two far satellites: empty cells and a hole.
    Holes,
    /// A height field with a skew cliff rising 10 over no horizontal distance.
    Cliff,
    /// Points exactly on a plane with a random normal.
    TiltedPlane,
    /// A column of points sharing one (x, y) above a flat base.
    Pillar,
    /// Integer lattice points: many lie exactly on knot lines and diagonals.
    Lattice,
    /// A unit patch with a few heights of ±1e30 (f32 holds up to 3.4e38): huge
    /// coefficients next to small heights, where rounding is largest.
    ExtremeHeights,
    /// `shroud_sim::Terrain` (hills and cliffs).
    SimTerrain,
    /// `shroud_sim::MovingSpheres` at a seed-dependent time.
    SimSpheres,
}

impl CloudKind {
    pub const ALL: [CloudKind; 15] = [
        CloudKind::UniformBox,
        CloudKind::TightClusters,
        CloudKind::Spikes,
        CloudKind::Duplicates,
        CloudKind::Huge,
        CloudKind::Tiny,
        CloudKind::FarOffset,
        CloudKind::Holes,
        CloudKind::Cliff,
        CloudKind::TiltedPlane,
        CloudKind::Pillar,
        CloudKind::Lattice,
        CloudKind::ExtremeHeights,
        CloudKind::SimTerrain,
        CloudKind::SimSpheres,
    ];
}

/// A generated cloud with the normal of the plane it roughly spans (used to aim
/// fitting directions nearly parallel to that plane).
#[derive(Debug, Clone)]
pub struct Cloud {
    pub points: Vec<[f32; 3]>,
    pub normal: [f64; 3],
}

const UP: [f64; 3] = [0.0, 0.0, 1.0];

/// `count` points (at least one) of the given kind.
pub fn cloud(kind: CloudKind, count: usize, seed: u64) -> Cloud {
    let count = count.max(1);
    let mut rng = Pcg64::seed_from_u64(seed);
    let rng = &mut rng;
    match kind {
        CloudKind::UniformBox => {
            let e = [
                rng.random_range(0.1..10.0),
                rng.random_range(0.1..10.0),
                rng.random_range(0.0..10.0),
            ];
            flat((0..count).map(|_| {
                [
                    rng.random_range(0.0..=e[0]),
                    rng.random_range(0.0..=e[1]),
                    rng.random_range(0.0..=e[2]),
                ]
            }))
        }
        CloudKind::TightClusters => tight_clusters(rng, count),
        CloudKind::Spikes => spikes(rng, count),
        CloudKind::Duplicates => duplicates(rng, count),
        CloudKind::Huge => flat((0..count).map(|_| [0; 3].map(|_| rng.random_range(1e6..1e7)))),
        CloudKind::Tiny => flat((0..count).map(|_| [0; 3].map(|_| rng.random_range(-1e-6..1e-6)))),
        CloudKind::FarOffset => flat((0..count).map(|_| {
            let (x, y): (f64, f64) = (rng.random_range(0.0..20.0), rng.random_range(0.0..20.0));
            [1e6 + x, -1e6 + y, 1e5 + (x * 0.7).sin() * 3.0 + y * 0.1]
        })),
        CloudKind::Holes => holes(rng, count),
        CloudKind::Cliff => flat((0..count).map(|_| {
            let (x, y): (f64, f64) = (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
            let step = if y > 0.37 * x + 0.05 { 10.0 } else { 0.0 };
            [
                x,
                y,
                step + (3.0 * x).sin() * 0.2 + rng.random_range(0.0..1e-3),
            ]
        })),
        CloudKind::TiltedPlane => tilted_plane(rng, count),
        CloudKind::Pillar => flat((0..count).map(|i| {
            if i % 3 == 0 {
                [0.25, 0.5, i as f64 * 0.01]
            } else {
                [
                    rng.random_range(0.0..1.0),
                    rng.random_range(0.0..1.0),
                    rng.random_range(0.0..0.05),
                ]
            }
        })),
        CloudKind::Lattice => {
            let side = rng.random_range(2..=24);
            flat((0..count).map(|i| {
                let (x, y) = ((i % side) as f64, ((i / side) % side) as f64);
                [x, y, ((x * 1.3).sin() + (y * 0.7).cos()).round()]
            }))
        }
        CloudKind::ExtremeHeights => flat((0..count).map(|i| {
            let z = match i % 97 {
                13 => 1e30,
                55 => -1e30,
                _ => rng.random_range(0.0..1.0),
            };
            [rng.random_range(0.0..1.0), rng.random_range(0.0..1.0), z]
        })),
        CloudKind::SimTerrain => sim_points(
            shroud_sim::Terrain {
                points: count,
                seed,
                ..Default::default()
            }
            .generate(),
        ),
        CloudKind::SimSpheres => {
            let time = rng.random_range(0.0..13.0);
            sim_points(
                shroud_sim::MovingSpheres {
                    points: count,
                    seed,
                    ..Default::default()
                }
                .generate(time),
            )
        }
    }
}

fn to_f32(p: [f64; 3]) -> [f32; 3] {
    p.map(|x| x as f32)
}

fn flat(points: impl Iterator<Item = [f64; 3]>) -> Cloud {
    Cloud {
        points: points.map(to_f32).collect(),
        normal: UP,
    }
}

fn sim_points<E: std::fmt::Debug>(points: Result<Vec<[f32; 3]>, E>) -> Cloud {
    let points =
        points.unwrap_or_else(|e| panic!("the scene generator refused valid parameters: {e:?}"));
    Cloud { points, normal: UP }
}

fn tight_clusters(rng: &mut Pcg64, count: usize) -> Cloud {
    let centres: Vec<[f64; 3]> = (0..rng.random_range(2..=6))
        .map(|_| [0; 3].map(|_| rng.random_range(0.0..1.0)))
        .collect();
    flat((0..count).map(|i| {
        let c = centres[i % centres.len()];
        c.map(|x| x + rng.random_range(-1e-4..1e-4))
    }))
}

fn spikes(rng: &mut Pcg64, count: usize) -> Cloud {
    let (up, down) = (rng.random_range(0..count), rng.random_range(0..count));
    let height = 10f64.powi(rng.random_range(3..=12));
    // Half the layers are exactly flat: the surface then touches many points at
    // once, right where the spikes' huge coefficients cancel.
    let layer = if rng.random_bool(0.5) { 0.0 } else { 0.01 };
    flat((0..count).map(|i| {
        let (x, y) = (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
        let z = if i == up {
            height
        } else if i == down {
            -height
        } else {
            rng.random_range(0.0..=layer)
        };
        [x, y, z]
    }))
}

fn duplicates(rng: &mut Pcg64, count: usize) -> Cloud {
    let distinct: Vec<[f64; 3]> = (0..4)
        .map(|_| [0; 3].map(|_| rng.random_range(-1.0..1.0)))
        .collect();
    flat((0..count).map(|_| distinct[rng.random_range(0..distinct.len())]))
}

fn holes(rng: &mut Pcg64, count: usize) -> Cloud {
    flat((0..count).map(|i| {
        let a = rng.random_range(0.0..TAU);
        match i % 5 {
            0 => [
                5.0 + rng.random_range(0.0..0.1),
                5.0 + rng.random_range(0.0..0.1),
                1.0,
            ],
            1 => [
                -4.0 - rng.random_range(0.0..0.1),
                3.0 + rng.random_range(0.0..0.1),
                -1.0,
            ],
            _ => {
                let r = rng.random_range(0.7..1.0);
                [r * a.cos(), r * a.sin(), (3.0 * a).sin() * 0.3]
            }
        }
    }))
}

fn tilted_plane(rng: &mut Pcg64, count: usize) -> Cloud {
    let normal = random_unit(rng);
    let (e1, e2) = plane_basis(normal);
    let centre = [0; 3].map(|_| rng.random_range(-3.0..3.0));
    let points = (0..count)
        .map(|_| {
            let (a, b) = (rng.random_range(-5.0..5.0), rng.random_range(-5.0..5.0));
            to_f32([0, 1, 2].map(|k| centre[k] + a * e1[k] + b * e2[k]))
        })
        .collect();
    Cloud { points, normal }
}

/// A uniformly random unit vector (rejection from the cube).
pub fn random_unit(rng: &mut impl Rng) -> [f64; 3] {
    loop {
        let v = [0; 3].map(|_| rng.random_range(-1.0..1.0));
        let len = dot(v, v).sqrt();
        if (0.1..=1.0).contains(&len) {
            return v.map(|x| x / len);
        }
    }
}

/// Two unit vectors spanning the plane orthogonal to the unit vector `n`.
pub fn plane_basis(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let helper = if n[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = normalize(cross(n, helper));
    (e1, cross(n, e1))
}

pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub fn normalize(a: [f64; 3]) -> [f64; 3] {
    let len = dot(a, a).sqrt();
    a.map(|x| x / len)
}
