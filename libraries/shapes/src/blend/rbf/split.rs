//! The RBF evaluated fast at the many points of a zero-set sampling: the cubic
//! kernel split at a radius (see [`super::split_kernel`]) into a far part summed
//! over every centre only at the nodes of a coarse lattice and interpolated
//! (tensor Lagrange of degree 5) in between, and a near part summed exactly over the few
//! centres within the radius. Carr et al. ("Reconstruction and representation of
//! 3D objects with radial basis functions", 2001), whose RBFs paper 001 fits,
//! evaluate them with fast multipole methods for the same reason: a direct sum
//! costs every centre at every point.
//!
//! The result differs from the direct sum by the interpolation error of the far
//! field, sixth order in the lattice step; the defaults keep it far below the
//! sampling cell (tests compare it with the direct sum).

use super::batch::BatchField;
use super::centre_bins::CentreBins;
use super::eval::Rbf;
use super::far_lattice::FarLattice;
use super::near_sum::NearCentres;
use super::split_kernel::SplitKernel;
use crate::blend::lattice::{cell_of, pack, Fast};
use glam::{DVec3, IVec3};
use rayon::prelude::*;
use std::collections::HashMap;

const LANES: usize = 4;

/// The interpolation stencil: 6 nodes per axis, from two below the cell's lower
/// corner to three above it (Lagrange of degree 5).
const STENCIL: usize = 6;

/// The stencil's first node, relative to the cell.
const BELOW: i32 = (STENCIL as i32 - 1) / 2;

/// Lattice cells whose shared data is kept at once. An entry holds a 6 x 6 x 6
/// stencil (1.7 KB) and its near centres (32 bytes a centre): issue 27's scene
/// uses about 7,000 cells of about 200 centres. Past either bound the cache
/// starts over: the data is a pure function of the cell, so results do not
/// change, only time.
const MAX_CACHED_CELLS: usize = 1 << 14;

/// Near-centre entries kept at once, over all cached cells (64 MB).
const MAX_CACHED_NEAR: usize = 1 << 21;

/// The RBF split into an interpolated far field and an exact near sum.
pub struct SplitField<'a> {
    rbf: &'a Rbf,
    kernel: SplitKernel,
    /// Lattice spacing of the far field, in the RBF's scaled coordinates.
    step: f64,
    /// The centres (scaled), for the near sums.
    centres: CentreBins,
    /// The far field at the lattice nodes computed so far.
    far: FarLattice,
    /// What the points of each cell seen so far share.
    cells: HashMap<u64, CellData, Fast>,
    /// Near-centre entries held by `cells`.
    cached_near: usize,
    /// Batches evaluated so far.
    batches: u64,
}

/// The points of one batch that fall in one lattice cell.
struct CellGroup {
    cell: IVec3,
    /// Its points: a range of the batch's cell-sorted order.
    members: std::ops::Range<usize>,
}

/// What one cell's points share: the far field at its stencil's nodes and the
/// centres near enough to matter.
struct CellData {
    /// Boxed: the cache's table then moves small entries when it grows.
    nodes: Box<[[[f64; STENCIL]; STENCIL]; STENCIL]>,
    near: NearCentres,
    /// The last batch that used the cell.
    used: u64,
}

impl<'a> SplitField<'a> {
    /// Splits `rbf` at `radius` with a far-field lattice of spacing `step` (both
    /// in world units; the radius is kept at least three steps).
    pub fn new(rbf: &'a Rbf, step: f64, radius: f64) -> Self {
        let step = step / rbf.scale;
        let radius = (radius / rbf.scale).max(3.0 * step);
        let centres = rbf.local_centres();
        Self {
            rbf,
            kernel: SplitKernel::new(radius),
            step,
            centres: CentreBins::new(centres, radius),
            far: FarLattice::default(),
            cells: HashMap::default(),
            cached_near: 0,
            batches: 0,
        }
    }

    /// The split a zero-set sampling on cells of `cell` (world units) uses: a
    /// lattice of two cells and a radius of twelve cells. On issue 27's scene
    /// (1200 centres) the sampled points then lie within 8e-6 of the RBF's zero
    /// set (a thousandth of a cell; the direct sum's within 3e-6), on the test
    /// scenes within 2e-3 of a cell more than the direct sum's; a lattice of
    /// three cells gives 7e-5 there, of four 3e-4, for less work.
    pub fn for_sampling(rbf: &'a Rbf, cell: f64) -> Self {
        Self::new(rbf, 2.0 * cell, 12.0 * cell)
    }

    /// Far-field lattice nodes computed so far (each a sum over every centre).
    pub fn far_nodes(&self) -> usize {
        self.far.len()
    }

    /// The far part of the sum at scaled point `q`: every centre's far kernel.
    fn far_sum(&self, q: DVec3) -> f64 {
        let r = self.rbf;
        let mut acc = [0.0f64; LANES];
        let chunks = r.xs.len() / LANES * LANES;
        let lanes = r.xs[..chunks]
            .chunks_exact(LANES)
            .zip(r.ys[..chunks].chunks_exact(LANES))
            .zip(r.zs[..chunks].chunks_exact(LANES))
            .zip(r.weights[..chunks].chunks_exact(LANES));
        for (((x, y), z), w) in lanes {
            for l in 0..LANES {
                let (dx, dy, dz) = (q.x - x[l], q.y - y[l], q.z - z[l]);
                acc[l] += w[l] * self.kernel.far(dx * dx + dy * dy + dz * dz);
            }
        }
        let tail = (chunks..r.xs.len()).map(|i| {
            let d = q - DVec3::new(r.xs[i], r.ys[i], r.zs[i]);
            r.weights[i] * self.kernel.far(d.length_squared())
        });
        acc.iter().sum::<f64>() + tail.sum::<f64>()
    }

    /// Computes the far field at every stencil node of `cells` not yet known.
    fn fill_far(&mut self, cells: &[IVec3]) {
        let nodes = self.far.missing(cells, -BELOW, STENCIL as i32 - 1 - BELOW);
        let step = self.step;
        let values: Vec<f64> = nodes
            .par_iter()
            .with_min_len(8)
            .map(|&n| self.far_sum(n.as_dvec3() * step))
            .collect();
        self.far.set(&nodes, &values);
    }

    /// The stencil's far values and the near centres of `cell`.
    fn cell_data(&self, cell: IVec3) -> CellData {
        let nodes = Box::new(self.far.stencil::<STENCIL>(cell, -BELOW));
        // Every centre within the radius of some point of the cell.
        let centre = (cell.as_dvec3() + 0.5) * self.step;
        let reach = self.kernel.radius() + 0.5 * 3f64.sqrt() * self.step;
        // Off the lattice the query cannot be binned: take every centre.
        let near = self
            .centres
            .within(centre, reach)
            .unwrap_or_else(|| (0..self.rbf.centres() as u32).collect());
        CellData {
            nodes,
            near: NearCentres::new(self.rbf, &near),
            used: 0,
        }
    }

    /// Prepares the cells of `groups` not seen before (or no longer cached):
    /// their far-field nodes, then their shared data.
    fn prepare(&mut self, groups: &[CellGroup]) {
        self.batches += 1;
        let batch = self.batches;
        for g in groups {
            if let Some(d) = self.cells.get_mut(&pack(g.cell)) {
                d.used = batch;
            }
        }
        self.evict(groups.len());
        let fresh: Vec<IVec3> = groups
            .iter()
            .map(|g| g.cell)
            .filter(|c| !self.cells.contains_key(&pack(*c)))
            .collect();
        self.fill_far(&fresh);
        let data: Vec<CellData> = fresh
            .par_iter()
            .with_min_len(4)
            .map(|&c| self.cell_data(c))
            .collect();
        for (c, mut d) in fresh.into_iter().zip(data) {
            d.used = batch;
            self.cached_near += d.near.len();
            self.cells.insert(pack(c), d);
        }
    }

    /// Keeps the cache within its bounds before `incoming` cells arrive: first
    /// drops the cells the current batch does not use (a walk moves on, its
    /// old layers are not seen again), then, if still needed, everything.
    fn evict(&mut self, incoming: usize) {
        let over = |this: &Self| {
            this.cells.len() + incoming > MAX_CACHED_CELLS || this.cached_near > MAX_CACHED_NEAR
        };
        if over(self) {
            let batch = self.batches;
            self.cells.retain(|_, d| d.used == batch);
            self.cached_near = self.cells.values().map(|d| d.near.len()).sum();
        }
        if over(self) {
            self.cells.clear();
            self.cached_near = 0;
        }
    }

    /// `s` (and, with `GRADIENT`, its scaled gradient) at scaled point `q` in `cell`.
    fn evaluate<const GRADIENT: bool>(
        &self,
        data: &CellData,
        cell: IVec3,
        q: DVec3,
    ) -> (f64, DVec3) {
        let u = q / self.step - cell.as_dvec3();
        let (far, far_gradient) = interpolate::<GRADIENT>(&data.nodes, u);
        let (near, near_gradient) = data.near.sum::<GRADIENT>(&self.kernel, q);
        let p = self.rbf.poly;
        let value = far + near + p[0] + p[1] * q.x + p[2] * q.y + p[3] * q.z;
        let gradient = far_gradient / self.step + near_gradient + DVec3::new(p[1], p[2], p[3]);
        (value, gradient)
    }

    /// Every point of the batch, grouped by cell; points off the lattice (far
    /// away or not finite) are summed directly.
    fn batch<const GRADIENT: bool>(&mut self, points: &[DVec3]) -> Vec<(f64, DVec3)> {
        let (groups, order, strays) = self.group(points);
        self.prepare(&groups);
        let this = &*self;
        let evaluated: Vec<(usize, (f64, DVec3))> = groups
            .par_iter()
            .flat_map_iter(|group| {
                let data = this.cells.get(&pack(group.cell));
                let order = &order;
                group.members.clone().map(move |k| {
                    let i = order[k];
                    let value = match data {
                        Some(data) => {
                            let q = this.rbf.local(points[i]);
                            let (s, g) = this.evaluate::<GRADIENT>(data, group.cell, q);
                            (s, g / this.rbf.scale)
                        }
                        None => this.rbf.value_gradient(points[i]),
                    };
                    (i, value)
                })
            })
            .collect();
        let mut out = vec![(0.0, DVec3::ZERO); points.len()];
        for (i, v) in evaluated {
            out[i] = v;
        }
        for i in strays {
            out[i] = self.rbf.value_gradient(points[i]);
        }
        out
    }

    /// The batch's points grouped by lattice cell (as ranges of the returned
    /// order, which sorts the points by cell), and the points off the lattice.
    fn group(&self, points: &[DVec3]) -> (Vec<CellGroup>, Vec<usize>, Vec<usize>) {
        let mut keyed: Vec<(u64, usize)> = Vec::with_capacity(points.len());
        let mut strays = Vec::new();
        for (i, &p) in points.iter().enumerate() {
            match cell_of(self.rbf.local(p), self.step) {
                Some(cell) => keyed.push((pack(cell), i)),
                None => strays.push(i),
            }
        }
        keyed.sort_unstable();
        let mut groups: Vec<CellGroup> = Vec::new();
        for (k, &(key, i)) in keyed.iter().enumerate() {
            match groups.last_mut() {
                Some(g) if keyed[g.members.start].0 == key => g.members.end = k + 1,
                _ => groups.push(CellGroup {
                    cell: cell_of(self.rbf.local(points[i]), self.step).unwrap_or_default(),
                    members: k..k + 1,
                }),
            }
        }
        (groups, keyed.into_iter().map(|(_, i)| i).collect(), strays)
    }
}

/// `1 / prod_(k != j) (n_j - n_k)` for the stencil's nodes `n_j = j - BELOW`
/// (-2..3): the Lagrange weights' constant denominators, 1/(-120), 1/24,
/// 1/(-12), 1/12, 1/(-24), 1/120.
const INVERSE_DENOMINATORS: [f64; STENCIL] = [
    -1.0 / 120.0,
    1.0 / 24.0,
    -1.0 / 12.0,
    1.0 / 12.0,
    -1.0 / 24.0,
    1.0 / 120.0,
];

/// Lagrange weights of the stencil's nodes (at `j - BELOW`) at `u` in [0, 1),
/// and their derivatives: `w_j = prod_(k != j) (u - n_k) / d_j`, from prefix
/// and suffix products of the factors `u - n_k` carried with their
/// derivatives (dual numbers), so O(STENCIL) work instead of O(STENCIL^2).
fn lagrange_weights(u: f64) -> ([f64; STENCIL], [f64; STENCIL]) {
    // (value, derivative) of a product of factors (u - n_k).
    let times = |(p, dp): (f64, f64), k: usize| {
        let a = u - (k as f64 - f64::from(BELOW));
        (p * a, dp * a + p)
    };
    let mut prefix = [(1.0, 0.0); STENCIL];
    let mut suffix = [(1.0, 0.0); STENCIL];
    for j in 1..STENCIL {
        prefix[j] = times(prefix[j - 1], j - 1);
        let k = STENCIL - 1 - j;
        suffix[k] = times(suffix[k + 1], k + 1);
    }
    let mut weights = [0.0; STENCIL];
    let mut derivatives = [0.0; STENCIL];
    for j in 0..STENCIL {
        let ((p, dp), (q, dq)) = (prefix[j], suffix[j]);
        weights[j] = p * q * INVERSE_DENOMINATORS[j];
        derivatives[j] = (dp * q + p * dq) * INVERSE_DENOMINATORS[j];
    }
    (weights, derivatives)
}

fn dot(a: &[f64; STENCIL], b: &[f64; STENCIL]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Degree-5 Lagrange interpolation of the stencil `nodes` at `u` (cell coordinates in
/// [0, 1)^3) and, with `GRADIENT`, its gradient in cell units.
fn interpolate<const GRADIENT: bool>(
    nodes: &[[[f64; STENCIL]; STENCIL]; STENCIL],
    u: DVec3,
) -> (f64, DVec3) {
    let (wx, dx) = lagrange_weights(u.x);
    let (wy, dy) = lagrange_weights(u.y);
    let (wz, dz) = lagrange_weights(u.z);
    // Contract z, then y, then x; the gradient takes one derivative each time.
    let mut along_z = [[0.0; STENCIL]; STENCIL];
    let mut along_z_dz = [[0.0; STENCIL]; STENCIL];
    for a in 0..STENCIL {
        for b in 0..STENCIL {
            along_z[a][b] = dot(&nodes[a][b], &wz);
            if GRADIENT {
                along_z_dz[a][b] = dot(&nodes[a][b], &dz);
            }
        }
    }
    let column = |rows: &[[f64; STENCIL]; STENCIL], w: &[f64; STENCIL]| {
        std::array::from_fn::<f64, STENCIL, _>(|a| dot(&rows[a], w))
    };
    let along_y = column(&along_z, &wy);
    let value = dot(&along_y, &wx);
    if !GRADIENT {
        return (value, DVec3::ZERO);
    }
    let gradient = DVec3::new(
        dot(&along_y, &dx),
        dot(&column(&along_z, &dy), &wx),
        dot(&column(&along_z_dz, &wy), &wx),
    );
    (value, gradient)
}

impl BatchField for SplitField<'_> {
    fn values(&mut self, points: &[DVec3]) -> Vec<f64> {
        self.batch::<false>(points)
            .into_iter()
            .map(|(s, _)| s)
            .collect()
    }

    fn value_gradients(&mut self, points: &[DVec3]) -> Vec<(f64, DVec3)> {
        self.batch::<true>(points)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lagrange_weights_reproduce_quintics() {
        for u in [0.0, 0.3, 0.77] {
            let (w, d) = lagrange_weights(u);
            let f = |x: f64| 2.0 - x + 0.5 * x * x - 0.25 * x.powi(3) + 0.1 * x.powi(5);
            let df = |x: f64| -1.0 + x - 0.75 * x * x + 0.5 * x.powi(4);
            let nodes = [-2.0, -1.0, 0.0, 1.0, 2.0, 3.0].map(f);
            assert!((dot(&w, &nodes) - f(u)).abs() < 1e-14);
            assert!((dot(&d, &nodes) - df(u)).abs() < 1e-13);
        }
    }
}
