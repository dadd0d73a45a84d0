//! Trimming (Section 6, Figures 7 and 8): grid cells, split by both diagonals into
//! four triangles, are kept only where data fell, so trim lines run along cell
//! edges and diagonals and the tensor-product footprint does not alias.

use serde::{Deserialize, Serialize};

/// One bit per triangle of each cell: bottom (near `t = g`), right, top, left.
pub const BOTTOM: u8 = 1;
pub const RIGHT: u8 = 2;
pub const TOP: u8 = 4;
pub const LEFT: u8 = 8;
pub const ALL: u8 = BOTTOM | RIGHT | TOP | LEFT;

/// The kept region of the parameter domain.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct TrimMask {
    /// Cells along s (`cols - 1`) and along t (`rows - 1`).
    pub cells_s: usize,
    pub cells_t: usize,
    /// Row-major `[g * cells_s + h]` triangle bits.
    pub bits: Vec<u8>,
}

/// Triangle bit of local cell coordinates `(u, v)` in `[0, 1]^2`.
#[inline]
pub fn triangle_of(u: f64, v: f64) -> u8 {
    let below_main = v < u; // below the diagonal from (0,0) to (1,1)
    let below_anti = u + v < 1.0; // below the diagonal from (0,1) to (1,0)
                                  // Branch-free (this runs once per point): bottom, right, top, left = 0..3.
    let index = 2 * u8::from(!below_main) + u8::from(below_main ^ below_anti);
    1 << index
}

impl TrimMask {
    pub fn empty(cells_s: usize, cells_t: usize) -> Self {
        Self {
            cells_s,
            cells_t,
            bits: vec![0; cells_s * cells_t],
        }
    }

    pub fn full(cells_s: usize, cells_t: usize) -> Self {
        Self {
            cells_s,
            cells_t,
            bits: vec![ALL; cells_s * cells_t],
        }
    }

    /// Cell and local coordinates of parameters `(s, t)` (clamped to the domain).
    #[inline]
    pub fn cell_of(&self, s: f64, t: f64) -> (usize, usize, f64, f64) {
        let (h, u) = shroud_geometry::spline::knot_interval(s, self.cells_s + 1);
        let (g, v) = shroud_geometry::spline::knot_interval(t, self.cells_t + 1);
        (h, g, u, v)
    }

    #[inline]
    pub fn mark(&mut self, s: f64, t: f64) {
        let (h, g, u, v) = self.cell_of(s, t);
        self.bits[g * self.cells_s + h] |= triangle_of(u, v);
    }

    /// Whether `(s, t)` (assumed inside the domain) lies in a kept triangle. Points
    /// exactly on a diagonal count for both triangles that share it.
    pub fn contains(&self, s: f64, t: f64) -> bool {
        let (h, g, u, v) = self.cell_of(s, t);
        let bits = self.bits[g * self.cells_s + h];
        let mut want = triangle_of(u, v);
        if u == v || u + v == 1.0 {
            want |= triangle_of(u + 1e-12, v) | triangle_of(u - 1e-12, v);
        }
        bits & want != 0
    }

    pub fn cell_bits(&self, h: usize, g: usize) -> u8 {
        self.bits[g * self.cells_s + h]
    }

    pub fn cell_kept(&self, h: usize, g: usize) -> bool {
        self.cell_bits(h, g) != 0
    }

    /// Bitwise union (used to merge per-thread masks).
    pub fn merge(&mut self, other: &TrimMask) {
        self.bits
            .iter_mut()
            .zip(&other.bits)
            .for_each(|(a, b)| *a |= b);
    }

    pub fn kept_triangles(&self) -> usize {
        self.bits.iter().map(|b| b.count_ones() as usize).sum()
    }

    /// Keeps the empty triangles of every small enclosed hole (a connected empty
    /// region of at most `max_triangles` that does not reach the domain border).
    /// The paper trims the *outer* boundary (Figures 7, 8); a sparse cloud leaves
    /// pinholes inside the data that are sampling gaps, not shape.
    pub fn fill_small_holes(&mut self, max_triangles: usize) {
        let n = self.bits.len() * 4;
        let mut seen = vec![false; n];
        let mut stack = Vec::new();
        let mut component = Vec::new();
        for start in 0..n {
            if seen[start] || self.is_kept(start) {
                continue;
            }
            component.clear();
            let mut touches_border = false;
            seen[start] = true;
            stack.push(start);
            while let Some(tri) = stack.pop() {
                component.push(tri);
                let (neighbours, on_border) = self.neighbours(tri);
                touches_border |= on_border;
                for next in neighbours.into_iter().flatten() {
                    if !seen[next] && !self.is_kept(next) {
                        seen[next] = true;
                        stack.push(next);
                    }
                }
            }
            if !touches_border && component.len() <= max_triangles {
                for &tri in &component {
                    self.bits[tri / 4] |= 1 << (tri % 4);
                }
            }
        }
    }

    /// Triangle ids are `cell * 4 + k` with `k` = bottom, right, top, left.
    fn is_kept(&self, tri: usize) -> bool {
        self.bits[tri / 4] & (1 << (tri % 4)) != 0
    }

    /// The three edge neighbours of a triangle, and whether one edge is the border.
    fn neighbours(&self, tri: usize) -> ([Option<usize>; 3], bool) {
        let (cell, k) = (tri / 4, tri % 4);
        let (h, g) = (cell % self.cells_s, cell / self.cells_s);
        let id = |h: usize, g: usize, k: usize| (g * self.cells_s + h) * 4 + k;
        // Inside the cell each triangle touches the two next to it around the centre.
        let inside = [Some(cell * 4 + (k + 1) % 4), Some(cell * 4 + (k + 3) % 4)];
        let across = match k {
            0 => g.checked_sub(1).map(|g| id(h, g, 2)),
            1 => (h + 1 < self.cells_s).then(|| id(h + 1, g, 3)),
            2 => (g + 1 < self.cells_t).then(|| id(h, g + 1, 0)),
            _ => h.checked_sub(1).map(|h| id(h, g, 1)),
        };
        ([inside[0], inside[1], across], across.is_none())
    }

    /// Kept area in parameter units (each triangle is a quarter cell).
    pub fn kept_area(&self) -> f64 {
        self.kept_triangles() as f64 * 0.25
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangles_partition_the_cell() {
        assert_eq!(triangle_of(0.5, 0.1), BOTTOM);
        assert_eq!(triangle_of(0.9, 0.5), RIGHT);
        assert_eq!(triangle_of(0.5, 0.9), TOP);
        assert_eq!(triangle_of(0.1, 0.5), LEFT);
    }

    #[test]
    fn small_enclosed_holes_are_filled_and_outer_gaps_stay_trimmed() {
        let mut m = TrimMask::full(5, 5);
        // A one-triangle pinhole in the middle, and an empty border cell.
        m.bits[2 * 5 + 2] &= !TOP;
        m.bits[0] = 0;
        // A large enclosed hole: the whole 3x3 centre block is empty.
        let mut big = TrimMask::full(5, 5);
        for g in 1..4 {
            for h in 1..4 {
                big.bits[g * 5 + h] = 0;
            }
        }
        m.fill_small_holes(8);
        big.fill_small_holes(8);
        assert_eq!(m.bits[2 * 5 + 2], ALL);
        assert_eq!(m.bits[0], 0);
        assert_eq!(big.kept_triangles(), 4 * (25 - 9));
    }

    #[test]
    fn marks_are_contained() {
        let mut m = TrimMask::empty(3, 2);
        m.mark(1.5, 0.1);
        assert!(m.contains(1.5, 0.1));
        assert!(m.contains(1.5, 0.2));
        assert!(!m.contains(1.5, 0.9));
        assert!(!m.contains(0.5, 0.5));
        assert_eq!(m.kept_triangles(), 1);
        m.mark(3.0, 2.0);
        assert!(m.contains(3.0, 2.0));
    }
}
