//! Greedy centre reduction (Carr et al. 2001, Section 3.1, used by Zou et al.,
//! Section 5): fit on a subset of the constraints, evaluate the residual at all of
//! them, add the worst-fitted ones as centres, and refit, until every residual is
//! within tolerance or the centre budget is spent. The rounds share one growing
//! Cholesky factor ([`super::grow`]); a round it cannot solve accurately is
//! solved from scratch ([`Rbf::interpolate`]), as are the rounds after it.

use super::constraints::Constraints;
use super::eval::Rbf;
use super::grow::GrowingFit;
use super::solve::{backward_error, check_distinct, MAX_BACKWARD_ERROR};
use crate::blend::error::BlendError;
use glam::DVec3;
use rayon::prelude::*;

/// Tuning of [`fit_greedy`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RbfParams {
    /// Centre budget (the dense solve is cubic in it; a few thousand at most).
    pub max_centres: usize,
    /// Centres of the first fit.
    pub initial_centres: usize,
    /// Stop when every |s(x_j) - f_j| is at most this (world units).
    pub tolerance: f64,
    /// Refits at most.
    pub max_rounds: usize,
}

impl Default for RbfParams {
    fn default() -> Self {
        Self {
            max_centres: 1200,
            initial_centres: 128,
            tolerance: 0.0,
            max_rounds: 8,
        }
    }
}

/// How the greedy fit went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GreedyReport {
    pub rounds: usize,
    pub centres: usize,
    /// Largest |s - f| over all constraints after the last fit.
    pub max_residual: f64,
    /// Largest |s| over the on-surface constraints after the last fit.
    pub max_surface_residual: f64,
}

/// Fits `constraints` greedily (see the module docs). With `tolerance` 0 the fit
/// grows to `max_centres` (or all constraints).
pub fn fit_greedy(
    constraints: &Constraints,
    params: &RbfParams,
) -> Result<(Rbf, GreedyReport), BlendError> {
    let total = constraints.points.len();
    if total < 5 {
        return Err(BlendError::TooFewCentres {
            count: total,
            min: 5,
        });
    }
    if !(params.tolerance >= 0.0) {
        return Err(BlendError::InvalidParameter {
            name: "rbf.tolerance",
            value: params.tolerance,
            reason: "must be >= 0",
        });
    }
    let budget = params.max_centres.clamp(5, total);
    let mut chosen = vec![false; total];
    let mut centres: Vec<usize> = shuffled(total)
        .into_iter()
        .take(params.initial_centres.clamp(5, budget))
        .collect();
    centres.iter().for_each(|&i| chosen[i] = true);
    let mut report = GreedyReport::default();
    let mut solver = Solver::start(constraints, &centres);
    loop {
        let rbf = solver.solve(constraints, &centres)?;
        report.rounds += 1;
        let residual: Vec<f64> = constraints
            .points
            .par_iter()
            .with_min_len(64)
            .zip(&constraints.values)
            .map(|(&p, &f)| rbf.value(p) - f)
            .collect();
        report.centres = centres.len();
        report.max_residual = residual.iter().fold(0.0, |m, r| m.max(r.abs()));
        report.max_surface_residual = residual[..constraints.on_surface]
            .iter()
            .fold(0.0, |m, r| m.max(r.abs()));
        let room = budget - centres.len();
        if report.max_residual <= params.tolerance
            || room == 0
            || report.rounds >= params.max_rounds
        {
            return Ok((rbf, report));
        }
        let mut worst: Vec<usize> = (0..total)
            .filter(|&i| !chosen[i] && residual[i].abs() > params.tolerance)
            .collect();
        if worst.is_empty() {
            return Ok((rbf, report));
        }
        let take = room.min(centres.len().max(16)).min(worst.len());
        if take < worst.len() {
            worst.select_nth_unstable_by(take, |&a, &b| {
                residual[b].abs().total_cmp(&residual[a].abs())
            });
            worst.truncate(take);
        }
        for i in worst {
            chosen[i] = true;
            centres.push(i);
        }
    }
}

/// The rounds' solver: a growing factor holding the first `usize` centres, or
/// none once it failed.
struct Solver(Option<(GrowingFit, usize)>);

impl Solver {
    /// A growing fit in the frame of all constraints (fixed across rounds),
    /// based on four of the first `centres`.
    fn start(constraints: &Constraints, centres: &[usize]) -> Self {
        let all = &constraints.points;
        let shift = all.iter().copied().sum::<DVec3>() / all.len().max(1) as f64;
        let scale = all.iter().map(|p| p.distance(shift)).fold(0.0, f64::max);
        if !(scale > 0.0 && scale.is_finite()) {
            return Self(None);
        }
        let (pts, vals) = gather(constraints, centres);
        let Some((mut fit, base)) = GrowingFit::new(shift, scale, &pts, &vals) else {
            return Self(None);
        };
        let rest: Vec<usize> = (0..centres.len()).filter(|i| !base.contains(i)).collect();
        let pick = |v: &[f64]| rest.iter().map(|&i| v[i]).collect::<Vec<f64>>();
        let rest_points: Vec<DVec3> = rest.iter().map(|&i| pts[i]).collect();
        match fit.extend(&rest_points, &pick(&vals)) {
            Ok(()) => Self(Some((fit, centres.len()))),
            Err(_) => Self(None),
        }
    }

    /// The RBF on `centres` (the factor's centres and those appended since).
    fn solve(&mut self, constraints: &Constraints, centres: &[usize]) -> Result<Rbf, BlendError> {
        if let Some((fit, done)) = &mut self.0 {
            let (pts, vals) = gather(constraints, &centres[*done..]);
            if fit.extend(&pts, &vals).is_ok() {
                *done = centres.len();
                let rbf = fit.rbf();
                let accurate = backward_error(&rbf, &fit.values()) <= MAX_BACKWARD_ERROR;
                if accurate && check_distinct(&rbf.local_centres()).is_ok() {
                    return Ok(rbf);
                }
            }
            self.0 = None;
        }
        let (pts, vals) = gather(constraints, centres);
        Rbf::interpolate(&pts, &vals)
    }
}

/// The points and values of the constraints `indices`.
fn gather(constraints: &Constraints, indices: &[usize]) -> (Vec<DVec3>, Vec<f64>) {
    indices
        .iter()
        .map(|&i| (constraints.points[i], constraints.values[i]))
        .unzip()
}

/// `0..n` in a fixed pseudo-random order (Fisher-Yates with a PCG-style LCG), so
/// the first centres spread over the region whatever the input order.
fn shuffled(n: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    let mut state: u64 = 0x853c_49e6_748f_ea9b;
    for i in (1..n).rev() {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let j = ((state >> 33) % (i as u64 + 1)) as usize;
        order.swap(i, j);
    }
    order
}
