//! The iterate of the interior-point method and one Mehrotra predictor-corrector
//! step: residuals, Newton directions from the normal equations, step lengths,
//! and the final lift onto the constraints.

use super::{IpmSettings, IpmSolution};
use crate::tight::banded_cholesky::BandedSpd;
use crate::tight::error::LpError;
use crate::tight::lp::SplineLp;

/// Fraction of the distance to the boundary taken by a step.
const STEP_TO_BOUNDARY: f64 = 0.995;

/// Iterate and workspace.
pub(super) struct State<'a> {
    pub(super) lp: &'a SplineLp,
    /// Constraint rows `m`; unknowns `n`; all rows `m + 2 n`.
    pub(super) m: usize,
    pub(super) n: usize,
    pub(super) total: usize,
    pub(super) x: Vec<f64>,
    pub(super) s: Vec<f64>,
    pub(super) y: Vec<f64>,
    /// Right-hand sides: the heights, the floors, the negated ceiling.
    pub(super) h: Vec<f64>,
    /// Residuals: `r_p = A x - s - h` (all rows), `r_d = c - A^T y`.
    pub(super) rp: Vec<f64>,
    pub(super) rd: Vec<f64>,
    /// `(sum c) min h`: the objective of a flat surface at the lowest height.
    pub(super) base_volume: f64,
    pub(super) normal: BandedSpd,
}

/// Scaled residuals of an iterate.
pub(super) struct Report {
    pub(super) gap: f64,
    pub(super) primal: f64,
    pub(super) dual: f64,
}

impl Report {
    /// How far the iterate is from the stopping rule, as a multiple of it
    /// (`<= 1`: converged).
    pub(super) fn merit(&self, settings: &IpmSettings) -> f64 {
        (self.gap / settings.gap)
            .max(self.primal / settings.feasibility)
            .max(self.dual / settings.feasibility)
    }
}

/// A Newton direction.
struct Direction {
    dx: Vec<f64>,
    ds: Vec<f64>,
    dy: Vec<f64>,
}

impl<'a> State<'a> {
    /// Starts from `start` with Mehrotra's shifted slacks and duals: positive,
    /// and centred enough that the first steps are long.
    pub(super) fn new(lp: &'a SplineLp, start: &[f64]) -> Result<Self, LpError> {
        let (m, n) = (lp.constraints(), lp.unknowns());
        let total = m + 2 * n;
        let mut h = lp.heights.clone();
        h.extend_from_slice(&lp.floors);
        h.extend(std::iter::repeat_n(-lp.ceiling, n));
        let x: Vec<f64> = start
            .iter()
            .zip(&lp.floors)
            .map(|(&v, &f)| v.clamp(f, lp.ceiling.max(f)))
            .collect();
        let mut state = State {
            lp,
            m,
            n,
            total,
            x,
            s: vec![0.0; total],
            y: vec![0.0; total],
            h,
            rp: vec![0.0; total],
            rd: vec![0.0; n],
            base_volume: base_volume(lp),
            normal: BandedSpd::zeros(n, lp.bandwidth),
        };
        state.initial_slacks_and_duals()?;
        Ok(state)
    }

    /// `s = max(A x - h, 0)`, `y` the least-squares solution of `A^T y = c`, both
    /// shifted positive as in Mehrotra (1992), Section 7.
    fn initial_slacks_and_duals(&mut self) -> Result<(), LpError> {
        let mut ax = vec![0.0; self.total];
        self.apply_all(&self.x, &mut ax);
        self.s = ax
            .iter()
            .zip(&self.h)
            .map(|(a, h)| (a - h).max(0.0))
            .collect();
        // y = A (A^T A)^-1 c.
        self.assemble(&vec![1.0; self.total])?;
        let mut z = self.lp.cost.clone();
        self.normal.solve_in_place(&mut z);
        let mut y = vec![0.0; self.total];
        self.apply_all(&z, &mut y);
        self.y = y;
        let shift = |v: &mut Vec<f64>| {
            let lowest = v.iter().fold(f64::INFINITY, |a, &b| a.min(b));
            let d = (-1.5 * lowest).max(0.0);
            v.iter_mut().for_each(|x| *x += d);
        };
        shift(&mut self.s);
        shift(&mut self.y);
        let sy: f64 = self.s.iter().zip(&self.y).map(|(a, b)| a * b).sum();
        let (ssum, ysum): (f64, f64) = (self.s.iter().sum(), self.y.iter().sum());
        let ds = 0.5 * sy / ysum.max(f64::MIN_POSITIVE);
        let dy = 0.5 * sy / ssum.max(f64::MIN_POSITIVE);
        let least = 1e-8 * (1.0 + self.h.iter().fold(0.0f64, |a, b| a.max(b.abs())));
        self.s.iter_mut().for_each(|v| *v = (*v + ds).max(least));
        self.y.iter_mut().for_each(|v| *v = (*v + dy).max(1e-8));
        Ok(())
    }

    /// `out = [A x; x; -x]`.
    pub(super) fn apply_all(&self, x: &[f64], out: &mut [f64]) {
        let (rows, rest) = out.split_at_mut(self.m);
        let (floors, ceilings) = rest.split_at_mut(self.n);
        self.lp.apply(x, rows);
        floors.copy_from_slice(x);
        ceilings.iter_mut().zip(x).for_each(|(o, v)| *o = -v);
    }

    /// `out = [A; I; -I]^T v`.
    pub(super) fn apply_all_transpose(&self, v: &[f64], out: &mut [f64]) {
        let (floors, ceilings) = (&v[self.m..self.m + self.n], &v[self.m + self.n..]);
        out.iter_mut()
            .zip(floors.iter().zip(ceilings))
            .for_each(|(o, (a, b))| *o = a - b);
        self.lp.apply_transpose(&v[..self.m], out);
    }

    pub(super) fn residuals(&mut self) -> Report {
        let mut ax = vec![0.0; self.total];
        self.apply_all(&self.x, &mut ax);
        for (r, ((a, s), h)) in self.rp.iter_mut().zip(ax.iter().zip(&self.s).zip(&self.h)) {
            *r = a - s - h;
        }
        let mut aty = vec![0.0; self.n];
        self.apply_all_transpose(&self.y, &mut aty);
        for (r, (c, a)) in self.rd.iter_mut().zip(self.lp.cost.iter().zip(&aty)) {
            *r = c - a;
        }
        let primal_objective = self.lp.objective(&self.x);
        let h_scale = 1.0 + self.h.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let c_scale = 1.0 + self.lp.cost.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        Report {
            gap: self.relative_gap(primal_objective),
            primal: max_abs(&self.rp) / h_scale,
            dual: max_abs(&self.rd) / c_scale,
        }
    }

    /// The complementarity gap `s.y` relative to the volume above the lowest
    /// constraint. For an infeasible iterate `c.x - h.y = s.y + x.r_d + y.r_p`;
    /// the residual terms are policed by the feasibility tests, and `s.y` keeps
    /// its relative precision where `c.x - h.y` cancels. Flat data has its
    /// optimum at that volume's zero, so the volume is not trusted below what
    /// rounding leaves of the objective.
    fn relative_gap(&self, primal: f64) -> f64 {
        let complementarity: f64 = self.s.iter().zip(&self.y).map(|(s, y)| s * y).sum();
        let rounding = 1e-9 * (primal.abs() + self.base_volume.abs());
        complementarity
            / (primal - self.base_volume)
                .abs()
                .max(rounding)
                .max(f64::MIN_POSITIVE)
    }

    /// One predictor-corrector iteration.
    pub(super) fn step(&mut self) -> Result<(), LpError> {
        let total = self.total;
        let d: Vec<f64> = self.y.iter().zip(&self.s).map(|(y, s)| y / s).collect();
        self.assemble(&d)?;
        let mu = self.s.iter().zip(&self.y).map(|(a, b)| a * b).sum::<f64>() / total as f64;
        // Predictor (affine scaling): complementarity target 0.
        let target: Vec<f64> = self.s.iter().zip(&self.y).map(|(s, y)| -s * y).collect();
        let affine = self.direction(&d, &target);
        let (ap, ad) = (
            self.max_step(&self.s, &affine.ds),
            self.max_step(&self.y, &affine.dy),
        );
        let mu_affine = (0..total)
            .map(|i| (self.s[i] + ap * affine.ds[i]) * (self.y[i] + ad * affine.dy[i]))
            .sum::<f64>()
            / total as f64;
        let sigma = (mu_affine / mu).powi(3).clamp(0.0, 1.0);
        // Corrector: centring plus the second-order term of the predictor.
        let target: Vec<f64> = (0..total)
            .map(|i| -self.s[i] * self.y[i] + sigma * mu - affine.ds[i] * affine.dy[i])
            .collect();
        let dir = self.direction(&d, &target);
        let ap = (STEP_TO_BOUNDARY * self.max_step(&self.s, &dir.ds)).min(1.0);
        let ad = (STEP_TO_BOUNDARY * self.max_step(&self.y, &dir.dy)).min(1.0);
        self.x
            .iter_mut()
            .zip(&dir.dx)
            .for_each(|(v, d)| *v += ap * d);
        self.s
            .iter_mut()
            .zip(&dir.ds)
            .for_each(|(v, d)| *v += ap * d);
        self.y
            .iter_mut()
            .zip(&dir.dy)
            .for_each(|(v, d)| *v += ad * d);
        Ok(())
    }

    /// Newton direction for complementarity target `S dy + Y ds = target`:
    /// `(A^T D A) dx = A^T (S^-1 target - D r_p) - r_d`, then
    /// `ds = A dx + r_p`, `dy = S^-1 target - D ds`.
    fn direction(&self, d: &[f64], target: &[f64]) -> Direction {
        let total = self.total;
        let v: Vec<f64> = (0..total)
            .map(|i| target[i] / self.s[i] - d[i] * self.rp[i])
            .collect();
        let mut dx = vec![0.0; self.n];
        self.apply_all_transpose(&v, &mut dx);
        dx.iter_mut().zip(&self.rd).for_each(|(a, r)| *a -= r);
        self.normal.solve_in_place(&mut dx);
        let mut ds = vec![0.0; total];
        self.apply_all(&dx, &mut ds);
        ds.iter_mut().zip(&self.rp).for_each(|(a, r)| *a += r);
        let dy = (0..total)
            .map(|i| target[i] / self.s[i] - d[i] * ds[i])
            .collect();
        Direction { dx, ds, dy }
    }

    /// Largest `alpha` in `(0, inf)` keeping `v + alpha dv >= 0`.
    fn max_step(&self, v: &[f64], dv: &[f64]) -> f64 {
        v.iter()
            .zip(dv)
            .filter(|(_, &d)| d < 0.0)
            .fold(f64::INFINITY, |a, (&x, &d)| a.min(-x / d))
    }

    /// Lifts `x` uniformly by the largest remaining row violation (the basis is a
    /// partition of unity, so this raises the surface at every row by as much).
    pub(super) fn finish(mut self, iterations: usize) -> IpmSolution {
        self.x
            .iter_mut()
            .zip(&self.lp.floors)
            .for_each(|(v, f)| *v = v.max(*f));
        let scale = self.h.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let mut values = vec![0.0; self.m];
        let mut lift = 0.0;
        // Rounding in the 16-term sums can leave a row a few ulps short after one
        // lift; a second pass settles it.
        for _ in 0..3 {
            self.lp.apply(&self.x, &mut values);
            let violation = values
                .iter()
                .zip(&self.lp.heights)
                .fold(0.0f64, |m, (f, h)| m.max(h - f));
            if violation <= 0.0 {
                break;
            }
            let step = violation + 16.0 * f64::EPSILON * scale;
            self.x.iter_mut().for_each(|v| *v += step);
            lift += step;
        }
        let objective = self.lp.objective(&self.x);
        IpmSolution {
            x: self.x,
            y: self.y,
            objective,
            iterations,
            lift,
        }
    }
}

/// `(sum c) min h` over the rows (0 for an empty LP). Not over the floors: the
/// safety floor lies far below the data, and a volume measured from it would
/// make the gap rule that much looser.
pub(super) fn base_volume(lp: &SplineLp) -> f64 {
    let lowest = lp.heights.iter().fold(f64::INFINITY, |m, &v| m.min(v));
    if lowest.is_finite() {
        lp.cost.iter().sum::<f64>() * lowest
    } else {
        0.0
    }
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}
