//! The normal equations `(A^T D A + D_floor + D_ceiling) dx = r` of a step:
//! assembled cell by cell (all rows of a cell share their 16 unknowns) and
//! factored by the banded Cholesky factorisation.

use super::state::State;
use crate::tight::error::LpError;

impl State<'_> {
    /// Assembles and factors `A^T D A + diag(D_floor + D_ceiling)`.
    pub(super) fn assemble(&mut self, d: &[f64]) -> Result<(), LpError> {
        self.normal.clear();
        for cell in &self.lp.cells {
            let block = weighted_gram(
                &self.lp.weights[cell.start..cell.end],
                &d[cell.start..cell.end],
            );
            self.scatter_block(&cell.unknowns, &block);
        }
        let scale = (0..self.n).fold(0.0f64, |m, i| m.max(self.normal.diagonal(i)));
        for i in 0..self.n {
            // A whisper of regularisation keeps unknowns without rows solvable.
            self.normal
                .add(i, i, d[self.m + i] + d[self.m + self.n + i] + 1e-14 * scale);
        }
        self.normal.factor()
    }

    /// Adds the symmetric 16 x 16 `block` (its lower triangle in slot order) at the
    /// cell's unknowns. Slot order and band order may differ (column-major band
    /// order), and clamped slots may share an unknown (then `(a, b)` and `(b, a)`
    /// land on the same entry).
    fn scatter_block(&mut self, unknowns: &[u32; 16], block: &[[f64; 16]; 16]) {
        for a in 0..16 {
            let pa = unknowns[a] as usize;
            self.normal.add(pa, pa, block[a][a]);
            for b in 0..a {
                let pb = unknowns[b] as usize;
                let value = if pa == pb {
                    2.0 * block[a][b]
                } else {
                    block[a][b]
                };
                self.normal.add(pa.max(pb), pa.min(pb), value);
            }
        }
    }
}

/// `sum_i d_i w_i w_i^T` over one cell's rows, two block rows at a time: their
/// 32 accumulators stay in registers across all rows of the cell (the block in
/// memory would cost a load and a store per multiply-add).
fn weighted_gram(weights: &[[f64; 16]], d: &[f64]) -> [[f64; 16]; 16] {
    let mut block = [[0.0; 16]; 16];
    for a in (0..16).step_by(2) {
        let (mut first, mut second) = ([0.0; 16], [0.0; 16]);
        for (w, di) in weights.iter().zip(d) {
            let (x, y) = (di * w[a], di * w[a + 1]);
            for b in 0..16 {
                first[b] = x.mul_add(w[b], first[b]);
                second[b] = y.mul_add(w[b], second[b]);
            }
        }
        block[a] = first;
        block[a + 1] = second;
    }
    block
}
