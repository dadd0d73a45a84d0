//! The optimal-safe-surface linear program over a constraint set: minimise the
//! integral of `f` over the kept domain subject to `f(s_i, t_i) >= h_i` (upper
//! sense). `f` is linear in the coefficients and each constraint row has at most
//! 16 non-zeros: `basis_weights(u) x basis_weights(v)` on the 4 x 4 coefficients
//! of the constraint's cell (Section 2, eq. (1), in tensor form).
//!
//! Two bounds make the LP well posed where data is sparse (see [`super::bounds`]);
//! neither binds where data is dense.

use super::bounds::{ceiling_of, safety_floor};
// Still public as `tight::lp::cell_slots`; defined in `cells`, below both the
// LP and its bounds, which need it too.
pub use super::cells::cell_slots;
use super::error::LpError;
use super::objective::objective_weights;
use crate::{Candidate, TrimMask};
use shroud_geometry::spline::{basis_weights, knot_interval, UniformCubicSurface};

/// The constraint rows falling into one grid cell, `rows[start..end]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellRows {
    /// Positions (unknown indices) of the 16 coefficients acting on the cell,
    /// `[r * 4 + q]` for coefficient slot `(q, r)`; clamped ends repeat an unknown.
    pub unknowns: [u32; 16],
    pub start: usize,
    pub end: usize,
}

/// The LP in the unknowns it actually moves. A coefficient is an unknown when it
/// has objective weight (its support touches a kept cell) and some constraint
/// depends on it; every other coefficient keeps its value.
#[derive(Debug, Clone)]
pub struct SplineLp {
    pub cols: usize,
    pub rows: usize,
    /// Coefficient index (`k * cols + j`) of each unknown, in band order.
    pub coefficient_of: Vec<usize>,
    /// Objective weight of each unknown.
    pub cost: Vec<f64>,
    /// Lower bound of each unknown (see [`super::bounds::safety_floor`]).
    pub floors: Vec<f64>,
    /// Upper bound shared by the unknowns (see [`super::bounds::ceiling_of`]).
    pub ceiling: f64,
    /// Half-bandwidth of `A^T D A` in the unknowns' order.
    pub bandwidth: usize,
    pub cells: Vec<CellRows>,
    /// Row weights `[r * 4 + q] = B_q(u) B_r(v)`, grouped by cell.
    pub weights: Vec<[f64; 16]>,
    pub heights: Vec<f64>,
}

impl SplineLp {
    /// The LP of `surface` (upper sense; it supplies the grid and the values of
    /// the coefficients that stay fixed) constrained by `constraints` over `trim`.
    pub fn new(
        surface: &UniformCubicSurface,
        trim: &TrimMask,
        constraints: &[Candidate],
    ) -> Result<Self, LpError> {
        let (cols, rows) = (surface.cols, surface.rows);
        check_inputs(cols, rows, trim, constraints)?;
        let objective = objective_weights(cols, rows, trim);
        let grouped = group_by_cell(cols, rows, constraints);
        let touched = touched_coefficients(cols, rows, &grouped, trim);
        let coefficient_of: Vec<usize> = band_order(cols, rows)
            .into_iter()
            .filter(|&i| objective[i] > 0.0 && touched[i])
            .collect();
        let cost = coefficient_of.iter().map(|&i| objective[i]).collect();
        let floors = vec![safety_floor(constraints); coefficient_of.len()];
        let lp = SplineLp {
            cols,
            rows,
            coefficient_of,
            cost,
            floors,
            ceiling: ceiling_of(constraints),
            bandwidth: 0,
            cells: Vec::new(),
            weights: Vec::new(),
            heights: Vec::new(),
        };
        Ok(lp.with_rows(surface, trim, &grouped))
    }

    /// The same unknowns, objective and floors with a different constraint set
    /// (the cutting planes of the reference). Constraints that weigh a fixed
    /// coefficient have its contribution moved to their right-hand side.
    pub fn with_constraints(
        &self,
        surface: &UniformCubicSurface,
        trim: &TrimMask,
        constraints: &[Candidate],
    ) -> Result<Self, LpError> {
        check_inputs(self.cols, self.rows, trim, constraints)?;
        Ok(self.clone_header().with_rows(
            surface,
            trim,
            &group_by_cell(self.cols, self.rows, constraints),
        ))
    }

    /// Everything but the rows.
    fn clone_header(&self) -> SplineLp {
        SplineLp {
            cols: self.cols,
            rows: self.rows,
            coefficient_of: self.coefficient_of.clone(),
            cost: self.cost.clone(),
            floors: self.floors.clone(),
            ceiling: self.ceiling,
            bandwidth: 0,
            cells: Vec::new(),
            weights: Vec::new(),
            heights: Vec::new(),
        }
    }

    fn with_rows(
        mut self,
        surface: &UniformCubicSurface,
        trim: &TrimMask,
        grouped: &[(usize, usize, Vec<Candidate>)],
    ) -> Self {
        let mut position = vec![u32::MAX; self.cols * self.rows];
        self.coefficient_of
            .iter()
            .enumerate()
            .for_each(|(p, &i)| position[i] = p as u32);
        for (h, g, list) in grouped {
            // Constraints outside the kept region have no say in the objective's
            // domain; the fitter never produces them (a point keeps its triangle).
            if !trim.cell_kept(*h, *g) {
                continue;
            }
            let slots = cell_slots(*h, *g, self.cols, self.rows);
            let Some(any) = slots.iter().map(|&i| position[i]).find(|&p| p != u32::MAX) else {
                continue;
            };
            // A slot that is not an unknown contributes a constant; its weight is
            // zeroed and its index borrowed from a real unknown of the cell.
            let fixed = slots.map(|i| position[i] == u32::MAX);
            let unknowns = slots.map(|i| {
                if position[i] == u32::MAX {
                    any
                } else {
                    position[i]
                }
            });
            let (lo, hi) = unknowns
                .iter()
                .fold((u32::MAX, 0), |(a, b), &p| (a.min(p), b.max(p)));
            self.bandwidth = self.bandwidth.max((hi - lo) as usize);
            let start = self.weights.len();
            for c in list {
                let mut w = row_weights(c.s, c.t, self.cols, self.rows);
                let mut height = c.height;
                for a in (0..16).filter(|&a| fixed[a]) {
                    height -= w[a] * surface.coefficients[slots[a]];
                    w[a] = 0.0;
                }
                self.weights.push(w);
                self.heights.push(height);
            }
            self.cells.push(CellRows {
                unknowns,
                start,
                end: self.weights.len(),
            });
        }
        self
    }

    pub fn unknowns(&self) -> usize {
        self.coefficient_of.len()
    }

    pub fn constraints(&self) -> usize {
        self.heights.len()
    }

    /// The unknowns' values in `coefficients`.
    pub fn gather(&self, coefficients: &[f64]) -> Vec<f64> {
        self.coefficient_of
            .iter()
            .map(|&i| coefficients[i])
            .collect()
    }

    /// Writes the unknowns back into `coefficients`, leaving the others as they are.
    pub fn scatter(&self, x: &[f64], coefficients: &mut [f64]) {
        self.coefficient_of
            .iter()
            .zip(x)
            .for_each(|(&i, &v)| coefficients[i] = v);
    }

    /// `c . x`: the integral of the surface over the kept domain, up to the
    /// contribution of the coefficients that are not unknowns.
    pub fn objective(&self, x: &[f64]) -> f64 {
        self.cost.iter().zip(x).map(|(c, v)| c * v).sum()
    }

    /// `A x` (the surface at every constraint) into `out`.
    pub fn apply(&self, x: &[f64], out: &mut [f64]) {
        for cell in &self.cells {
            let xs = cell.unknowns.map(|p| x[p as usize]);
            let rows = cell.start..cell.end;
            for (o, w) in out[rows.clone()].iter_mut().zip(&self.weights[rows]) {
                *o = dot16(w, &xs);
            }
        }
    }

    /// `out += A^T v`.
    pub fn apply_transpose(&self, v: &[f64], out: &mut [f64]) {
        for cell in &self.cells {
            let mut acc = [0.0; 16];
            let rows = cell.start..cell.end;
            for (w, vi) in self.weights[rows.clone()].iter().zip(&v[rows]) {
                acc.iter_mut().zip(w).for_each(|(a, wa)| *a += wa * vi);
            }
            cell.unknowns
                .iter()
                .zip(&acc)
                .for_each(|(&p, a)| out[p as usize] += a);
        }
    }

    /// Largest `h_i - f(s_i, t_i)` over the constraints (negative when all hold
    /// with room to spare; `-inf` without constraints).
    pub fn max_violation(&self, x: &[f64]) -> f64 {
        let mut values = vec![0.0; self.constraints()];
        self.apply(x, &mut values);
        values
            .iter()
            .zip(&self.heights)
            .fold(f64::NEG_INFINITY, |m, (f, h)| m.max(h - f))
    }
}

#[inline]
pub fn dot16(a: &[f64; 16], b: &[f64; 16]) -> f64 {
    let mut acc = [0.0; 4];
    for r in 0..4 {
        for q in 0..4 {
            acc[q] += a[r * 4 + q] * b[r * 4 + q];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

/// `B_q(u) B_r(v)` at `(s, t)`, `[r * 4 + q]`.
pub fn row_weights(s: f64, t: f64, cols: usize, rows: usize) -> [f64; 16] {
    let (_, u) = knot_interval(s, cols);
    let (_, v) = knot_interval(t, rows);
    let (bu, bv) = (basis_weights(u), basis_weights(v));
    let mut w = [0.0; 16];
    for r in 0..4 {
        for q in 0..4 {
            w[r * 4 + q] = bu[q] * bv[r];
        }
    }
    w
}

/// Constraints grouped by cell `(h, g)`, cells in row-major order.
pub fn group_by_cell(
    cols: usize,
    rows: usize,
    constraints: &[Candidate],
) -> Vec<(usize, usize, Vec<Candidate>)> {
    let cells_s = cols - 1;
    let mut lists: Vec<Vec<Candidate>> = vec![Vec::new(); cells_s * (rows - 1)];
    for c in constraints {
        let (h, _) = knot_interval(c.s, cols);
        let (g, _) = knot_interval(c.t, rows);
        lists[g * cells_s + h].push(*c);
    }
    lists
        .into_iter()
        .enumerate()
        .filter(|(_, l)| !l.is_empty())
        .map(|(i, l)| (i % cells_s, i / cells_s, l))
        .collect()
}

fn check_inputs(
    cols: usize,
    rows: usize,
    trim: &TrimMask,
    constraints: &[Candidate],
) -> Result<(), LpError> {
    if trim.cells_s + 1 != cols || trim.cells_t + 1 != rows {
        return Err(LpError::TrimMismatch {
            cols,
            rows,
            cells_s: trim.cells_s,
            cells_t: trim.cells_t,
        });
    }
    match constraints
        .iter()
        .position(|c| !(c.s.is_finite() && c.t.is_finite() && c.height.is_finite()))
    {
        Some(index) => {
            let c = constraints[index];
            Err(LpError::NonFiniteConstraint {
                index,
                s: c.s,
                t: c.t,
                height: c.height,
            })
        }
        None => Ok(()),
    }
}

/// Coefficients some constraint in a kept cell gives a positive weight.
fn touched_coefficients(
    cols: usize,
    rows: usize,
    grouped: &[(usize, usize, Vec<Candidate>)],
    trim: &TrimMask,
) -> Vec<bool> {
    let mut touched = vec![false; cols * rows];
    for (h, g, list) in grouped.iter().filter(|(h, g, _)| trim.cell_kept(*h, *g)) {
        let slots = cell_slots(*h, *g, cols, rows);
        let mut any = [false; 16];
        for c in list {
            let w = row_weights(c.s, c.t, cols, rows);
            (0..16).for_each(|a| any[a] |= w[a] > 0.0);
        }
        slots.iter().zip(&any).for_each(|(&i, &a)| touched[i] |= a);
    }
    touched
}

/// Coefficient indices in the order that makes `A^T D A` banded with the smaller
/// half-bandwidth: a constraint couples coefficients at most 3 apart along each
/// parameter, so row-major order gives `3 cols + 3`, column-major `3 rows + 3`.
fn band_order(cols: usize, rows: usize) -> Vec<usize> {
    if cols <= rows {
        (0..cols * rows).collect()
    } else {
        (0..cols)
            .flat_map(|j| (0..rows).map(move |k| k * cols + j))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shroud_geometry::spline::UniformCubicSurface;

    fn candidates() -> Vec<Candidate> {
        (0..300)
            .map(|i| {
                let (s, t) = ((i * 37 % 101) as f64 * 0.06, (i * 53 % 97) as f64 * 0.041);
                Candidate {
                    s,
                    t,
                    height: (s * 0.8).sin() + 0.2 * t,
                }
            })
            .collect()
    }

    #[test]
    fn rows_evaluate_the_surface() {
        let (cols, rows) = (8, 5);
        let cands = candidates();
        let lp = SplineLp::new(
            &UniformCubicSurface::constant(cols, rows, 0.0).unwrap(),
            &TrimMask::full(cols - 1, rows - 1),
            &cands,
        )
        .unwrap();
        assert_eq!(lp.unknowns(), cols * rows);
        let b: Vec<f64> = (0..cols * rows)
            .map(|i| ((i * 29) % 13) as f64 * 0.1)
            .collect();
        let surface = UniformCubicSurface::new(cols, rows, b.clone()).unwrap();
        let mut values = vec![0.0; lp.constraints()];
        lp.apply(&lp.gather(&b), &mut values);
        let mut expected: Vec<f64> = cands.iter().map(|c| surface.eval(c.s, c.t)).collect();
        let mut got = values.clone();
        expected.sort_by(f64::total_cmp);
        got.sort_by(f64::total_cmp);
        got.iter()
            .zip(&expected)
            .for_each(|(a, e)| assert!((a - e).abs() < 1e-12));
    }

    #[test]
    fn transpose_is_the_adjoint() {
        let (cols, rows) = (9, 6);
        let lp = SplineLp::new(
            &UniformCubicSurface::constant(cols, rows, 0.0).unwrap(),
            &TrimMask::full(cols - 1, rows - 1),
            &candidates(),
        )
        .unwrap();
        let x: Vec<f64> = (0..lp.unknowns())
            .map(|i| (i as f64 * 0.37).cos())
            .collect();
        let v: Vec<f64> = (0..lp.constraints())
            .map(|i| (i as f64 * 0.11).sin())
            .collect();
        let mut ax = vec![0.0; lp.constraints()];
        lp.apply(&x, &mut ax);
        let mut atv = vec![0.0; lp.unknowns()];
        lp.apply_transpose(&v, &mut atv);
        let (left, right): (f64, f64) = (
            ax.iter().zip(&v).map(|(a, b)| a * b).sum(),
            atv.iter().zip(&x).map(|(a, b)| a * b).sum(),
        );
        assert!((left - right).abs() < 1e-10);
        assert!(lp.bandwidth <= 3 * rows + 3, "{}", lp.bandwidth);
    }

    #[test]
    fn trimmed_coefficients_are_not_unknowns() {
        let (cols, rows) = (8, 5);
        let mut trim = TrimMask::empty(cols - 1, rows - 1);
        trim.bits[0] = crate::trim::ALL;
        let cands: Vec<Candidate> = candidates()
            .into_iter()
            .filter(|c| c.s < 1.0 && c.t < 1.0)
            .collect();
        let surface = UniformCubicSurface::constant(cols, rows, 0.0).unwrap();
        let lp = SplineLp::new(&surface, &trim, &cands).unwrap();
        assert_eq!(lp.unknowns(), 9);
        let taller = UniformCubicSurface::constant(cols, rows + 1, 0.0).unwrap();
        assert!(SplineLp::new(&taller, &trim, &cands).is_err());
    }
}
