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
        Self { cells_s, cells_t, bits: vec![0; cells_s * cells_t] }
    }

    pub fn full(cells_s: usize, cells_t: usize) -> Self {
        Self { cells_s, cells_t, bits: vec![ALL; cells_s * cells_t] }
    }

    /// Cell and local coordinates of parameters `(s, t)` (clamped to the domain).
    #[inline]
    pub fn cell_of(&self, s: f64, t: f64) -> (usize, usize, f64, f64) {
        let (h, u) = crate::spline::knot_interval(s, self.cells_s + 1);
        let (g, v) = crate::spline::knot_interval(t, self.cells_t + 1);
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
        self.bits.iter_mut().zip(&other.bits).for_each(|(a, b)| *a |= b);
    }

    pub fn kept_triangles(&self) -> usize {
        self.bits.iter().map(|b| b.count_ones() as usize).sum()
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
