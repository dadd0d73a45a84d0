//! Spline coefficients laid out for evaluation at many points.

use shroud_geometry::spline::{basis_weights, knot_interval, UniformCubicSurface};

/// Coefficients padded with their repeated end rows/columns, so evaluation needs
/// no index clamping in the hot loop: the 16 coefficients of cell `(h, g)` start
/// at `g * stride + h`, four rows `stride` apart.
#[derive(Debug, Clone)]
pub struct PaddedSurface {
    pub(super) cols: usize,
    pub(super) rows: usize,
    pub(super) stride: usize,
    pub(super) data: Vec<f64>,
    /// At `g * stride + h`: the largest `|coefficient|` of cell `(h, g)`, the
    /// scale of the rounding error of any evaluation there.
    pub(super) scale: Vec<f64>,
    /// The largest of `scale`.
    pub(super) max_scale: f64,
}

impl PaddedSurface {
    pub fn new(surface: &UniformCubicSurface) -> Self {
        let stride = surface.cols + 2;
        let mut data = Vec::with_capacity(stride * (surface.rows + 2));
        for k in -1..=surface.rows as isize {
            for j in -1..=surface.cols as isize {
                data.push(surface.coefficient(j, k));
            }
        }
        // The largest |coefficient| of each 4 x 4 block, separably: along rows,
        // then down columns.
        let row_max: Vec<f64> = (0..data.len())
            .map(|i| {
                data[i..(i + 4).min(data.len())]
                    .iter()
                    .fold(0.0f64, |m, c| m.max(c.abs()))
            })
            .collect();
        let mut scale = vec![0.0; data.len()];
        for g in 0..surface.rows - 1 {
            for h in 0..surface.cols - 1 {
                let first = g * stride + h;
                scale[first] = (0..4).fold(0.0f64, |m, r| m.max(row_max[first + r * stride]));
            }
        }
        let max_scale = scale.iter().fold(0.0f64, |m, &c| m.max(c));
        Self {
            cols: surface.cols,
            rows: surface.rows,
            stride,
            data,
            scale,
            max_scale,
        }
    }

    /// Same value as `UniformCubicSurface::eval`, bit for bit (same operation order).
    #[inline]
    pub fn eval(&self, s: f64, t: f64) -> f64 {
        let (h, u) = knot_interval(s, self.cols);
        let (g, v) = knot_interval(t, self.rows);
        self.eval_in_cell(g * self.stride + h, &basis_weights(u), &basis_weights(v))
    }

    /// `UniformCubicSurface::cell_value` of the cell whose coefficients start at
    /// `first`.
    #[inline(always)]
    pub(super) fn eval_in_cell(&self, first: usize, a: &[f64; 4], b: &[f64; 4]) -> f64 {
        let cell = &self.data[first..first + 3 * self.stride + 4];
        let row = |r: usize| -> [f64; 4] { std::array::from_fn(|q| cell[r * self.stride + q]) };
        UniformCubicSurface::cell_value(a, b, &[row(0), row(1), row(2), row(3)])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_scales_are_the_largest_coefficient_of_each_cell() {
        let b: Vec<f64> = (0..42).map(|i| ((i * 29) % 13) as f64 - 6.5).collect();
        let surf = UniformCubicSurface::new(7, 6, b).unwrap();
        let p = PaddedSurface::new(&surf);
        let mut largest = 0.0f64;
        for g in 0..5 {
            for h in 0..6 {
                let expected = surf
                    .cell_coefficients(h, g)
                    .iter()
                    .flatten()
                    .fold(0.0f64, |m, c| m.max(c.abs()));
                assert_eq!(p.scale[g * p.stride + h], expected, "cell ({h}, {g})");
                largest = largest.max(expected);
            }
        }
        assert_eq!(p.max_scale, largest);
    }

    #[test]
    fn padded_eval_matches_surface_eval() {
        let b: Vec<f64> = (0..30)
            .map(|i| ((i * 37) % 11) as f64 * 0.3 - 1.0)
            .collect();
        let surf = UniformCubicSurface::new(6, 5, b).unwrap();
        let p = PaddedSurface::new(&surf);
        for (s, t) in [
            (0.0, 0.0),
            (5.0, 4.0),
            (2.7, 1.3),
            (4.99, 0.01),
            (-1.0, 9.0),
            (f64::NAN, 2.5),
        ] {
            assert_eq!(p.eval(s, t).to_bits(), surf.eval(s, t).to_bits());
        }
    }
}
