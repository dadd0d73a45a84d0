//! Sampling the zero set of the RBF by marching tetrahedra (Zou et al., Section 5),
//! restricted to the blending region by surface following: starting from the grid
//! cells that hold the constraint points, only cells the surface passes through
//! are expanded (Bloomenthal's continuation), never the whole volume. Each cube is
//! split into the six Kuhn tetrahedra around its main diagonal (consistent across
//! neighbours), so the tetrahedra's edges are the cube edges, the face diagonals
//! and the body diagonal. Every sign-changing edge gives one point, placed by
//! linear interpolation and one Newton step along the gradient, which is also its
//! normal. The RBF is evaluated in batches, one layer of the walk at a time, by
//! its split evaluation ([`SplitField`]) unless the caller passes another.

use super::error::BlendError;
use super::lattice::{cell_of, pack, Fast};
use super::rbf::{BatchField, Rbf, SplitField};
use glam::{DVec3, IVec3};
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};

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

/// Corner `i` (bits x, y, z) of a unit cell, as an offset from its lower corner.
fn corner_offset(i: usize) -> IVec3 {
    IVec3::new((i & 1) as i32, ((i >> 1) & 1) as i32, ((i >> 2) & 1) as i32)
}

/// The inverse of [`corner_offset`] for offsets in {0, 1}^3.
fn corner_index(o: IVec3) -> usize {
    (o.x | (o.y << 1) | (o.z << 2)) as usize
}

/// The sampling grid: cells of side `cell` anchored at `origin`.
#[derive(Debug, Clone, Copy)]
struct Grid {
    origin: DVec3,
    cell: f64,
}

impl Grid {
    fn vertex(&self, v: IVec3) -> DVec3 {
        self.origin + v.as_dvec3() * self.cell
    }
    fn centre(&self, c: IVec3) -> DVec3 {
        self.origin + (c.as_dvec3() + 0.5) * self.cell
    }
}

/// A cell the surface crosses, with its eight corner values.
struct Crossed {
    cell: IVec3,
    corners: [f64; 8],
}

/// What the walk over the cells found.
struct Walk {
    /// Refined points and their normals (zero where the gradient vanished).
    refined: Vec<(DVec3, DVec3)>,
    crossed: usize,
    visited: usize,
    evaluations: usize,
}

/// The zero set of `rbf` around `seeds`, on a grid of spacing `cell` anchored at
/// `origin`, expanding only through cells whose centre satisfies `inside`.
/// Fails if more than `max_cells` cells would be visited or the seeds are not
/// near any zero crossing. The RBF is evaluated by [`SplitField::for_sampling`].
pub fn sample_zero_set(
    rbf: &Rbf,
    seeds: &[DVec3],
    origin: DVec3,
    cell: f64,
    inside: &(dyn Fn(DVec3) -> bool + Sync),
    max_cells: usize,
) -> Result<SampledSurface, BlendError> {
    check_cell(cell)?;
    let mut field = SplitField::for_sampling(rbf, cell);
    sample_zero_set_with(&mut field, seeds, origin, cell, inside, max_cells)
}

/// [`sample_zero_set`] with the field evaluated by `field` (for instance
/// [`super::rbf::ExactField`], the direct sum).
pub fn sample_zero_set_with(
    field: &mut dyn BatchField,
    seeds: &[DVec3],
    origin: DVec3,
    cell: f64,
    inside: &(dyn Fn(DVec3) -> bool + Sync),
    max_cells: usize,
) -> Result<SampledSurface, BlendError> {
    check_cell(cell)?;
    let grid = Grid { origin, cell };
    let walk = follow_surface(field, grid, seeds, inside, max_cells)?;
    if walk.crossed == 0 {
        return Err(BlendError::NoTransitionSurface);
    }
    let (points, normals) = walk
        .refined
        .into_iter()
        .filter(|(_, n)| *n != DVec3::ZERO)
        .unzip();
    Ok(SampledSurface {
        points,
        normals,
        cells_visited: walk.visited,
        cells_crossed: walk.crossed,
        evaluations: walk.evaluations,
    })
}

fn check_cell(cell: f64) -> Result<(), BlendError> {
    if cell > 0.0 && cell.is_finite() {
        return Ok(());
    }
    Err(BlendError::InvalidParameter {
        name: "cell",
        value: cell,
        reason: "the sampling cell must be positive",
    })
}

/// The continuation: a breadth-first walk from the seeds' cells through the
/// faces of every crossed cell (and every seed cell), one layer at a time.
/// Each layer's crossed cells are refined right away, while the evaluator's
/// data for their cells is still at hand.
fn follow_surface(
    field: &mut dyn BatchField,
    grid: Grid,
    seeds: &[DVec3],
    inside: &(dyn Fn(DVec3) -> bool + Sync),
    max_cells: usize,
) -> Result<Walk, BlendError> {
    let mut values: HashMap<u64, f64, Fast> = HashMap::default();
    let mut visited: HashSet<u64, Fast> = HashSet::default();
    let mut outside: HashSet<u64, Fast> = HashSet::default();
    let mut crossed = 0;
    let mut edges: HashSet<(u64, u8), Fast> = HashSet::default();
    let mut refined = Vec::new();
    let mut frontier: Vec<(IVec3, bool)> = Vec::new();
    for &s in seeds {
        if let Some(c) = cell_of(s - grid.origin, grid.cell) {
            if visited.insert(pack(c)) {
                frontier.push((c, true));
            }
        }
    }
    let mut evaluations = 0;
    while !frontier.is_empty() {
        if visited.len() > max_cells {
            return Err(BlendError::SamplingLimit { limit: max_cells });
        }
        evaluations += evaluate_corners(field, grid, &frontier, &mut values);
        let mut next = Vec::new();
        let mut layer = Vec::new();
        let mut candidates = Vec::new();
        let mut queued: HashSet<u64, Fast> = HashSet::default();
        for (c, seed) in frontier {
            let corners = corner_values(&values, c);
            let positive = corners.iter().filter(|&&s| s >= 0.0).count();
            let crosses = positive != 0 && positive != 8;
            if crosses {
                layer.push(Crossed { cell: c, corners });
            }
            if !(crosses || seed) {
                continue;
            }
            for f in FACES {
                let n = c + f;
                let key = pack(n);
                if !visited.contains(&key) && !outside.contains(&key) && queued.insert(key) {
                    candidates.push(n);
                }
            }
        }
        // The region test (a polygon distance) in parallel, in walk order.
        let within: Vec<bool> = candidates
            .par_iter()
            .with_min_len(256)
            .map(|&n| inside(grid.centre(n)))
            .collect();
        for (n, within) in candidates.into_iter().zip(within) {
            if within {
                visited.insert(pack(n));
                next.push((n, false));
            } else {
                outside.insert(pack(n));
            }
        }
        crossed += layer.len();
        let (starts, lengths) = edge_points(&layer, grid, &mut edges);
        evaluations += starts.len();
        refined.extend(refine(field, &starts, &lengths));
        frontier = next;
    }
    Ok(Walk {
        refined,
        crossed,
        visited: visited.len(),
        evaluations,
    })
}

/// Evaluates the corners of `frontier` not yet in `values`, in one batch;
/// returns how many.
fn evaluate_corners(
    field: &mut dyn BatchField,
    grid: Grid,
    frontier: &[(IVec3, bool)],
    values: &mut HashMap<u64, f64, Fast>,
) -> usize {
    let mut needed: Vec<IVec3> = Vec::new();
    let mut queued: HashSet<u64, Fast> = HashSet::default();
    for &(c, _) in frontier {
        for corner in 0..8 {
            let v = c + corner_offset(corner);
            let key = pack(v);
            if !values.contains_key(&key) && queued.insert(key) {
                needed.push(v);
            }
        }
    }
    let positions: Vec<DVec3> = needed.iter().map(|&v| grid.vertex(v)).collect();
    let fresh = field.values(&positions);
    for (v, s) in needed.iter().zip(fresh) {
        values.insert(pack(*v), s);
    }
    needed.len()
}

fn corner_values(values: &HashMap<u64, f64, Fast>, c: IVec3) -> [f64; 8] {
    std::array::from_fn(|corner| {
        let v = c + corner_offset(corner);
        values.get(&pack(v)).copied().unwrap_or(0.0)
    })
}

/// One point per sign-changing tetrahedron edge not in `edges` yet (which it
/// joins), by linear interpolation, with its edge's length.
fn edge_points(
    crossed: &[Crossed],
    grid: Grid,
    edges: &mut HashSet<(u64, u8), Fast>,
) -> (Vec<DVec3>, Vec<f64>) {
    let mut starts = Vec::new();
    let mut lengths = Vec::new();
    for Crossed { cell: c, corners } in crossed {
        for corner in 0..8 {
            let o = corner_offset(corner);
            let sa = corners[corner];
            for (k, d) in DIRECTIONS.iter().enumerate() {
                let end = o + *d;
                if end.max_element() > 1 {
                    continue;
                }
                let sb = corners[corner_index(end)];
                let a = *c + o;
                if (sa >= 0.0) == (sb >= 0.0) || !edges.insert((pack(a), k as u8)) {
                    continue;
                }
                let t = sa / (sa - sb);
                starts.push(grid.vertex(a).lerp(grid.vertex(a + *d), t));
                lengths.push(grid.cell * d.as_dvec3().length());
            }
        }
    }
    (starts, lengths)
}

/// One Newton step from each start toward the zero set, at most half its
/// edge's length; the unit gradient is the normal (zero where it vanishes).
fn refine(field: &mut dyn BatchField, starts: &[DVec3], edges: &[f64]) -> Vec<(DVec3, DVec3)> {
    field
        .value_gradients(starts)
        .into_iter()
        .zip(starts.iter().zip(edges))
        .map(|((s, g), (&p, &edge))| {
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
        .collect()
}
