//! The default tightening post-pass: lowers each coefficient as far as the
//! candidate constraints allow (coordinate descent on the linear program
//! "minimise the surface's integral subject to every candidate lying below it",
//! whose exact optimum is `crate::tight`).
//!
//! Lowering coefficient `b_jk` by `δ` lowers `f` at a candidate by `δ W_jk(s, t)`
//! (its B-spline weight), so the largest safe move is `min gap_i / W_jk(p_i)` over
//! the candidates in its support. Points that are not candidates are caught by
//! certification, which only ever moves the surface away from the cloud.
//!
//! The constraint matrix is stored by columns (each coefficient with its
//! candidates and weights), so a sweep costs one pass over its ~16 non-zeros per
//! candidate: well under a millisecond at 20 x 20.

use super::candidates::Candidate;
use super::trim::TrimMask;
use crate::bins::MAX_SUB_CELLS;
use crate::exact_weights::exact_basis_weights;
use shroud_geometry::spline::{basis_weights, knot_interval, UniformCubicSurface};

/// Fraction of the largest safe move taken in all but the last sweep. A full step
/// makes one candidate tight, and a tight candidate blocks all 16 coefficients
/// around it (the usual trap of coordinate descent on an LP); a partial step
/// leaves room for the neighbours.
const STEP: f64 = 0.5;

/// Coordinate descent over the coefficients (`sweeps` passes). `surface` is in the
/// upper sense; each candidate represents one of `sub x sub` sub-cells per cell.
/// Returns the number of coefficient moves.
pub fn lower_onto_candidates(
    surface: &mut UniformCubicSurface,
    candidates: &[Candidate],
    trim: &TrimMask,
    sub: usize,
    sweeps: usize,
) -> u64 {
    let mut buffers = LoweringBuffers::default();
    lower_reusing(&mut buffers, surface, candidates, trim, sub, sweeps)
}

/// The constraint matrix's storage, kept by a fitter from one frame to the
/// next: a stream's matrices have about the same size, so a warm fit writes
/// its matrix over the last one instead of allocating and clearing a new one
/// (about 2 MB at 300K points, 20 x 20).
#[derive(Default)]
pub(crate) struct LoweringBuffers {
    start: Vec<usize>,
    entries: Vec<Entry>,
}

/// A copy starts with empty storage: what a buffer holds never changes a result.
impl Clone for LoweringBuffers {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for LoweringBuffers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "LoweringBuffers({} entries)", self.entries.len())
    }
}

/// [`lower_onto_candidates`] in `buffers`, which it leaves holding this matrix.
/// `sub` is clamped to `1..=MAX_SUB_CELLS` (the reciprocal table grows as its
/// square); fewer, larger sub-cells only make the moves more cautious.
pub(crate) fn lower_reusing(
    buffers: &mut LoweringBuffers,
    surface: &mut UniformCubicSurface,
    candidates: &[Candidate],
    trim: &TrimMask,
    sub: usize,
    sweeps: usize,
) -> u64 {
    let storage = std::mem::take(buffers);
    let sub = sub.clamp(1, MAX_SUB_CELLS);
    let mut lowering = Lowering::new(storage, surface, candidates, trim, sub);
    let moves = lowering.descend(surface, sweeps);
    *buffers = lowering.into_buffers();
    moves
}

impl Lowering {
    /// `sweeps` passes of coordinate descent; returns the moves.
    fn descend(&mut self, surface: &mut UniformCubicSurface, sweeps: usize) -> u64 {
        let mut moves = 0;
        for sweep in 0..sweeps {
            let step = if sweep + 1 == sweeps { 1.0 } else { STEP };
            let moved = self.sweep(surface, step);
            moves += moved;
            if moved == 0 {
                break;
            }
        }
        moves
    }

    fn into_buffers(self) -> LoweringBuffers {
        LoweringBuffers {
            start: self.start,
            entries: self.entries,
        }
    }
}

/// One non-zero of the constraint matrix: candidate `row`, the coefficient's
/// weight at the candidate, and its largest weight over the candidate's sub-cell.
#[derive(Debug, Clone, Copy)]
struct Entry {
    row: u32,
    weight: f64,
    /// Reciprocal of the largest weight over the sub-cell: the candidate stands for
    /// every point of its sub-cell, and a point with a larger weight than the
    /// candidate's would drop further than it does. (That weight is at least
    /// `(1/sub)^3 / 6`, so the reciprocal is finite.)
    inverse_bound: f64,
}

/// Every [`Entry::inverse_bound`] a fill can need, computed once: it depends only
/// on the candidate's sub-cell and on whether its cell is at an end of the grid
/// (where [`merged`] folds weights together), and a division per entry would cost
/// more than the rest of filling it.
struct InverseBounds {
    /// Keys per axis: four edge cases of each of the `sub` sub-cells.
    keys: usize,
    /// At `key_s * keys + key_t`, slot `4 q + r`: `1 / max(mu_q mv_r, 1e-12)`.
    table: Vec<[f64; 16]>,
}

impl InverseBounds {
    fn new(sub: usize) -> Self {
        let keys = 4 * sub;
        // Largest weights over each sub-cell, merged as each edge case merges them.
        let largest: Vec<[f64; 4]> = (0..keys)
            .map(|key| {
                let q = key / 4;
                let w = weights_max(q as f64 / sub as f64, (q + 1) as f64 / sub as f64);
                merged_at_ends(w, key & 1 != 0, key & 2 != 0)
            })
            .collect();
        let table = (0..keys * keys)
            .map(|k| {
                let (mu, mv) = (&largest[k / keys], &largest[k % keys]);
                std::array::from_fn(|slot| 1.0 / (mu[slot / 4] * mv[slot % 4]).max(1e-12))
            })
            .collect();
        Self { keys, table }
    }

    /// The bounds of candidate `l`'s 16 slots.
    #[inline]
    fn of(&self, l: &Located, cols: usize, rows: usize) -> &[f64; 16] {
        let key = |q: usize, cell: usize, len: usize| {
            4 * q + usize::from(cell == 0) + 2 * usize::from(cell + 3 > len)
        };
        &self.table[key(l.qu, l.h, cols) * self.keys + key(l.qv, l.g, rows)]
    }
}

/// The candidate constraints by coefficient, with the current gaps.
struct Lowering {
    /// `entries[start[i]..start[i + 1]]` belong to coefficient `i` (row-major).
    start: Vec<usize>,
    entries: Vec<Entry>,
    /// `f(p_i) - h_i >= 0` per candidate.
    gap: Vec<f64>,
    /// Lowest value each coefficient may take (see `crate::tight::bounds::floors_of`):
    /// the lowest candidate in the kept cells it acts on; `+inf` when there is
    /// none (no objective weight, or no data to lower it onto: it is not moved).
    floor: Vec<f64>,
}

impl Lowering {
    /// Fills the columns (each lists its candidates in increasing order), the
    /// gaps and the floors, one candidate at a time, in `storage`.
    fn new(
        storage: LoweringBuffers,
        surface: &UniformCubicSurface,
        candidates: &[Candidate],
        trim: &TrimMask,
        sub: usize,
    ) -> Self {
        let (cols, rows) = (surface.cols, surface.rows);
        let bounds = InverseBounds::new(sub);
        let located: Vec<Located> = candidates
            .iter()
            .map(|c| Located::new(c, cols, rows, sub))
            .collect();
        let LoweringBuffers {
            mut start,
            mut entries,
        } = storage;
        column_starts(&located, cols, rows, &mut start);
        // Every entry is written below, so those left from the last matrix
        // need no clearing.
        let blank = Entry {
            row: 0,
            weight: 0.0,
            inverse_bound: 0.0,
        };
        let total = start[cols * rows];
        entries.truncate(total);
        entries.resize(total, blank);
        // A much smaller matrix than the last gives the rest back.
        if entries.capacity() > 2 * total {
            entries.shrink_to(total);
        }
        let mut gap = Vec::with_capacity(candidates.len());
        let mut lowest = vec![f64::INFINITY; (cols - 1) * (rows - 1)];
        let mut next = start.clone();
        for (row, (l, c)) in (0..).zip(located.iter().zip(candidates)) {
            let (wu, wv) = (
                merged(exact_basis_weights(l.u), l.h, cols),
                merged(exact_basis_weights(l.v), l.g, rows),
            );
            let inverse = bounds.of(l, cols, rows);
            let mut value = 0.0;
            l.for_each_slot(cols, rows, |i, q, r| {
                let weight = wu[q] * wv[r];
                entries[next[i]] = Entry {
                    row,
                    weight,
                    inverse_bound: inverse[4 * q + r],
                };
                next[i] += 1;
                value += weight * surface.coefficients[i];
            });
            gap.push(value - c.height);
            if trim.cell_kept(l.h, l.g) {
                let cell = &mut lowest[l.g * (cols - 1) + l.h];
                *cell = cell.min(c.height);
            }
        }
        Self {
            start,
            entries,
            gap,
            floor: floors_of_cells(cols, rows, &lowest),
        }
    }

    /// One pass over the coefficients with step fraction `step`; returns the moves.
    fn sweep(&mut self, surface: &mut UniformCubicSurface, step: f64) -> u64 {
        let mut moves = 0;
        for i in 0..surface.coefficients.len() {
            let column = &self.entries[self.start[i]..self.start[i + 1]];
            let room = surface.coefficients[i] - self.floor[i];
            // Not finite: the coefficient acts on no kept cell.
            if !(room > 0.0 && room.is_finite()) {
                continue;
            }
            let delta = step * largest_safe_move(column, &self.gap, room);
            if delta > 0.0 {
                surface.coefficients[i] -= delta;
                column
                    .iter()
                    .for_each(|e| self.gap[e.row as usize] -= delta * e.weight);
                moves += 1;
            }
        }
        moves
    }
}

/// `min(room, min_i gap_i / bound_i)` over a column (`<= 0` when a candidate is
/// already tight or short). Four running minima break the dependency chain of a
/// single one, which would otherwise bound the whole pass by its latency.
#[inline]
fn largest_safe_move(column: &[Entry], gap: &[f64], room: f64) -> f64 {
    let mut lows = [room; 4];
    let chunks = column.chunks_exact(4);
    for e in chunks.remainder() {
        lows[0] = lows[0].min(gap[e.row as usize] * e.inverse_bound);
    }
    for chunk in chunks {
        for (low, e) in lows.iter_mut().zip(chunk) {
            let v = gap[e.row as usize] * e.inverse_bound;
            if v < *low {
                *low = v;
            }
        }
    }
    lows[0].min(lows[1]).min(lows[2].min(lows[3]))
}

/// `start[i]..start[i + 1]`: where coefficient `i`'s entries go (a counting pass).
fn column_starts(located: &[Located], cols: usize, rows: usize, start: &mut Vec<usize>) {
    start.clear();
    start.resize(cols * rows + 1, 0);
    for l in located {
        l.for_each_slot(cols, rows, |i, _, _| start[i + 1] += 1);
    }
    for i in 0..cols * rows {
        start[i + 1] += start[i];
    }
}

/// Where a candidate lies: its cell, local parameters and sub-cell.
struct Located {
    h: usize,
    g: usize,
    u: f64,
    v: f64,
    qu: usize,
    qv: usize,
}

impl Located {
    fn new(c: &Candidate, cols: usize, rows: usize, sub: usize) -> Self {
        let (h, u) = knot_interval(c.s, cols);
        let (g, v) = knot_interval(c.t, rows);
        let q = |x: f64| ((x * sub as f64) as usize).min(sub - 1);
        Self {
            h,
            g,
            u,
            v,
            qu: q(u),
            qv: q(v),
        }
    }

    /// Calls `f(coefficient, q, r)` for each distinct coefficient acting on the
    /// cell: slots that repeat an end coefficient are skipped, their weight
    /// being merged into the first slot (see [`merged`]).
    #[inline]
    fn for_each_slot(&self, cols: usize, rows: usize, f: impl FnMut(usize, usize, usize)) {
        for_each_slot_of_cell(self.h, self.g, cols, rows, f);
    }
}

/// Calls `f(coefficient, q, r)` for each distinct coefficient acting on cell
/// `(h, g)` (see [`Located::for_each_slot`]).
#[inline]
fn for_each_slot_of_cell(
    h: usize,
    g: usize,
    cols: usize,
    rows: usize,
    mut f: impl FnMut(usize, usize, usize),
) {
    let (q0, q1) = slot_range(h, cols);
    let (r0, r1) = slot_range(g, rows);
    if (q0, q1, r0, r1) == (0, 4, 0, 4) {
        // Away from the ends (almost every cell): fixed bounds, which the
        // compiler unrolls.
        let first = (g - 1) * cols + h - 1;
        for r in 0..4 {
            for q in 0..4 {
                f(first + r * cols + q, q, r);
            }
        }
        return;
    }
    for r in r0..r1 {
        for q in q0..q1 {
            f((g + r - 1) * cols + h + q - 1, q, r);
        }
    }
}

/// The lowest value each coefficient may take (`crate::tight::bounds::floors_of`)
/// from the lowest constraint of each cell (row-major, `+inf` for a cell that is
/// trimmed or has none): the lowest of the cells it acts on.
pub(crate) fn floors_of_cells(cols: usize, rows: usize, lowest: &[f64]) -> Vec<f64> {
    let mut floors = vec![f64::INFINITY; cols * rows];
    let cells = lowest.iter().enumerate().filter(|(_, l)| l.is_finite());
    for (cell, &low) in cells {
        let (h, g) = (cell % (cols - 1), cell / (cols - 1));
        for_each_slot_of_cell(h, g, cols, rows, |i, _, _| floors[i] = floors[i].min(low));
    }
    floors
}

/// Slots `[first, end)` of interval `cell` that address distinct coefficients.
#[inline]
fn slot_range(cell: usize, len: usize) -> (usize, usize) {
    (usize::from(cell == 0), if cell + 3 > len { 3 } else { 4 })
}

/// Weights of the four slots of interval `cell` with those of slots that repeat an
/// end coefficient (`b_{-1} = b_0`, `b_n = b_{n-1}`) moved onto its first slot.
fn merged(w: [f64; 4], cell: usize, len: usize) -> [f64; 4] {
    merged_at_ends(w, cell == 0, cell + 3 > len)
}

/// [`merged`] for a cell that is (or is not) the first and the last.
fn merged_at_ends(mut w: [f64; 4], first: bool, last: bool) -> [f64; 4] {
    if first {
        w[1] += w[0];
        w[0] = 0.0;
    }
    if last {
        // Slot 3 addresses b_{cell+2} = b_{len-1} = slot 2's coefficient.
        w[2] += w[3];
        w[3] = 0.0;
    }
    w
}

/// Largest of the four basis weights over `[a, b]` (sampled at the ends and middle;
/// each weight is a cubic with at most one interior maximum near the middle).
fn weights_max(a: f64, b: f64) -> [f64; 4] {
    let (x, y, z) = (
        basis_weights(a),
        basis_weights(0.5 * (a + b)),
        basis_weights(b),
    );
    [0, 1, 2, 3].map(|q| x[q].max(y[q]).max(z[q]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table holds, bit for bit, the reciprocal a division per candidate
    /// and slot would give, in every cell (the ends included) of small grids.
    #[test]
    fn inverse_bounds_are_the_divisions_they_replace() {
        for sub in [1, 3, 4] {
            let bounds = InverseBounds::new(sub);
            for (cols, rows) in [(2, 2), (3, 5), (4, 4), (7, 6)] {
                for (h, g) in (0..rows - 1).flat_map(|g| (0..cols - 1).map(move |h| (h, g))) {
                    for (qu, qv) in (0..sub).flat_map(|a| (0..sub).map(move |b| (a, b))) {
                        let l = Located {
                            h,
                            g,
                            u: 0.0,
                            v: 0.0,
                            qu,
                            qv,
                        };
                        let largest = |q: usize| {
                            weights_max(q as f64 / sub as f64, (q + 1) as f64 / sub as f64)
                        };
                        let mu = merged(largest(qu), h, cols);
                        let mv = merged(largest(qv), g, rows);
                        let table = bounds.of(&l, cols, rows);
                        for (q, r) in (0..4).flat_map(|q| (0..4).map(move |r| (q, r))) {
                            let direct = 1.0 / (mu[q] * mv[r]).max(1e-12);
                            assert_eq!(table[4 * q + r].to_bits(), direct.to_bits());
                        }
                    }
                }
            }
        }
    }

    fn candidates() -> Vec<Candidate> {
        (0..400)
            .map(|i| {
                let (s, t) = ((i % 20) as f64 * 0.25, (i / 20) as f64 * 0.2);
                Candidate {
                    s,
                    t,
                    height: (s * 0.9).sin() + 0.3 * t,
                }
            })
            .collect()
    }

    #[test]
    fn lowers_a_high_surface_onto_its_candidates_without_crossing_them() {
        let candidates = candidates();
        let mut surf = UniformCubicSurface::constant(6, 5, 10.0).unwrap();
        let moves = lower_onto_candidates(&mut surf, &candidates, &TrimMask::full(5, 4), 1, 6);
        assert!(moves > 0);
        let gaps: Vec<f64> = candidates
            .iter()
            .map(|c| surf.eval(c.s, c.t) - c.height)
            .collect();
        assert!(gaps.iter().all(|&g| g >= -1e-9));
        let mean = gaps.iter().sum::<f64>() / gaps.len() as f64;
        assert!(mean < 1.0, "mean gap {mean}");
    }

    #[test]
    fn never_lowers_a_coefficient_below_the_lowest_candidate_it_acts_on() {
        let candidates = candidates();
        let lowest = candidates
            .iter()
            .fold(f64::INFINITY, |m, c| m.min(c.height));
        let mut surf = UniformCubicSurface::constant(6, 5, 10.0).unwrap();
        lower_onto_candidates(&mut surf, &candidates, &TrimMask::full(5, 4), 1, 50);
        assert!(surf.coefficients.iter().all(|&b| b >= lowest));
    }

    /// A fitter's buffers hold the last frame's matrix; lowering over them
    /// gives the same surface as over fresh storage, whether the last matrix
    /// was larger or smaller.
    #[test]
    fn reused_buffers_give_the_same_lowering() {
        let all = candidates();
        let fresh = |c: &[Candidate]| {
            let mut surf = UniformCubicSurface::constant(6, 5, 10.0).unwrap();
            let moves = lower_onto_candidates(&mut surf, c, &TrimMask::full(5, 4), 2, 4);
            (surf, moves)
        };
        let mut buffers = LoweringBuffers::default();
        for c in [&all[..], &all[..50], &all[..], &all[..300]] {
            let mut surf = UniformCubicSurface::constant(6, 5, 10.0).unwrap();
            let moves = lower_reusing(&mut buffers, &mut surf, c, &TrimMask::full(5, 4), 2, 4);
            assert_eq!((surf, moves), fresh(c));
        }
    }

    #[test]
    fn leaves_coefficients_of_trimmed_cells_alone() {
        let candidates: Vec<Candidate> = candidates().into_iter().filter(|c| c.s < 1.0).collect();
        let mut trim = TrimMask::empty(5, 4);
        (0..4).for_each(|g| trim.bits[g * 5] = crate::trim::ALL);
        let mut surf = UniformCubicSurface::constant(6, 5, 10.0).unwrap();
        lower_onto_candidates(&mut surf, &candidates, &trim, 1, 6);
        for k in 0..5 {
            for j in 0..6 {
                assert_eq!(surf.coefficients[k * 6 + j] < 10.0, j <= 2, "({j}, {k})");
            }
        }
    }
}
