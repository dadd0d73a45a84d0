//! The matrix form (2): `f(s) = (I_s + S_s D / 6) b`, built densely for tests and
//! for the trial-and-error baseline of Section 3 on small problems.

use super::basis::knot_interval;

/// `D`: rows are second-difference masks `1, -2, 1`, the first and last rows are
/// first differences `-1, 1` because of the repeated end coefficients.
pub fn difference_matrix(n: usize) -> Vec<Vec<f64>> {
    let mut d = vec![vec![0.0; n]; n];
    for (i, row) in d.iter_mut().enumerate() {
        let prev = i.saturating_sub(1);
        let next = (i + 1).min(n - 1);
        row[prev] += 1.0;
        row[i] -= 2.0;
        row[next] += 1.0;
    }
    d
}

/// `I_s + S_s D / 6` for parameters `s`, a `|s| x n` dense matrix.
pub fn evaluation_matrix(s: &[f64], n: usize) -> Vec<Vec<f64>> {
    let d = difference_matrix(n);
    s.iter()
        .map(|&si| {
            let (h, u) = knot_interval(si, n);
            let mut row = vec![0.0; n];
            row[h] += 1.0 - u;
            row[h + 1] += u;
            let (a, c) = ((1.0 - u).powi(3) / 6.0, u.powi(3) / 6.0);
            for j in 0..n {
                row[j] += a * d[h][j] + c * d[h + 1][j];
            }
            row
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::UniformCubicCurve;

    #[test]
    fn matrix_form_matches_evaluation() {
        let b = vec![1.0, 3.0, -2.0, 0.5, 4.0];
        let curve = UniformCubicCurve::new(b.clone()).unwrap();
        let s = [0.0, 0.3, 1.7, 2.0, 3.99, 4.0];
        for (row, &si) in evaluation_matrix(&s, b.len()).iter().zip(&s) {
            let f: f64 = row.iter().zip(&b).map(|(a, c)| a * c).sum();
            assert!((f - curve.eval(si)).abs() < 1e-12);
        }
        let d = difference_matrix(4);
        assert_eq!(d[0], vec![-1.0, 1.0, 0.0, 0.0]);
        assert_eq!(d[3], vec![0.0, 0.0, 1.0, -1.0]);
    }
}
