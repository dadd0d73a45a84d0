//! A primal-dual interior-point method (Mehrotra predictor-corrector) for the
//! spline LP `min c.x  s.t.  A x >= h,  floors <= x <= ceiling`.
//!
//! Each iteration solves the normal equations `(A^T D A + D_b) dx = r` once for
//! the predictor and once for the corrector with the same factor. `A^T D A` is
//! assembled cell by cell (all rows of a cell share their 16 unknowns) and is
//! banded in the unknowns' order, so a banded Cholesky factorisation does it.

use super::banded_cholesky::BandedSpd;
use super::error::LpError;
use super::lp::SplineLp;

/// Stopping rule and budget.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IpmSettings {
    /// Duality gap `|c.x - h.y|` to stop at, relative to the volume between the
    /// surface and the lowest constraint, `c.x - (sum c) min h`. Both are
    /// unchanged when every height moves by a constant (the basis sums to one),
    /// so the rule does not depend on where the frame's origin is.
    pub gap: f64,
    /// Relative primal and dual infeasibility to stop at.
    pub feasibility: f64,
    pub max_iterations: usize,
}

impl Default for IpmSettings {
    fn default() -> Self {
        Self {
            gap: 1e-9,
            feasibility: 1e-9,
            max_iterations: 60,
        }
    }
}

/// The solution in the LP's unknowns.
#[derive(Debug, Clone, PartialEq)]
pub struct IpmSolution {
    pub x: Vec<f64>,
    /// Dual values of the constraint rows (then of the floor bounds).
    pub y: Vec<f64>,
    pub objective: f64,
    pub iterations: usize,
    /// The uniform lift applied at the end so that every row holds exactly (the
    /// unknowns are also raised to their floors first).
    pub lift: f64,
}

/// Largest factorisation accepted, in multiply-adds (`n bw^2 / 2`): about a
/// second per iteration on one core. A 100 x 100 grid needs ~5e8; beyond the
/// limit the caller falls back to coordinate descent.
const MAX_FACTOR_FLOPS: f64 = 2e9;

/// Fraction of the distance to the boundary taken by a step.
const STEP_TO_BOUNDARY: f64 = 0.995;

/// Solves `lp` from `start` (the unknowns' values of a surface; feasibility is not
/// required). The rows are the constraints, then one identity row per unknown
/// for its floor and one negated identity row for the ceiling; slacks `s = A x - h`
/// and duals `y` live on all of them.
pub fn solve(lp: &SplineLp, start: &[f64], settings: &IpmSettings) -> Result<IpmSolution, LpError> {
    let (unknowns, bandwidth) = (lp.unknowns(), lp.bandwidth);
    let flops = unknowns as f64 * (bandwidth as f64 + 1.0).powi(2) / 2.0;
    if flops > MAX_FACTOR_FLOPS {
        return Err(LpError::TooLarge {
            unknowns,
            bandwidth,
            flops,
        });
    }
    let mut state = State::new(lp, start)?;
    let mut best = Best {
        merit: f64::INFINITY,
        x: Vec::new(),
        y: Vec::new(),
        at: 0,
    };
    for iterations in 0.. {
        let report = state.residuals();
        let merit = report.merit(settings);
        if merit <= 1.0 {
            return Ok(state.finish(iterations));
        }
        if merit < best.merit {
            best = Best {
                merit,
                x: state.x.clone(),
                y: state.y.clone(),
                at: iterations,
            };
        }
        // Near the optimum the normal equations become so ill-conditioned that the
        // residuals can stall above the tolerance (and then grow again) while the
        // complementarity gap has long converged.
        let stalled = report.gap <= settings.gap && iterations >= best.at + STALL_ITERATIONS;
        if iterations == settings.max_iterations || stalled {
            if best.merit <= ACCEPTABLE_MERIT {
                (state.x, state.y) = (best.x, best.y);
                return Ok(state.finish(iterations));
            }
            return Err(LpError::NoConvergence {
                iterations,
                gap: report.gap,
                infeasibility: report.primal.max(report.dual),
            });
        }
        state.step()?;
    }
    Err(LpError::NoConvergence {
        iterations: usize::MAX,
        gap: f64::NAN,
        infeasibility: f64::NAN,
    })
}

/// The iterate closest to the stopping rule so far.
struct Best {
    merit: f64,
    x: Vec<f64>,
    y: Vec<f64>,
    at: usize,
}

/// Iterations without a better iterate, once the gap has closed, after which the
/// method stops.
const STALL_ITERATIONS: usize = 6;
/// A stalled run still returns its best iterate if that meets the tolerances to
/// within this factor (the final lift makes it feasible in any case).
const ACCEPTABLE_MERIT: f64 = 1e3;

/// Iterate and workspace.
struct State<'a> {
    lp: &'a SplineLp,
    /// Constraint rows `m`; unknowns `n`; all rows `m + 2 n`.
    m: usize,
    n: usize,
    total: usize,
    x: Vec<f64>,
    s: Vec<f64>,
    y: Vec<f64>,
    /// Right-hand sides: the heights, the floors, the negated ceiling.
    h: Vec<f64>,
    /// Residuals: `r_p = A x - s - h` (all rows), `r_d = c - A^T y`.
    rp: Vec<f64>,
    rd: Vec<f64>,
    /// `(sum c) min h`: the objective of a flat surface at the lowest height.
    base_volume: f64,
    normal: BandedSpd,
}

/// Scaled residuals of an iterate.
struct Report {
    gap: f64,
    primal: f64,
    dual: f64,
}

impl Report {
    /// How far the iterate is from the stopping rule, as a multiple of it
    /// (`<= 1`: converged).
    fn merit(&self, settings: &IpmSettings) -> f64 {
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
    fn new(lp: &'a SplineLp, start: &[f64]) -> Result<Self, LpError> {
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
    fn apply_all(&self, x: &[f64], out: &mut [f64]) {
        let (rows, rest) = out.split_at_mut(self.m);
        let (floors, ceilings) = rest.split_at_mut(self.n);
        self.lp.apply(x, rows);
        floors.copy_from_slice(x);
        ceilings.iter_mut().zip(x).for_each(|(o, v)| *o = -v);
    }

    /// `out = [A; I; -I]^T v`.
    fn apply_all_transpose(&self, v: &[f64], out: &mut [f64]) {
        let (floors, ceilings) = (&v[self.m..self.m + self.n], &v[self.m + self.n..]);
        out.iter_mut()
            .zip(floors.iter().zip(ceilings))
            .for_each(|(o, (a, b))| *o = a - b);
        self.lp.apply_transpose(&v[..self.m], out);
    }

    /// Assembles and factors `A^T D A + diag(D_floor + D_ceiling)`.
    fn assemble(&mut self, d: &[f64]) -> Result<(), LpError> {
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

    fn residuals(&mut self) -> Report {
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
    fn step(&mut self) -> Result<(), LpError> {
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
    fn finish(mut self, iterations: usize) -> IpmSolution {
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

/// `(sum c) min h` over the rows and floors (0 for an empty LP).
fn base_volume(lp: &SplineLp) -> f64 {
    let lowest = lp
        .heights
        .iter()
        .chain(&lp.floors)
        .fold(f64::INFINITY, |m, &v| m.min(v));
    if lowest.is_finite() {
        lp.cost.iter().sum::<f64>() * lowest
    } else {
        0.0
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

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

#[cfg(test)]
mod tests {
    use super::super::fixture::Fixture;
    use super::super::lp_reference::solve_with_clarabel;
    use super::*;
    use crate::spline::UniformCubicSurface;
    use crate::surrogate::{Candidate, TrimMask};

    fn assert_matches_clarabel(lp: &SplineLp, start: &[f64]) {
        let ipm = solve(lp, start, &IpmSettings::default()).unwrap();
        let reference = lp.objective(&solve_with_clarabel(lp).unwrap());
        let relative = (ipm.objective - reference).abs() / reference.abs().max(1e-300);
        assert!(
            relative < 1e-6,
            "ipm {} vs clarabel {reference} ({} iterations)",
            ipm.objective,
            ipm.iterations
        );
        assert!(lp.max_violation(&ipm.x) <= 0.0);
    }

    #[test]
    fn matches_clarabel_on_a_fitted_candidate_lp() {
        for fixture in [
            Fixture::spheres(20_000, 12, 0.3),
            Fixture::terrain(20_000, 10),
        ] {
            let surface = &fixture.plain.upper.as_ref().unwrap().surface;
            let lp = SplineLp::new(surface, &fixture.plain.trim, &fixture.candidates()).unwrap();
            assert_matches_clarabel(&lp, &lp.gather(&surface.coefficients));
        }
    }

    #[test]
    fn solves_flat_degenerate_data() {
        // Every candidate and floor at one height: the optimum is the flat surface,
        // with every constraint and bound active at once.
        let (cols, rows) = (5, 5);
        let candidates: Vec<Candidate> = (0..cols * 4)
            .map(|i| Candidate {
                s: i as f64 * 0.25,
                t: (i % rows) as f64,
                height: 1.0,
            })
            .collect();
        let surface = UniformCubicSurface::constant(cols, rows, 2.0).unwrap();
        let lp = SplineLp::new(&surface, &TrimMask::full(cols - 1, rows - 1), &candidates).unwrap();
        let solution = solve(
            &lp,
            &lp.gather(&surface.coefficients),
            &IpmSettings::default(),
        )
        .unwrap();
        assert!(
            (solution.objective - 16.0).abs() < 1e-8,
            "{}",
            solution.objective
        );
        assert_matches_clarabel(&lp, &lp.gather(&surface.coefficients));
    }

    #[test]
    fn refuses_a_band_too_large_to_factor() {
        // One candidate per cell of a 150 x 150 grid: 22500 unknowns, half-bandwidth
        // 453, about 2.3e9 multiply-adds per factorisation.
        let (cols, rows) = (150, 150);
        let candidates: Vec<Candidate> = (0..(cols - 1) * (rows - 1))
            .map(|i| Candidate {
                s: (i % (cols - 1)) as f64 + 0.5,
                t: (i / (cols - 1)) as f64 + 0.5,
                height: 1.0,
            })
            .collect();
        let surface = UniformCubicSurface::constant(cols, rows, 2.0).unwrap();
        let lp = SplineLp::new(&surface, &TrimMask::full(cols - 1, rows - 1), &candidates).unwrap();
        let error = solve(
            &lp,
            &lp.gather(&surface.coefficients),
            &IpmSettings::default(),
        )
        .unwrap_err();
        assert!(matches!(error, LpError::TooLarge { .. }), "{error}");
    }

    #[test]
    fn matches_clarabel_from_an_infeasible_start_on_a_wide_grid() {
        // cols > rows exercises the column-major band order; the zero start is
        // below every candidate.
        let (cols, rows) = (11, 5);
        let candidates: Vec<Candidate> = (0..900)
            .map(|i| {
                let (s, t) = (
                    (i * 37 % 997) as f64 * 0.01,
                    (i * 53 % 401) as f64 * 0.00997,
                );
                Candidate {
                    s,
                    t,
                    height: (s * 1.3).sin() + (t * 2.1).cos() * 0.5 + ((i * 7) % 5) as f64 * 0.05,
                }
            })
            .collect();
        let surface = UniformCubicSurface::constant(cols, rows, 0.0).unwrap();
        let lp = SplineLp::new(&surface, &TrimMask::full(cols - 1, rows - 1), &candidates).unwrap();
        assert!(lp.bandwidth <= 3 * rows + 3);
        assert_matches_clarabel(&lp, &lp.gather(&surface.coefficients));
    }
}
