//! The LP objective: the integral of the surface over the kept (untrimmed)
//! domain, a linear function `sum_jk c_jk b_jk` of the coefficients.

use super::quadrature::TriangleMoments;
use crate::TrimMask;

/// `c_jk = ∫_kept N_j(s) N_k(t) ds dt` in parameter units, row-major like the
/// coefficients (`c[k * cols + j]`). The repeated end coefficients fold their
/// weights into the first and last row and column. Coefficients whose support
/// touches no kept cell get exactly zero.
///
/// `trim` must have `cols - 1` by `rows - 1` cells.
pub fn objective_weights(cols: usize, rows: usize, trim: &TrimMask) -> Vec<f64> {
    let moments = TriangleMoments::new();
    let mut c = vec![0.0; cols * rows];
    for g in 0..trim.cells_t {
        for h in 0..trim.cells_s {
            let bits = trim.cell_bits(h, g);
            if bits == 0 {
                continue;
            }
            let m = moments.of(bits);
            for (r, row) in m.iter().enumerate() {
                let k = clamp_index(g + r, rows);
                for (q, value) in row.iter().enumerate() {
                    c[k * cols + clamp_index(h + q, cols)] += value;
                }
            }
        }
    }
    c
}

/// Coefficient index of slot `shifted = cell + q` (slot `q` acts on `cell + q - 1`),
/// with the repeated ends `b_{-1} = b_0`, `b_n = b_{n-1}` of Section 2.
#[inline]
pub fn clamp_index(shifted: usize, len: usize) -> usize {
    shifted.saturating_sub(1).min(len - 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_geometry::spline::UniformCubicSurface;

    #[test]
    fn weights_sum_to_the_kept_area() {
        // Partition of unity: sum_jk N_j N_k = 1 on the domain.
        let mut trim = TrimMask::empty(6, 4);
        for (i, b) in trim.bits.iter_mut().enumerate() {
            *b = ((i * 7) % 16) as u8;
        }
        let c = objective_weights(7, 5, &trim);
        let sum: f64 = c.iter().sum();
        assert!(
            (sum - trim.kept_area()).abs() < 1e-13,
            "{sum} vs {}",
            trim.kept_area()
        );
        assert!(c.iter().all(|&x| x >= 0.0));
    }

    #[test]
    fn weights_integrate_a_surface_exactly() {
        // c . b equals the integral of f; checked against a fine midpoint rule over
        // the full domain for a non-constant surface.
        let (cols, rows) = (5, 4);
        let b: Vec<f64> = (0..cols * rows)
            .map(|i| ((i * 13) % 7) as f64 - 2.0)
            .collect();
        let surface = UniformCubicSurface::new(cols, rows, b.clone()).unwrap();
        let c = objective_weights(cols, rows, &TrimMask::full(cols - 1, rows - 1));
        let exact: f64 = c.iter().zip(&b).map(|(x, y)| x * y).sum();
        let n = 400;
        let (ws, wt) = ((cols - 1) as f64 / n as f64, (rows - 1) as f64 / n as f64);
        let mut approx = 0.0;
        for i in 0..n {
            for k in 0..n {
                approx += surface.eval((i as f64 + 0.5) * ws, (k as f64 + 0.5) * wt) * ws * wt;
            }
        }
        assert!((exact - approx).abs() < 1e-4, "{exact} vs {approx}");
    }

    #[test]
    fn coefficients_away_from_kept_cells_get_no_weight() {
        let mut trim = TrimMask::empty(9, 9);
        trim.bits[0] = crate::trim::ALL; // only cell (0, 0)
        let c = objective_weights(10, 10, &trim);
        // Cell (0, 0) uses columns and rows 0..=2 (slot 0 is the repeated b_0).
        for k in 0..10 {
            for j in 0..10 {
                assert_eq!(c[k * 10 + j] > 0.0, j <= 2 && k <= 2, "({j}, {k})");
            }
        }
    }
}
