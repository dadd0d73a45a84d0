//! A small banded linear solver with partial pivoting, for the pentadiagonal
//! systems (7) and (4) of the heuristics.
//!
//! Hand-written on purpose: these systems have `n <= ~100` unknowns and two bands
//! on each side, are solved millions of times per second in the fitting hot path,
//! and a general sparse or dense solver costs more in setup than the solve itself.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum BandedSolveError {
    #[error("the banded system is singular at row {0}")]
    Singular(usize),
}

/// Square matrix with `KL` sub- and `KU` super-diagonals stored row-wise; pivoting
/// widens the upper band by `KL`, which the storage reserves.
#[derive(Debug, Clone)]
pub struct BandedMatrix<const KL: usize, const KU: usize> {
    n: usize,
    width: usize,
    /// Row `i` stores columns `i - KL ..= i + KU + KL` at offsets `0 ..= width-1`.
    data: Vec<f64>,
}

impl<const KL: usize, const KU: usize> BandedMatrix<KL, KU> {
    pub fn zeros(n: usize) -> Self {
        let width = 2 * KL + KU + 1;
        Self {
            n,
            width,
            data: vec![0.0; n * width],
        }
    }

    pub fn n(&self) -> usize {
        self.n
    }

    /// Clears the matrix for reuse without reallocating.
    pub fn clear(&mut self) {
        self.data.iter_mut().for_each(|x| *x = 0.0);
    }

    /// Adds `value` at `(row, col)`; `col` must lie within the band.
    #[inline]
    pub fn add(&mut self, row: usize, col: usize, value: f64) {
        debug_assert!(col + KL >= row && col <= row + KU);
        let off = col + KL - row;
        self.data[row * self.width + off] += value;
    }

    /// Solves `A x = rhs` in place (`rhs` becomes `x`); `A` is destroyed.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), BandedSolveError> {
        let n = self.n;
        let scale = self.data.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let tiny = scale * 1e-13 + f64::MIN_POSITIVE;
        for k in 0..n {
            let last_row = (k + KL).min(n - 1);
            let piv = (k..=last_row)
                .max_by(|&a, &b| self.at(a, k).abs().total_cmp(&self.at(b, k).abs()))
                .unwrap_or(k);
            if self.at(piv, k).abs() <= tiny {
                return Err(BandedSolveError::Singular(k));
            }
            let last_col = (k + KU + KL).min(n - 1);
            if piv != k {
                for c in k..=last_col {
                    let (a, b) = (self.at(k, c), self.at(piv, c));
                    self.set(k, c, b);
                    self.set(piv, c, a);
                }
                rhs.swap(k, piv);
            }
            let p = self.at(k, k);
            for r in k + 1..=last_row {
                let f = self.at(r, k) / p;
                if f != 0.0 {
                    for c in k..=last_col {
                        let v = self.at(r, c) - f * self.at(k, c);
                        self.set(r, c, v);
                    }
                    rhs[r] -= f * rhs[k];
                }
            }
        }
        for k in (0..n).rev() {
            let last_col = (k + KU + KL).min(n - 1);
            let tail: f64 = (k + 1..=last_col)
                .zip(&rhs[k + 1..=last_col])
                .map(|(c, x)| self.at(k, c) * x)
                .sum();
            rhs[k] = (rhs[k] - tail) / self.at(k, k);
        }
        Ok(())
    }

    #[inline]
    fn at(&self, row: usize, col: usize) -> f64 {
        if col + KL < row || col > row + KU + KL {
            return 0.0;
        }
        self.data[row * self.width + col + KL - row]
    }

    #[inline]
    fn set(&mut self, row: usize, col: usize, value: f64) {
        let off = col + KL - row;
        self.data[row * self.width + off] = value;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_pentadiagonal_with_pivoting() {
        let n = 7;
        let mut dense = vec![vec![0.0; n]; n];
        let mut a = BandedMatrix::<2, 2>::zeros(n);
        for (i, row) in dense.iter_mut().enumerate() {
            for (j, entry) in row
                .iter_mut()
                .enumerate()
                .take((i + 3).min(n))
                .skip(i.saturating_sub(2))
            {
                // A zero diagonal forces pivoting.
                let v = if i == j {
                    if i == 2 {
                        0.0
                    } else {
                        1.0
                    }
                } else {
                    ((i * 3 + j) % 5) as f64 - 1.5
                };
                *entry = v;
                a.add(i, j, v);
            }
        }
        let x: Vec<f64> = (0..n).map(|i| i as f64 - 2.5).collect();
        let mut rhs: Vec<f64> = dense
            .iter()
            .map(|r| r.iter().zip(&x).map(|(p, q)| p * q).sum())
            .collect();
        a.solve_in_place(&mut rhs).unwrap();
        for (p, q) in rhs.iter().zip(&x) {
            assert!((p - q).abs() < 1e-9, "{rhs:?}");
        }
    }

    #[test]
    fn reports_singular() {
        let mut a = BandedMatrix::<2, 2>::zeros(3);
        a.add(0, 0, 1.0);
        a.add(1, 0, 1.0);
        let mut rhs = vec![1.0, 1.0, 1.0];
        assert!(a.solve_in_place(&mut rhs).is_err());
    }
}
