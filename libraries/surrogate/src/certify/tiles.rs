//! Tiles of cells with the smallest gap of each. A local correction changes the
//! surface only near the corrected points, so the minima of the other tiles stay
//! valid and only the points of the touched tiles are evaluated again.

/// Bytes of tile minima allowed per point of the cloud (with a floor), so the
/// tiles never cost much memory next to the cloud itself.
const BYTES_PER_POINT: usize = 2;
const MIN_BYTES: usize = 64 * 1024;

/// Tiles are numbered in 16 bits (one number is stored per point).
pub(super) const MAX_TILES: usize = 1 << 16;

/// Square tiles of `2^shift x 2^shift` cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct TileGrid {
    shift: u32,
    cells_s: usize,
    cells_t: usize,
    tiles_s: usize,
    tiles_t: usize,
}

impl TileGrid {
    /// The finest tiling whose minima, one copy per part, fit the budget.
    pub fn new(cells_s: usize, cells_t: usize, points: usize, parts: usize) -> Self {
        let budget = (points * BYTES_PER_POINT).max(MIN_BYTES);
        let mut shift = 0;
        loop {
            let grid = Self::with_shift(cells_s, cells_t, shift);
            let bytes = grid.len() * parts.max(1) * std::mem::size_of::<f64>();
            if (bytes <= budget && grid.len() <= MAX_TILES) || grid.len() == 1 {
                return grid;
            }
            shift += 1;
        }
    }

    fn with_shift(cells_s: usize, cells_t: usize, shift: u32) -> Self {
        let side = 1usize << shift;
        Self {
            shift,
            cells_s,
            cells_t,
            tiles_s: cells_s.div_ceil(side),
            tiles_t: cells_t.div_ceil(side),
        }
    }

    pub fn len(&self) -> usize {
        self.tiles_s * self.tiles_t
    }

    /// Tile of cell `(h, g)`, given as floats (exact small integers): the tile
    /// number as a float, `floor(g / 2^shift) * tiles_s + floor(h / 2^shift)`.
    #[inline(always)]
    pub fn tile(&self, h: f64, g: f64) -> f64 {
        let inverse_side = 1.0 / (1u64 << self.shift) as f64;
        (g * inverse_side).floor() * self.tiles_s as f64 + (h * inverse_side).floor()
    }

    /// Marks the tiles of the cells `h0..=h1 x g0..=g1` (clamped to the grid).
    pub fn mark(&self, marks: &mut [bool], (h0, h1): (usize, usize), (g0, g1): (usize, usize)) {
        let (h1, g1) = (h1.min(self.cells_s - 1), g1.min(self.cells_t - 1));
        for g in (g0 >> self.shift)..=(g1 >> self.shift) {
            for h in (h0 >> self.shift)..=(h1 >> self.shift) {
                marks[g * self.tiles_s + h] = true;
            }
        }
    }
}

/// Lowers `minima[tiles[i]]` to `gaps[i]` where smaller.
#[inline]
pub(super) fn lower_minima(minima: &mut [f64], tiles: &[u32], gaps: &[f64]) {
    for (&tile, &gap) in tiles.iter().zip(gaps) {
        let m = &mut minima[tile as usize];
        // A comparison rather than `min`: one instruction, and a NaN gap is
        // reported as a wrong point anyway.
        *m = if gap < *m { gap } else { *m };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_coarsen_until_the_minima_fit_the_budget() {
        let fine = TileGrid::new(19, 19, 300_000, 8);
        assert_eq!((fine.shift, fine.len()), (0, 361));
        let coarse = TileGrid::new(59, 59, 30_000, 4);
        assert!(coarse.shift >= 1 && coarse.len() * 4 * 8 <= MIN_BYTES);
        assert_eq!(coarse.tile(58.0, 58.0), (coarse.len() - 1) as f64);
        assert_eq!(coarse.tile(3.0, 0.0), (3 >> coarse.shift) as f64);
        let huge = TileGrid::new(1023, 1023, 100_000_000, 1);
        assert!(huge.len() <= MAX_TILES);
    }

    #[test]
    fn marking_covers_the_tiles_of_a_cell_range() {
        let grid = TileGrid::with_shift(10, 6, 1);
        let mut marks = vec![false; grid.len()];
        grid.mark(&mut marks, (3, 4), (0, 9));
        let marked: Vec<usize> = (0..grid.len()).filter(|&i| marks[i]).collect();
        assert_eq!(marked, vec![1, 2, 6, 7, 11, 12]);
    }

    #[test]
    fn minima_take_the_smallest_gap_of_each_tile() {
        let mut minima = vec![f64::INFINITY; 3];
        lower_minima(
            &mut minima,
            &[0, 0, 2, 1, 1, 0],
            &[1.0, 2.0, 3.0, 5.0, 4.0, -1.0],
        );
        assert_eq!(minima, vec![-1.0, 4.0, 3.0]);
    }
}
