//! Section 6, reduction to gridded data: (1) every point is projected to its two
//! neighbouring parameter lines, (2) each line gets a Section 5 curve over the
//! points projected onto it, (3) each column of the resulting control grid gets a
//! Section 4 broken-line fit. The surface then lies above the bilinear interpolant
//! of each point's two projections, hence above the point.
//!
//! The lines here run along the first parameter `a` (s, or t when transposed for
//! symmetrisation); their candidates are the sub-cell maxima of the two cell rows
//! adjacent to the line, reduced to the upper hull of each knot interval.

use super::bins::SubCellMaxima;
use super::broken_line::fit_broken_line_above;
use super::error::FitError;
use super::scattered_curve::{fit_sorted_candidates_above, CurveWarmStart};
use super::upper_hull::upper_hull_into;
use crate::FitStats;
use rayon::prelude::*;

/// Warm-start state of one orientation of one side.
#[derive(Debug, Clone, Default)]
pub struct ReductionWarmStart {
    pub lines: Vec<CurveWarmStart>,
    pub columns: Vec<Vec<bool>>,
}

/// Which parameter the curves run along.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Orientation {
    /// Curves in `s` on lines `t = k` (the paper's order).
    AlongS,
    /// Curves in `t` on lines `s = j` (for symmetrisation).
    AlongT,
}

/// Grid values `c[line][j]`, which of them carry data, and the curve statistics.
struct LineFits {
    values: Vec<Vec<f64>>,
    /// `has_data[line][h]`: the line has candidates on knot interval `h`.
    has_data: Vec<Vec<bool>>,
}

/// Runs the reduction for one side. `param_of(index)` gives `(s, t)` of a point.
/// Returns row-major surface coefficients (`[k * cols + j]`) in the *upper* sense
/// (heights already multiplied by the side's sign).
pub fn fit_by_reduction(
    maxima: &SubCellMaxima,
    orientation: Orientation,
    param_of: &(dyn Fn(u32) -> (f64, f64) + Sync),
    warm: &mut ReductionWarmStart,
    max_solves: usize,
    stats: &mut FitStats,
) -> Result<Vec<f64>, FitError> {
    let (curve_len, lines) = match orientation {
        Orientation::AlongS => (maxima.cells_s + 1, maxima.cells_t + 1),
        Orientation::AlongT => (maxima.cells_t + 1, maxima.cells_s + 1),
    };
    let fits = fit_lines(
        maxima,
        orientation,
        param_of,
        warm,
        max_solves,
        curve_len,
        lines,
        stats,
    )?;
    let columns = fit_columns(&fits, warm, curve_len, lines, stats)?;
    // columns[j][k]: coefficient at curve index j, line k.
    let (cols, rows) = match orientation {
        Orientation::AlongS => (curve_len, lines),
        Orientation::AlongT => (lines, curve_len),
    };
    let mut out = vec![0.0; cols * rows];
    for (j, column) in columns.iter().enumerate() {
        for (k, &b) in column.iter().enumerate() {
            let (c, r) = match orientation {
                Orientation::AlongS => (j, k),
                Orientation::AlongT => (k, j),
            };
            out[r * cols + c] = b;
        }
    }
    Ok(out)
}

#[allow(clippy::too_many_arguments)]
fn fit_lines(
    maxima: &SubCellMaxima,
    orientation: Orientation,
    param_of: &(dyn Fn(u32) -> (f64, f64) + Sync),
    warm: &mut ReductionWarmStart,
    max_solves: usize,
    curve_len: usize,
    lines: usize,
    stats: &mut FitStats,
) -> Result<LineFits, FitError> {
    if warm.lines.len() != lines {
        warm.lines = vec![CurveWarmStart::default(); lines];
    }
    let results: Vec<_> = (0..lines)
        .into_par_iter()
        .map(|k| {
            let candidates = line_candidates(maxima, orientation, param_of, k, curve_len);
            if candidates.is_empty() {
                return Ok((None, candidates.len(), vec![false; curve_len - 1]));
            }
            let mut has = vec![false; curve_len - 1];
            for &(a, _) in &candidates {
                has[shroud_geometry::spline::knot_interval(a, curve_len).0] = true;
            }
            let warm_k = (!warm.lines[k].signs.is_empty()).then_some(&warm.lines[k]);
            let fit = fit_sorted_candidates_above(&candidates, curve_len, warm_k, max_solves)?;
            Ok((Some(fit), candidates.len(), has))
        })
        .collect::<Result<Vec<_>, FitError>>()?;
    let mut values: Vec<Option<Vec<f64>>> = Vec::with_capacity(lines);
    let mut has_data = Vec::with_capacity(lines);
    for (k, (fit, count, has)) in results.into_iter().enumerate() {
        stats.candidates += count as u64;
        has_data.push(has);
        match fit {
            Some(f) => {
                stats.curve_solves.add(f.solves);
                stats.reselections += f.reselections as u64;
                stats.raised_intervals += f.raised_intervals as u64;
                values.push(Some(f.curve.coefficients));
                warm.lines[k] = f.warm;
            }
            None => values.push(None),
        }
    }
    Ok(LineFits {
        values: fill_empty_lines(values)?,
        has_data,
    })
}

/// Lines without any data copy their nearest neighbour with data; every one of
/// their grid values is free in the column step, so the copy only shapes trimmed
/// regions.
fn fill_empty_lines(values: Vec<Option<Vec<f64>>>) -> Result<Vec<Vec<f64>>, FitError> {
    let with_data: Vec<usize> = (0..values.len()).filter(|&k| values[k].is_some()).collect();
    if with_data.is_empty() {
        return Err(FitError::NoSamples);
    }
    (0..values.len())
        .map(|k| {
            let nearest = with_data
                .iter()
                .min_by_key(|&&d| d.abs_diff(k))
                .copied()
                .unwrap_or(k);
            values[nearest].clone().ok_or(FitError::NoSamples)
        })
        .collect()
}

/// Candidates of line `k`: per knot interval and sub-bin of the curve parameter,
/// the highest point of the two cell rows touching the line, then the upper hull
/// of each interval. Sorted by the curve parameter.
fn line_candidates(
    m: &SubCellMaxima,
    orientation: Orientation,
    param_of: &(dyn Fn(u32) -> (f64, f64) + Sync),
    k: usize,
    curve_len: usize,
) -> Vec<(f64, f64)> {
    let (sub_a, sub_b, cross_cells) = match orientation {
        Orientation::AlongS => (m.bs, m.bt, m.cells_t),
        Orientation::AlongT => (m.bt, m.bs, m.cells_s),
    };
    let rows: Vec<usize> = [k.checked_sub(1), (k < cross_cells).then_some(k)]
        .into_iter()
        .flatten()
        .collect();
    let mut out = Vec::new();
    let mut interval = Vec::with_capacity(sub_a);
    let mut hull = Vec::new();
    for h in 0..curve_len - 1 {
        interval.clear();
        for qa in 0..sub_a {
            let mut best: Option<(f64, u32)> = None;
            for &g in &rows {
                for qb in 0..sub_b {
                    let slot = match orientation {
                        Orientation::AlongS => m.slot(h, g, qa, qb),
                        Orientation::AlongT => m.slot(g, h, qb, qa),
                    };
                    let y = m.height[slot];
                    if y > f64::NEG_INFINITY && best.is_none_or(|b| y > b.0) {
                        best = Some((y, m.index[slot]));
                    }
                }
            }
            if let Some((y, idx)) = best {
                let (s, t) = param_of(idx);
                let a = match orientation {
                    Orientation::AlongS => s,
                    Orientation::AlongT => t,
                };
                interval.push((a, y));
            }
        }
        // Sub-bins are ordered, but a point on a sub-bin boundary may tie.
        interval.sort_by(|p, q| p.0.total_cmp(&q.0));
        upper_hull_into(&interval, &mut hull);
        out.extend_from_slice(&hull);
    }
    out
}

/// Step 3: one broken-line fit per column of grid values. A grid value is free when
/// its line has no data under the column's B-spline (intervals `j-2 ..= j+1`), so no
/// point's safety depends on it (Figure 7, left).
fn fit_columns(
    fits: &LineFits,
    warm: &mut ReductionWarmStart,
    curve_len: usize,
    lines: usize,
    stats: &mut FitStats,
) -> Result<Vec<Vec<f64>>, FitError> {
    if warm.columns.len() != curve_len {
        warm.columns = vec![Vec::new(); curve_len];
    }
    let mut out = Vec::with_capacity(curve_len);
    for j in 0..curve_len {
        let values: Vec<f64> = (0..lines).map(|k| fits.values[k][j]).collect();
        let lo = j.saturating_sub(2);
        let hi = (j + 1).min(curve_len - 2);
        let free: Vec<bool> = (0..lines)
            .map(|k| !(lo..=hi).any(|h| fits.has_data[k][h]))
            .collect();
        if free.iter().all(|&f| f) {
            out.push(values);
            continue;
        }
        let warm_j = (warm.columns[j].len() == lines).then_some(warm.columns[j].as_slice());
        let fit = fit_broken_line_above(&values, &free, warm_j)?;
        stats.column_solves.add(fit.solves);
        warm.columns[j] = fit.signs;
        out.push(fit.curve.coefficients);
    }
    Ok(out)
}
