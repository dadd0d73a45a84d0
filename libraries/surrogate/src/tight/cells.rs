//! The coefficients acting on one grid cell: the indexing shared by the LP's
//! rows, its bounds and the excess measure.

use super::objective::clamp_index;

/// The coefficient indices (`k * cols + j`) acting on cell `(h, g)`, `[r * 4 + q]`.
pub fn cell_slots(h: usize, g: usize, cols: usize, rows: usize) -> [usize; 16] {
    let mut slots = [0; 16];
    for r in 0..4 {
        for q in 0..4 {
            slots[r * 4 + q] = clamp_index(g + r, rows) * cols + clamp_index(h + q, cols);
        }
    }
    slots
}
