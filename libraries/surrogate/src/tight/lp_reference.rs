//! The exact reference: the optimal safe surface over *every* point, computed with
//! clarabel (a general interior-point solver) and cutting planes. Slow but
//! trustworthy; tests and the tightness benchmark measure the fast paths against it.
//!
//! Start from the candidate LP (one extreme point per occupied sub-cell), solve,
//! add every point of the cloud that the solution leaves on the wrong side (the
//! worst one per envelope raster square per round), and repeat until none does.
//!
//! Its only lower bound on the coefficients is one global safety floor far below
//! the data ([`super::bounds::safety_floor`], from the candidates, as in the fit).

use super::cloud_side::CloudSide;
use super::error::LpError;
use super::lp::SplineLp;
use crate::bins::bin_points;
use crate::Candidate;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
};
use rayon::prelude::*;
use shroud_geometry::spline::{knot_interval, UniformCubicSurface};

/// Cutting-plane rounds before giving up.
const MAX_ROUNDS: usize = 60;
/// Violations below this (relative to the height scale) are solver noise.
const TOLERANCE: f64 = 1e-9;
/// Raster squares per cell (per parameter) among which the worst violator of a
/// round is added.
const CUT_RASTER: usize = 8;

/// The reference optimum.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceOptimum {
    /// The optimal safe surface, in real heights (on the cloud's side).
    pub surface: UniformCubicSurface,
    /// `c . x` in the upper sense over the LP's unknowns (parameter units).
    pub objective: f64,
    pub rounds: usize,
    /// Constraint rows of the last LP.
    pub constraints: usize,
    /// Final uniform lift that made every point hold exactly (solver noise).
    pub lift: f64,
    /// The safety floor under every coefficient (upper sense).
    pub floor: f64,
    /// Coefficients the LP moves.
    pub unknowns: usize,
    /// Unknowns resting on the floor or on the ceiling: where some do, the
    /// optimum depends on where the bounds were put.
    pub at_floor: usize,
    pub at_ceiling: usize,
}

/// The optimal safe surface of `cloud` in the spline space of `start` (real
/// heights; its coefficients without objective weight or constraints are kept).
/// `sub_cells` fixes the initial candidate set, as in the fitter.
pub fn optimal_surface(
    cloud: &CloudSide,
    start: &UniformCubicSurface,
    sub_cells: usize,
) -> Result<ReferenceOptimum, LpError> {
    let points: Vec<Candidate> = cloud.constraints().collect();
    let mut included = vec![false; points.len()];
    let mut rows: Vec<Candidate> = Vec::new();
    let mut include = |indices: &[u32], rows: &mut Vec<Candidate>| {
        for &i in indices {
            if !std::mem::replace(&mut included[i as usize], true) {
                rows.push(points[i as usize]);
            }
        }
    };
    include(&candidate_indices(cloud, sub_cells), &mut rows);
    let sign = cloud.side.sign();
    let mut upper = start.clone();
    upper.coefficients.iter_mut().for_each(|c| *c *= sign);
    let base = SplineLp::new(&upper, cloud.trim, &rows)?;
    let floor = base.floors.first().copied().unwrap_or(f64::NEG_INFINITY);
    let scale = 1.0 + points.iter().fold(0.0f64, |m, c| m.max(c.height.abs()));
    for round in 1..=MAX_ROUNDS {
        let lp = base.with_constraints(&upper, cloud.trim, &rows)?;
        let x = solve_with_clarabel(&lp)?;
        lp.scatter(&x, &mut upper.coefficients);
        let before = rows.len();
        include(
            &worst_violators(&upper, &points, TOLERANCE * scale),
            &mut rows,
        );
        // No violator left, or only rows the solver already holds to its accuracy.
        if rows.len() == before {
            let lift = lift_onto(&mut upper, &lp, &points);
            let x = lp.gather(&upper.coefficients);
            let near = |v: f64, bound: f64| (v - bound).abs() <= 1e-6 * scale;
            let at_floor = x.iter().filter(|&&v| near(v, floor)).count();
            let at_ceiling = x.iter().filter(|&&v| near(v, lp.ceiling)).count();
            upper.coefficients.iter_mut().for_each(|c| *c *= sign);
            return Ok(ReferenceOptimum {
                surface: upper,
                objective: lp.objective(&x),
                rounds: round,
                constraints: lp.constraints(),
                lift,
                floor,
                unknowns: x.len(),
                at_floor,
                at_ceiling,
            });
        }
    }
    Err(LpError::CuttingPlanes(MAX_ROUNDS))
}

/// The fitter's candidate set of `cloud` (indices of the extreme point of each
/// occupied sub-cell).
pub fn candidate_indices(cloud: &CloudSide, sub_cells: usize) -> Vec<u32> {
    let binning = bin_points(
        cloud.points,
        cloud.frame,
        cloud.domain,
        &[cloud.side],
        sub_cells.max(1),
    );
    binning
        .maxima
        .first()
        .map(|m| m.occupied().map(|(_, _, i)| i).collect())
        .unwrap_or_default()
}

/// Solves `lp` with clarabel: `min c.x` s.t. `A x >= h`, `floors <= x <= ceiling`,
/// written as `[-A; -I; I] x + s = [-h; -floors; ceiling]`, `s >= 0`.
pub fn solve_with_clarabel(lp: &SplineLp) -> Result<Vec<f64>, LpError> {
    let (m, n) = (lp.constraints(), lp.unknowns());
    let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
    for cell in &lp.cells {
        for i in cell.start..cell.end {
            for (a, &w) in lp.weights[i].iter().enumerate() {
                if w != 0.0 {
                    rows.push(i);
                    cols.push(cell.unknowns[a] as usize);
                    vals.push(-w);
                }
            }
        }
    }
    for j in 0..n {
        rows.extend([m + j, m + n + j]);
        cols.extend([j, j]);
        vals.extend([-1.0, 1.0]);
    }
    let a = CscMatrix::new_from_triplets(m + 2 * n, n, rows, cols, vals);
    let p = CscMatrix::zeros((n, n));
    let mut b: Vec<f64> = lp.heights.iter().map(|h| -h).collect();
    b.extend(lp.floors.iter().map(|f| -f));
    b.extend(std::iter::repeat_n(lp.ceiling, n));
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(200)
        .tol_gap_abs(1e-11)
        .tol_gap_rel(1e-11)
        .tol_feas(1e-11)
        .build()
        .map_err(|e| LpError::Reference(format!("{e:?}")))?;
    let mut solver = DefaultSolver::new(
        &p,
        &lp.cost,
        &a,
        &b,
        &[NonnegativeConeT(m + 2 * n)],
        settings,
    )
    .map_err(|e| LpError::Reference(format!("{e:?}")))?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Ok(solver.solution.x.clone()),
        status => Err(LpError::Reference(format!(
            "clarabel stopped with status {status:?}"
        ))),
    }
}

/// Index of the worst violating point (by more than `tolerance`) of each raster square.
fn worst_violators(
    surface: &UniformCubicSurface,
    points: &[Candidate],
    tolerance: f64,
) -> Vec<u32> {
    let (cs, ct) = surface.cells();
    let slots = cs * ct * CUT_RASTER * CUT_RASTER;
    let square = |x: f64| ((x * CUT_RASTER as f64) as usize).min(CUT_RASTER - 1);
    let slot_of = |c: &Candidate| {
        let (h, u) = knot_interval(c.s, surface.cols);
        let (g, v) = knot_interval(c.t, surface.rows);
        ((g * cs + h) * CUT_RASTER + square(v)) * CUT_RASTER + square(u)
    };
    const CHUNK: usize = 16 * 1024;
    let worst = points
        .par_chunks(CHUNK)
        .enumerate()
        .fold(
            || vec![(tolerance, u32::MAX); slots],
            |mut acc, (k, chunk)| {
                for (i, c) in chunk.iter().enumerate() {
                    let violation = c.height - surface.eval(c.s, c.t);
                    let slot = &mut acc[slot_of(c)];
                    if violation > slot.0 {
                        *slot = (violation, (k * CHUNK + i) as u32);
                    }
                }
                acc
            },
        )
        .reduce(
            || vec![(tolerance, u32::MAX); slots],
            |mut a, b| {
                a.iter_mut()
                    .zip(b)
                    .filter(|(x, y)| y.0 > x.0)
                    .for_each(|(x, y)| *x = y);
                a
            },
        );
    worst
        .into_iter()
        .filter(|w| w.1 != u32::MAX)
        .map(|w| w.1)
        .collect()
}

/// Raises the unknowns uniformly until no point is below the surface; returns the lift.
fn lift_onto(surface: &mut UniformCubicSurface, lp: &SplineLp, points: &[Candidate]) -> f64 {
    let violation = points
        .par_iter()
        .map(|c| c.height - surface.eval(c.s, c.t))
        .reduce(|| 0.0, f64::max);
    if violation <= 0.0 {
        return 0.0;
    }
    let lift = violation * (1.0 + 1e-12) + f64::EPSILON * (1.0 + violation);
    let mut x = lp.gather(&surface.coefficients);
    x.iter_mut().for_each(|v| *v += lift);
    lp.scatter(&x, &mut surface.coefficients);
    lift
}

#[cfg(test)]
mod tests {
    use super::super::excess::{Envelope, DEFAULT_RASTER};
    use super::super::fixture::Fixture;
    use super::super::ipm::{solve, IpmSettings};
    use super::*;
    use crate::Tightness;

    #[test]
    fn the_reference_is_safe_and_bounded_by_the_candidate_lp_and_the_heuristic() {
        for fixture in [
            Fixture::spheres(15_000, 10, 1.0),
            Fixture::terrain(15_000, 9),
        ] {
            let cloud = fixture.cloud();
            let plain = &fixture.plain.upper.as_ref().unwrap().surface;
            let optimum = optimal_surface(&cloud, plain, fixture.options.sub_cells).unwrap();
            for c in cloud.constraints() {
                assert!(
                    optimum.surface.eval(c.s, c.t) >= c.height,
                    "a point is above the optimum"
                );
            }
            // More constraints, higher optimum: candidates <= all points <= heuristic.
            let lp = SplineLp::new(plain, cloud.trim, &fixture.candidates()).unwrap();
            let relaxed = solve(
                &lp,
                &lp.gather(&plain.coefficients),
                &IpmSettings::default(),
            )
            .unwrap();
            let heuristic = lp.objective(&lp.gather(&plain.coefficients));
            assert!(
                relaxed.objective <= optimum.objective * (1.0 + 1e-9),
                "{} > {}",
                relaxed.objective,
                optimum.objective
            );
            assert!(
                optimum.objective <= heuristic,
                "{} > {heuristic}",
                optimum.objective
            );
        }
    }

    #[test]
    fn the_optimum_has_the_least_excess_volume() {
        let fixture = Fixture::spheres(15_000, 10, 0.3);
        let cloud = fixture.cloud();
        let envelope = Envelope::new(&cloud, DEFAULT_RASTER, fixture.options.sub_cells);
        let plain = &fixture.plain.upper.as_ref().unwrap().surface;
        let optimum = envelope.excess(
            &optimal_surface(&cloud, plain, fixture.options.sub_cells)
                .unwrap()
                .surface,
        );
        assert!(optimum > 0.0);
        for tightness in [Tightness::Plain, Tightness::Lowered, Tightness::Optimal] {
            let fitted = fixture.fit(tightness);
            let excess = envelope.excess(&fitted.upper.as_ref().unwrap().surface);
            assert!(
                excess >= optimum * (1.0 - 1e-9),
                "{tightness:?}: {excess} < optimum {optimum}"
            );
        }
    }
}
