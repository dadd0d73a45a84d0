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
    ///
    /// Gaussian elimination with partial pivoting (of equally large
    /// candidates, the one furthest down), then back-substitution, both on
    /// the band storage directly: step `k` works on row slices that start at
    /// column `k`, where row `k + d` keeps column `k` at offset `KL - d`.
    /// Every entry the loops touch lies in the band, so none is tested; the
    /// pivot column's entries below the pivot are never written (nothing
    /// reads them again). Panics if `rhs` has fewer than `n` entries.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), BandedSolveError> {
        let n = self.n;
        let rhs = &mut rhs[..n];
        let scale = self.data.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let tiny = scale * 1e-13 + f64::MIN_POSITIVE;
        // Away from the last rows every step spans the whole band: the same
        // step with its sizes known at compile time, so that the loops unroll.
        let full = KU + KL;
        for k in 0..n {
            let rest = n - 1 - k;
            if rest >= full {
                self.eliminate(k, KL, full + 1, rhs, tiny)?;
            } else {
                self.eliminate(k, KL.min(rest), rest + 1, rhs, tiny)?;
            }
        }
        for k in (0..n).rev() {
            let rest = n - 1 - k;
            if rest >= full {
                self.substitute(k, full + 1, rhs);
            } else {
                self.substitute(k, rest + 1, rhs);
            }
        }
        Ok(())
    }

    /// Elimination step `k`: rows `k + 1 ..= k + below` have an entry in
    /// column `k`, and the rows taking part reach columns `k .. k + len`.
    #[inline(always)]
    fn eliminate(
        &mut self,
        k: usize,
        below: usize,
        len: usize,
        rhs: &mut [f64],
        tiny: f64,
    ) -> Result<(), BandedSolveError> {
        let w = self.width;
        let column = |d: usize| self.data[(k + d) * w + KL - d].abs();
        let (mut piv, mut largest) = (0, column(0));
        for d in 1..below + 1 {
            let v = column(d);
            if largest.total_cmp(&v).is_le() {
                (piv, largest) = (d, v);
            }
        }
        if largest <= tiny {
            return Err(BandedSolveError::Singular(k));
        }
        let (upper, lower) = self.data.split_at_mut((k + 1) * w);
        let row_k = &mut upper[k * w + KL..][..len];
        let row_below = |d: usize| (d - 1) * w + KL - d;
        if piv != 0 {
            let start = row_below(piv);
            row_k.swap_with_slice(&mut lower[start..start + len]);
            rhs.swap(k, k + piv);
        }
        let (p, x_k) = (row_k[0], rhs[k]);
        for d in 1..below + 1 {
            let start = row_below(d);
            let row = &mut lower[start..start + len];
            let f = row[0] / p;
            if f != 0.0 {
                for (a, b) in row[1..].iter_mut().zip(&row_k[1..]) {
                    *a -= f * b;
                }
                rhs[k + d] -= f * x_k;
            }
        }
        Ok(())
    }

    /// Back-substitution of row `k`, whose entries reach columns `k .. k + len`.
    #[inline(always)]
    fn substitute(&self, k: usize, len: usize, rhs: &mut [f64]) {
        let row = &self.data[k * self.width + KL..][..len];
        let tail: f64 = row[1..]
            .iter()
            .zip(&rhs[k + 1..k + len])
            .map(|(a, x)| a * x)
            .sum();
        rhs[k] = (rhs[k] - tail) / row[0];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::collection::vec;
    use proptest::prelude::*;

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

    /// Gaussian elimination with partial pivoting on the full matrix (every
    /// column, every row below the pivot), then back-substitution: the
    /// reference the banded solver must agree with. Outside the band its
    /// entries stay zero, so it picks the same pivots and does the banded
    /// solver's arithmetic plus terms that are zero.
    fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
        let n = b.len();
        for k in 0..n {
            let piv = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
            if a[piv][k] == 0.0 {
                return None;
            }
            a.swap(k, piv);
            b.swap(k, piv);
            let (top, rows_below) = a.split_at_mut(k + 1);
            let pivot_row = &top[k];
            for (d, row) in rows_below.iter_mut().enumerate() {
                let f = row[k] / pivot_row[k];
                for (x, p) in row[k..].iter_mut().zip(&pivot_row[k..]) {
                    *x -= f * p;
                }
                b[k + 1 + d] -= f * b[k];
            }
        }
        for k in (0..n).rev() {
            let tail: f64 = (k + 1..n).map(|c| a[k][c] * b[c]).sum();
            b[k] = (b[k] - tail) / a[k][k];
        }
        Some(b)
    }

    /// The 1-norm condition number of `a`, its inverse taken column by
    /// column with [`dense_solve`].
    fn condition(a: &[Vec<f64>]) -> Option<f64> {
        let n = a.len();
        let norm = |m: &dyn Fn(usize, usize) -> f64| {
            (0..n)
                .map(|c| (0..n).map(|r| m(r, c).abs()).sum::<f64>())
                .fold(0.0, f64::max)
        };
        let mut inverse = Vec::with_capacity(n);
        for c in 0..n {
            let unit = (0..n).map(|r| f64::from(u8::from(r == c))).collect();
            inverse.push(dense_solve(a.to_vec(), unit)?);
        }
        Some(norm(&|r, c| a[r][c]) * norm(&|r, c| inverse[c][r]))
    }

    /// A random band (`KL` below, `KU` above the diagonal) from `entries`
    /// in `[-1, 1]`, the diagonal raised by `lift` (small lifts leave rows
    /// whose largest entry is off the diagonal, so the solver pivots); `x`
    /// is the solution. Systems worse conditioned than 1e6 are skipped. The
    /// banded solver must give the dense one's solution exactly (the terms
    /// the dense one adds are zeros), and that within rounding of `x`.
    fn agrees_with_dense<const KL: usize, const KU: usize>(
        entries: &[f64],
        lift: f64,
        x: &[f64],
    ) -> Result<(), TestCaseError> {
        let n = x.len();
        let mut dense = vec![vec![0.0; n]; n];
        let mut band = BandedMatrix::<KL, KU>::zeros(n);
        let mut entries = entries.iter();
        for (i, row) in dense.iter_mut().enumerate() {
            for (j, entry) in row
                .iter_mut()
                .enumerate()
                .take(i + KU + 1)
                .skip(i.saturating_sub(KL))
            {
                let v = entries.next().copied().unwrap_or(0.0) + if i == j { lift } else { 0.0 };
                *entry = v;
                band.add(i, j, v);
            }
        }
        let cond = condition(&dense);
        prop_assume!(cond.is_some_and(|c| c < 1e6));
        let rhs: Vec<f64> = dense
            .iter()
            .map(|r| r.iter().zip(x).map(|(p, q)| p * q).sum())
            .collect();
        let reference = dense_solve(dense, rhs.clone()).expect("nonsingular");
        let mut solved = rhs;
        band.solve_in_place(&mut solved).expect("well-conditioned");
        let tolerance = 1e-13 * cond.unwrap_or(f64::INFINITY) * n as f64;
        for (i, (p, q)) in solved.iter().zip(&reference).enumerate() {
            prop_assert!(p == q, "x[{i}]: banded {p}, dense {q}");
            prop_assert!(
                (p - x[i]).abs() <= tolerance * (1.0 + x[i].abs()),
                "x[{i}]: banded {p}, solution {}",
                x[i]
            );
        }
        Ok(())
    }

    /// `n`, band entries for every row (some unused near the ends), a
    /// diagonal lift, and a solution.
    fn system(width: usize) -> impl Strategy<Value = (Vec<f64>, f64, Vec<f64>)> {
        (1usize..40).prop_flat_map(move |n| {
            (
                vec(-1.0f64..1.0, n * width),
                0.0f64..3.0,
                vec(-10.0f64..10.0, n),
            )
        })
    }

    proptest! {
        #[test]
        fn pentadiagonal_agrees_with_dense_elimination((entries, lift, x) in system(5)) {
            agrees_with_dense::<2, 2>(&entries, lift, &x)?;
        }

        #[test]
        fn tridiagonal_agrees_with_dense_elimination((entries, lift, x) in system(3)) {
            agrees_with_dense::<1, 1>(&entries, lift, &x)?;
        }

        #[test]
        fn lopsided_bands_agree_with_dense_elimination((entries, lift, x) in system(5)) {
            agrees_with_dense::<3, 1>(&entries, lift, &x)?;
            agrees_with_dense::<1, 3>(&entries, lift, &x)?;
        }
    }
}
