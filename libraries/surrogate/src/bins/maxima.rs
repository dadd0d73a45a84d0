//! The extreme point of every sub-cell: the candidates of Section 6's reduction
//! (and, at a finer resolution, the check points certification starts from).

use crate::model::Side;

/// Extreme point of each sub-cell: `bs x bt` sub-cells per grid cell, storing the
/// largest signed height `side.sign() * w` and the index of the point that has it.
/// Ties go to the lowest index, so the result does not depend on how the pass was
/// split between threads.
#[derive(Debug, Clone)]
pub struct SubCellMaxima {
    pub side: Side,
    pub cells_s: usize,
    pub cells_t: usize,
    pub bs: usize,
    pub bt: usize,
    pub height: Vec<f64>,
    pub index: Vec<u32>,
}

impl SubCellMaxima {
    pub(crate) fn new(side: Side, cells_s: usize, cells_t: usize, bs: usize, bt: usize) -> Self {
        let len = cells_s * cells_t * bs * bt;
        Self {
            side,
            cells_s,
            cells_t,
            bs,
            bt,
            height: vec![f64::NEG_INFINITY; len],
            index: vec![0; len],
        }
    }

    /// Slot of sub-cell `(qs, qt)` of cell `(h, g)`.
    #[inline]
    pub fn slot(&self, h: usize, g: usize, qs: usize, qt: usize) -> usize {
        ((g * self.cells_s + h) * self.bt + qt) * self.bs + qs
    }

    /// Heights and indices, for the binning pass's updates.
    #[inline]
    pub(crate) fn slots_mut(&mut self) -> (&mut [f64], &mut [u32]) {
        (&mut self.height, &mut self.index)
    }

    pub(crate) fn merge(&mut self, other: &SubCellMaxima) {
        for (i, (&b, &j)) in other.height.iter().zip(&other.index).enumerate() {
            if wins(b, j, self.height[i], self.index[i]) {
                self.height[i] = b;
                self.index[i] = j;
            }
        }
    }

    /// The maxima of `factor x factor` times coarser sub-cells: each is the best of
    /// its children under the same order (height, then lowest index). For a
    /// power-of-two factor this is exactly what a pass at the coarse resolution
    /// keeps: `u * 2 sub` is `u * sub` doubled without rounding, so a point's fine
    /// sub-cell lies inside its coarse one.
    pub fn coarsen(&self, factor: usize) -> SubCellMaxima {
        let factor = factor.max(1);
        let (bs, bt) = ((self.bs / factor).max(1), (self.bt / factor).max(1));
        let mut out = SubCellMaxima::new(self.side, self.cells_s, self.cells_t, bs, bt);
        // Coarse sub-cell q has the fine children q * factor .. (q + 1) * factor,
        // the last one also any remainder: `owner` maps a fine index to its parent.
        let owner = |q: usize, coarse: usize| (q / factor).min(coarse - 1);
        let (fine_cell, coarse_cell) = (self.bs * self.bt, bs * bt);
        let cells = self
            .height
            .chunks_exact(fine_cell)
            .zip(self.index.chunks_exact(fine_cell));
        let targets = out
            .height
            .chunks_exact_mut(coarse_cell)
            .zip(out.index.chunks_exact_mut(coarse_cell));
        let column_owner: Vec<usize> = (0..self.bs).map(|qs| owner(qs, bs)).collect();
        for ((height, index), (best_height, best_index)) in cells.zip(targets) {
            let rows = height
                .chunks_exact(self.bs)
                .zip(index.chunks_exact(self.bs));
            for (qt, (heights, indices)) in rows.enumerate() {
                let first = owner(qt, bt) * bs;
                for ((&h, &i), &column) in heights.iter().zip(indices).zip(&column_owner) {
                    let to = first + column;
                    if wins(h, i, best_height[to], best_index[to]) {
                        (best_height[to], best_index[to]) = (h, i);
                    }
                }
            }
        }
        out
    }

    /// Occupied slots: `(slot, height, point index)`.
    pub fn occupied(&self) -> impl Iterator<Item = (usize, f64, u32)> + '_ {
        (0..self.height.len())
            .filter(|&i| self.height[i] > f64::NEG_INFINITY)
            .map(|i| (i, self.height[i], self.index[i]))
    }
}

/// Whether point `(height, index)` beats the kept `(kept_height, kept_index)`.
#[inline]
fn wins(height: f64, index: u32, kept_height: f64, kept_index: u32) -> bool {
    height > kept_height
        || (height == kept_height && height > f64::NEG_INFINITY && index < kept_index)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarsening_keeps_the_best_child_and_the_lowest_index_on_ties() {
        let mut fine = SubCellMaxima::new(Side::Upper, 2, 1, 4, 4);
        for (h, qs, qt, height, index) in [
            (0, 0, 0, 1.0, 7),
            (0, 1, 1, 1.0, 3),
            (0, 2, 0, 0.5, 1),
            (1, 3, 3, -2.0, 9),
        ] {
            let slot = fine.slot(h, 0, qs, qt);
            (fine.height[slot], fine.index[slot]) = (height, index);
        }
        let coarse = fine.coarsen(2);
        assert_eq!((coarse.bs, coarse.bt), (2, 2));
        let at = |h, qs, qt| {
            let slot = coarse.slot(h, 0, qs, qt);
            (coarse.height[slot], coarse.index[slot])
        };
        assert_eq!(at(0, 0, 0), (1.0, 3));
        assert_eq!(at(0, 1, 0), (0.5, 1));
        assert_eq!(at(1, 1, 1), (-2.0, 9));
        assert_eq!(coarse.occupied().count(), 3);
    }

    #[test]
    fn merging_is_independent_of_the_order() {
        let mut a = SubCellMaxima::new(Side::Upper, 1, 1, 1, 2);
        let mut b = a.clone();
        (a.height[0], a.index[0]) = (2.0, 5);
        (b.height[0], b.index[0]) = (2.0, 4);
        (b.height[1], b.index[1]) = (1.0, 8);
        let (mut ab, mut ba) = (a.clone(), b.clone());
        ab.merge(&b);
        ba.merge(&a);
        assert_eq!((ab.height.clone(), ab.index.clone()), (ba.height, ba.index));
        assert_eq!(ab.index, vec![4, 8]);
    }
}
