//! A symmetric positive definite banded matrix and its in-place Cholesky
//! factorisation, for the normal equations `A^T D A dx = r` of the interior-point
//! method.
//!
//! Hand-written: the matrix is small (`cols * rows` unknowns) with half-bandwidth
//! about `3 min(cols, rows) + 3`, so the band factorisation (`n bw^2 / 2` flops)
//! is far cheaper than a dense one and needs no sparse-matrix machinery.

use super::error::LpError;

/// Lower band of a symmetric matrix: row `i` stores columns `i - bw ..= i` at
/// offsets `0 ..= bw` (columns before 0 are padding), so the dot products of the
/// factorisation run over contiguous memory.
#[derive(Debug, Clone)]
pub struct BandedSpd {
    n: usize,
    bw: usize,
    data: Vec<f64>,
}

/// Pivots below this fraction of their original diagonal are treated as zero: the
/// unknown is frozen for this step (the standard remedy for normal equations that
/// become singular near an LP optimum; Wright, Primal-Dual Interior-Point
/// Methods, Ch. 11).
const PIVOT_TOLERANCE: f64 = 1e-30;
/// Stand-in for a dropped pivot: large enough that the unknown does not move.
const FROZEN_PIVOT: f64 = 1e64;

impl BandedSpd {
    pub fn zeros(n: usize, bw: usize) -> Self {
        let bw = bw.min(n.saturating_sub(1));
        Self {
            n,
            bw,
            data: vec![0.0; n * (bw + 1)],
        }
    }

    pub fn n(&self) -> usize {
        self.n
    }

    pub fn bandwidth(&self) -> usize {
        self.bw
    }

    pub fn clear(&mut self) {
        self.data.iter_mut().for_each(|x| *x = 0.0);
    }

    /// Adds `value` at `(row, col)` of the lower triangle (`col <= row <= col + bw`).
    #[inline]
    pub fn add(&mut self, row: usize, col: usize, value: f64) {
        debug_assert!(col <= row && row <= col + self.bw);
        self.data[row * (self.bw + 1) + col + self.bw - row] += value;
    }

    #[inline]
    pub fn diagonal(&self, i: usize) -> f64 {
        self.data[i * (self.bw + 1) + self.bw]
    }

    /// Overwrites the matrix with its Cholesky factor `L` (`A = L L^T`), row by row
    /// (Cholesky-Banachiewicz). Entries of a row are computed four at a time: the
    /// four dot products share their stretch of row `i` (one load feeds four
    /// multiply-adds), and only the small triangle inside the block is sequential.
    /// Near-zero pivots are frozen (see `PIVOT_TOLERANCE`); a clearly negative one
    /// means the matrix is not positive semi-definite.
    pub fn factor(&mut self) -> Result<(), LpError> {
        let (n, bw, stride) = (self.n, self.bw, self.bw + 1);
        // Offset of column 0 of row r: entry (r, k) is data[base(r) + k].
        let base = |r: usize| r * stride + bw - r;
        // Reciprocal pivots: a multiply instead of a divide on the sequential path.
        let mut inverse = vec![0.0; n];
        for i in 0..n {
            let (first, ri) = (i.saturating_sub(bw), base(i));
            let mut j = first;
            while j <= i {
                let block = (i + 1 - j).min(4);
                let rows = [0, 1, 2, 3].map(|b| base(j + b.min(block - 1)));
                let mut sums = dot4(&self.data, ri, rows, first, j);
                for b in 0..block {
                    let (jj, rj) = (j + b, rows[b]);
                    for k in j..jj {
                        sums[b] = self.data[ri + k].mul_add(self.data[rj + k], sums[b]);
                    }
                    let value = self.data[ri + jj] - sums[b];
                    self.data[ri + jj] = if jj < i {
                        value * inverse[jj]
                    } else {
                        let pivot = self.pivot(i, value)?;
                        inverse[i] = 1.0 / pivot;
                        pivot
                    };
                }
                j += block;
            }
        }
        Ok(())
    }

    /// The diagonal entry of `L` from the remaining value of `A_ii`.
    fn pivot(&self, i: usize, value: f64) -> Result<f64, LpError> {
        let original = self.diagonal(i);
        if value > PIVOT_TOLERANCE * original.abs().max(f64::MIN_POSITIVE) {
            Ok(value.sqrt())
        } else if value >= -1e-8 * original.abs() {
            Ok(FROZEN_PIVOT)
        } else {
            Err(LpError::NotPositiveDefinite(i))
        }
    }

    /// Solves `L L^T x = rhs` in place with the factor from [`Self::factor`].
    pub fn solve_in_place(&self, rhs: &mut [f64]) {
        let (n, bw, stride) = (self.n, self.bw, self.bw + 1);
        for i in 0..n {
            let first = i.saturating_sub(bw);
            let ri = i * stride + bw - i;
            let acc = dot(&self.data[ri + first..ri + i], &rhs[first..i]);
            rhs[i] = (rhs[i] - acc) / self.data[ri + i];
        }
        for i in (0..n).rev() {
            let ri = i * stride + bw - i;
            rhs[i] /= self.data[ri + i];
            let xi = rhs[i];
            let first = i.saturating_sub(bw);
            for (r, l) in rhs[first..i].iter_mut().zip(&self.data[ri + first..ri + i]) {
                *r -= l * xi;
            }
        }
    }
}

/// Dot product with four independent accumulators (lets the compiler vectorise).
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] = x[k].mul_add(y[k], acc[k]);
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// Four dot products of `data[x + k]` with `data[y[b] + k]` over `k in from..to`.
#[inline]
fn dot4(data: &[f64], x: usize, y: [usize; 4], from: usize, to: usize) -> [f64; 4] {
    let len = to.saturating_sub(from);
    let xs = &data[x + from..x + from + len];
    let [y0, y1, y2, y3] = y.map(|r| &data[r + from..r + from + len]);
    let (mut a0, mut a1, mut a2, mut a3) = ([0.0; 4], [0.0; 4], [0.0; 4], [0.0; 4]);
    let chunks = xs
        .chunks_exact(4)
        .zip(y0.chunks_exact(4))
        .zip(y1.chunks_exact(4))
        .zip(y2.chunks_exact(4));
    for ((((xc, a), b), c), d) in chunks.zip(y3.chunks_exact(4)) {
        for l in 0..4 {
            a0[l] = xc[l].mul_add(a[l], a0[l]);
            a1[l] = xc[l].mul_add(b[l], a1[l]);
            a2[l] = xc[l].mul_add(c[l], a2[l]);
            a3[l] = xc[l].mul_add(d[l], a3[l]);
        }
    }
    let acc = [a0, a1, a2, a3];
    let mut out = acc.map(|a| (a[0] + a[1]) + (a[2] + a[3]));
    for k in len / 4 * 4..len {
        for (o, yb) in out.iter_mut().zip([y0, y1, y2, y3]) {
            *o = xs[k].mul_add(yb[k], *o);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random-looking SPD band matrix `B B^T + I` with `B` lower banded.
    fn dense_spd(n: usize, bw: usize) -> Vec<Vec<f64>> {
        let b: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        if j <= i && i - j <= bw / 2 {
                            ((i * 7 + j * 3) % 5) as f64 - 1.7
                        } else {
                            0.0
                        }
                    })
                    .collect()
            })
            .collect();
        (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        (0..n).map(|k| b[i][k] * b[j][k]).sum::<f64>()
                            + if i == j { 1.0 } else { 0.0 }
                    })
                    .collect()
            })
            .collect()
    }

    #[test]
    fn solves_a_banded_spd_system() {
        let (n, bw) = (30, 6);
        let dense = dense_spd(n, bw);
        let mut band = BandedSpd::zeros(n, bw);
        for (i, row) in dense.iter().enumerate() {
            for (j, &value) in row
                .iter()
                .enumerate()
                .take(i + 1)
                .skip(i.saturating_sub(bw))
            {
                band.add(i, j, value);
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).sin()).collect();
        let mut rhs: Vec<f64> = dense
            .iter()
            .map(|r| r.iter().zip(&x).map(|(a, b)| a * b).sum())
            .collect();
        band.factor().unwrap();
        band.solve_in_place(&mut rhs);
        rhs.iter()
            .zip(&x)
            .for_each(|(a, b)| assert!((a - b).abs() < 1e-10, "{a} vs {b}"));
    }

    #[test]
    fn freezes_a_zero_pivot_and_rejects_an_indefinite_matrix() {
        let mut band = BandedSpd::zeros(3, 1);
        band.add(0, 0, 2.0);
        band.add(2, 2, 4.0);
        band.factor().unwrap();
        let mut rhs = vec![2.0, 5.0, 8.0];
        band.solve_in_place(&mut rhs);
        assert!(
            (rhs[0] - 1.0).abs() < 1e-12 && rhs[1].abs() < 1e-50 && (rhs[2] - 2.0).abs() < 1e-12
        );
        let mut bad = BandedSpd::zeros(2, 1);
        bad.add(0, 0, 1.0);
        bad.add(1, 0, 2.0);
        bad.add(1, 1, 1.0);
        assert!(bad.factor().is_err());
    }
}
