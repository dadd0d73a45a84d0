//! The floor a fit's time is measured against (issue 27): the least work any
//! fit of a cloud must do, one look at every point and one number kept per
//! cell, with nothing certified.
//!
//! One thread, two plain loops over the points: the bounding box of their
//! `(x, y)`, then every point binned into a `grid x grid` grid of cells, each
//! cell keeping its largest `z` (f32, no allocation besides the grid). For a
//! fit of `n x n` control points the benchmarks give the floor `n` cells a
//! side (the fit has `n - 1`: the floor does a hair more work). Shared by
//! `shroud-bench surrogate` and the `fit_floor` example, so that both time
//! the same loops.

/// The floor's grid of cell maxima, kept between runs so that a run
/// allocates nothing.
#[derive(Debug, Clone)]
pub struct Floor {
    grid: usize,
    cells: Vec<f32>,
    /// The last run's bounding box of the points' `(x, y)`: lower, upper.
    bounds: [[f32; 2]; 2],
}

impl Floor {
    /// A floor of `grid x grid` cells (`grid >= 1`).
    pub fn new(grid: usize) -> Self {
        assert!(grid >= 1, "the floor needs at least one cell");
        Self {
            grid,
            cells: vec![f32::NEG_INFINITY; grid * grid],
            bounds: [[f32::INFINITY; 2], [f32::NEG_INFINITY; 2]],
        }
    }

    /// Cells along a side.
    pub fn grid(&self) -> usize {
        self.grid
    }

    /// The last run's cell maxima (see [`Self::cell_maxima`]).
    pub fn cells(&self) -> &[f32] {
        &self.cells
    }

    /// The last run's bounding box of the points' `(x, y)`, `[lower, upper]`
    /// (empty, lower above upper, before the first run or after an empty
    /// cloud); cell `(i, j)` spans `lower + (i, j) * (upper - lower) / grid`
    /// to the next.
    pub fn bounds(&self) -> [[f32; 2]; 2] {
        self.bounds
    }

    /// One run: the bounding box of the points' `(x, y)`, then each cell's
    /// largest `z`, row by row (cell `(i, j)` at `j * grid + i`; an empty
    /// cell keeps negative infinity). Points on the box's far edges fall in
    /// the last cells.
    pub fn cell_maxima(&mut self, points: &[[f32; 3]]) -> &[f32] {
        let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
        for &[x, y, _] in points {
            (lo[0], hi[0]) = (lo[0].min(x), hi[0].max(x));
            (lo[1], hi[1]) = (lo[1].min(y), hi[1].max(y));
        }
        self.bounds = [lo, hi];
        let grid = self.grid;
        let scale = [0, 1].map(|k| grid as f32 / (hi[k] - lo[k]));
        self.cells.fill(f32::NEG_INFINITY);
        let last = grid - 1;
        for p in points {
            let i = (((p[0] - lo[0]) * scale[0]) as usize).min(last);
            let j = (((p[1] - lo[1]) * scale[1]) as usize).min(last);
            let cell = &mut self.cells[j * grid + i];
            *cell = cell.max(p[2]);
        }
        &self.cells
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_each_cells_largest_height() {
        // A 4 x 4 lattice on [0, 3]^2 binned into 2 x 2 cells, and the
        // heights 10 i + j: each cell's largest is at its far corner.
        let points: Vec<[f32; 3]> = (0..4)
            .flat_map(|i| (0..4).map(move |j| [i as f32, j as f32, (10 * i + j) as f32]))
            .collect();
        let mut floor = Floor::new(2);
        assert_eq!(floor.cell_maxima(&points), &[11.0, 31.0, 13.0, 33.0]);
        assert_eq!(floor.cells(), &[11.0, 31.0, 13.0, 33.0]);
        assert_eq!(floor.bounds(), [[0.0, 0.0], [3.0, 3.0]]);
        // Reused: the previous run's maxima do not leak into the next.
        assert_eq!(
            floor.cell_maxima(&points[..1]),
            &[0.0, f32::NEG_INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY]
        );
    }

    #[test]
    fn a_cloud_without_extent_lands_in_one_cell() {
        let mut floor = Floor::new(3);
        let maxima = floor
            .cell_maxima(&[[1.0, 2.0, 5.0], [1.0, 2.0, 7.0]])
            .to_vec();
        assert_eq!(maxima[0], 7.0);
        assert!(maxima[1..].iter().all(|m| *m == f32::NEG_INFINITY));
    }
}
