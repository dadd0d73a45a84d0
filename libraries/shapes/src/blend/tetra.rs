//! Sampling the zero set of the RBF by marching tetrahedra (Zou et al., Section 5),
//! restricted to the blending region by surface following: starting from the grid
//! cells that hold the constraint points, only cells the surface passes through
//! are expanded (Bloomenthal's continuation), never the whole volume. Each cube is
//! split into the six Kuhn tetrahedra around its main diagonal (consistent across
//! neighbours), so the tetrahedra's edges are the cube edges, the face diagonals
//! and the body diagonal. Every sign-changing edge gives one point, placed by
//! linear interpolation and one Newton step along the gradient, which is also its
//! normal.

use super::error::BlendError;
use super::rbf::Rbf;
use glam::{DVec3, IVec3};
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// Points on the sampled transition surface T_R with unit normals (toward +s,
/// the outside).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SampledSurface {
    pub points: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    /// Cells visited and cells the surface crosses.
    pub cells_visited: usize,
    pub cells_crossed: usize,
    /// RBF evaluations spent (corner values plus point refinements).
    pub evaluations: usize,
}

/// The seven edge directions of the Kuhn triangulation (lower vertex to upper).
const DIRECTIONS: [IVec3; 7] = [
    IVec3::new(1, 0, 0),
    IVec3::new(0, 1, 0),
    IVec3::new(0, 0, 1),
    IVec3::new(1, 1, 0),
    IVec3::new(1, 0, 1),
    IVec3::new(0, 1, 1),
    IVec3::new(1, 1, 1),
];

const FACES: [IVec3; 6] = [
    IVec3::new(1, 0, 0),
    IVec3::new(-1, 0, 0),
    IVec3::new(0, 1, 0),
    IVec3::new(0, -1, 0),
    IVec3::new(0, 0, 1),
    IVec3::new(0, 0, -1),
];

/// A cheap multiplicative hasher for packed grid keys.
#[derive(Default)]
struct GridHasher(u64);

impl Hasher for GridHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (x ^ (x >> 29)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        self.0 ^= self.0 >> 32;
    }
}

type Fast = BuildHasherDefault<GridHasher>;

/// Corner `i` (bits x, y, z) of a unit cell, as an offset from its lower corner.
fn corner_offset(i: usize) -> IVec3 {
    IVec3::new((i & 1) as i32, ((i >> 1) & 1) as i32, ((i >> 2) & 1) as i32)
}

/// The inverse of [`corner_offset`] for offsets in {0, 1}^3.
fn corner_index(o: IVec3) -> usize {
    (o.x | (o.y << 1) | (o.z << 2)) as usize
}

/// Packs a grid vertex (each coordinate within +-2^20) into a u64.
fn pack(v: IVec3) -> u64 {
    let f = |c: i32| (c as i64 + (1 << 20)) as u64 & 0x1f_ffff;
    f(v.x) | f(v.y) << 21 | f(v.z) << 42
}

/// The zero set of `rbf` around `seeds`, on a grid of spacing `cell` anchored at
/// `origin`, expanding only through cells whose centre satisfies `inside`.
/// Fails if more than `max_cells` cells would be visited or the seeds are not
/// near any zero crossing.
pub fn sample_zero_set(
    rbf: &Rbf,
    seeds: &[DVec3],
    origin: DVec3,
    cell: f64,
    inside: &(dyn Fn(DVec3) -> bool + Sync),
    max_cells: usize,
) -> Result<SampledSurface, BlendError> {
    if !(cell > 0.0 && cell.is_finite()) {
        return Err(BlendError::InvalidParameter {
            name: "cell",
            value: cell,
            reason: "the sampling cell must be positive",
        });
    }
    let to_cell = |p: DVec3| -> Option<IVec3> {
        let g = ((p - origin) / cell).floor();
        (g.abs().max_element() < f64::from(1 << 19)).then(|| g.as_ivec3())
    };
    let vertex = |v: IVec3| origin + v.as_dvec3() * cell;
    let centre = |c: IVec3| origin + (c.as_dvec3() + 0.5) * cell;

    let mut values: HashMap<u64, f64, Fast> = HashMap::default();
    let mut visited: HashSet<u64, Fast> = HashSet::default();
    let mut crossed: Vec<IVec3> = Vec::new();
    let mut frontier: Vec<(IVec3, bool)> = Vec::new();
    for &s in seeds {
        if let Some(c) = to_cell(s) {
            if visited.insert(pack(c)) {
                frontier.push((c, true));
            }
        }
    }
    let mut evaluations = 0usize;
    while !frontier.is_empty() {
        if visited.len() > max_cells {
            return Err(BlendError::SamplingLimit { limit: max_cells });
        }
        // Corner values of this layer, evaluated in parallel.
        let mut needed: Vec<IVec3> = Vec::new();
        let mut queued: HashSet<u64, Fast> = HashSet::default();
        for &(c, _) in &frontier {
            for corner in 0..8 {
                let v = c + corner_offset(corner);
                let key = pack(v);
                if !values.contains_key(&key) && queued.insert(key) {
                    needed.push(v);
                }
            }
        }
        let fresh: Vec<f64> = needed
            .par_iter()
            .with_min_len(32)
            .map(|&v| rbf.value(vertex(v)))
            .collect();
        evaluations += fresh.len();
        for (v, s) in needed.into_iter().zip(fresh) {
            values.insert(pack(v), s);
        }
        let mut next = Vec::new();
        for (c, seed) in frontier {
            let mut positive = 0;
            for corner in 0..8 {
                let v = c + corner_offset(corner);
                if values.get(&pack(v)).copied().unwrap_or(0.0) >= 0.0 {
                    positive += 1;
                }
            }
            let crosses = positive != 0 && positive != 8;
            if crosses {
                crossed.push(c);
            }
            if crosses || seed {
                for f in FACES {
                    let n = c + f;
                    if inside(centre(n)) && visited.insert(pack(n)) {
                        next.push((n, false));
                    }
                }
            }
        }
        frontier = next;
    }
    if crossed.is_empty() {
        return Err(BlendError::NoTransitionSurface);
    }
    // One point per sign-changing tetrahedron edge, deduplicated.
    let mut edges: HashSet<(u64, u8), Fast> = HashSet::default();
    let mut raw: Vec<(DVec3, f64)> = Vec::new();
    for &c in &crossed {
        // The cell's eight corner values, looked up once (every corner of a
        // crossed cell was evaluated): the 19 edges below only index them.
        let mut corner_values = [0.0f64; 8];
        for (corner, value) in corner_values.iter_mut().enumerate() {
            let v = c + corner_offset(corner);
            *value = values.get(&pack(v)).copied().unwrap_or(0.0);
        }
        for corner in 0..8 {
            let o = corner_offset(corner);
            let sa = corner_values[corner];
            for (k, d) in DIRECTIONS.iter().enumerate() {
                let end = o + *d;
                if end.max_element() > 1 {
                    continue;
                }
                let sb = corner_values[corner_index(end)];
                let a = c + o;
                if (sa >= 0.0) == (sb >= 0.0) || !edges.insert((pack(a), k as u8)) {
                    continue;
                }
                let t = sa / (sa - sb);
                raw.push((
                    vertex(a).lerp(vertex(a + *d), t),
                    cell * d.as_dvec3().length(),
                ));
            }
        }
    }
    let refined: Vec<(DVec3, DVec3)> = raw
        .par_iter()
        .with_min_len(32)
        .map(|&(p, edge)| {
            let (s, g) = rbf.value_gradient(p);
            let g2 = g.length_squared();
            if !(g2 > 0.0) || !s.is_finite() {
                return (p, DVec3::ZERO);
            }
            let step = (s / g2) * g;
            let step = if step.length() > 0.5 * edge {
                step * (0.5 * edge / step.length())
            } else {
                step
            };
            (p - step, g / g2.sqrt())
        })
        .collect();
    evaluations += refined.len();
    let (points, normals) = refined
        .into_iter()
        .filter(|(_, n)| *n != DVec3::ZERO)
        .unzip();
    Ok(SampledSurface {
        points,
        normals,
        cells_visited: visited.len(),
        cells_crossed: crossed.len(),
        evaluations,
    })
}
