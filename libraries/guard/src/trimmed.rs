//! The trimmed triangles of an envelope, laid out once per surrogate for the
//! unseen search (`guard::unseen`): per row of cells, the cells that have a
//! trimmed triangle and those triangles' frame corners, and per cell a lower
//! bound on the distance from anywhere in it to the nearest such triangle,
//! so that a shape no trimmed triangle can come near skips the search.
//!
//! Why it is a lower bound. A trimmed triangle of cell `(h', g')` lies in
//! that cell's closed rectangle, so a point of cell `(h, g)` is at least the
//! gap between the two rectangles away from it: `max(0, |h - h'| - 1)` steps
//! along `u` and `max(0, |g - g'| - 1)` along `v`, combined by Pythagoras.
//! Distances computed in floating point differ from the exact ones by a few
//! ulps of the coordinates, far less than the [`ROUNDING_REL`] allowance the
//! bound is reduced by, so a cell or shape skipped by it could not have
//! lowered the computed minimum: the search's answer is bit for bit the
//! exhaustive one.

use glam::DVec2;
use shroud_surrogate::trim::{ALL, BOTTOM, LEFT, RIGHT, TOP};
use shroud_surrogate::{Domain, TrimMask};

/// A point of the `(u, v)` plane.
pub(crate) type P2 = DVec2;

/// The four triangles of a cell in local coordinates: the edge, then the
/// centre (see `surrogate::trim`).
pub(crate) const TRIANGLES: [(u8, [P2; 3]); 4] = [
    (
        BOTTOM,
        [P2::new(0.0, 0.0), P2::new(1.0, 0.0), P2::new(0.5, 0.5)],
    ),
    (
        RIGHT,
        [P2::new(1.0, 0.0), P2::new(1.0, 1.0), P2::new(0.5, 0.5)],
    ),
    (
        TOP,
        [P2::new(1.0, 1.0), P2::new(0.0, 1.0), P2::new(0.5, 0.5)],
    ),
    (
        LEFT,
        [P2::new(0.0, 1.0), P2::new(0.0, 0.0), P2::new(0.5, 0.5)],
    ),
];

/// Rounding allowance of every bound here, relative to the largest
/// coordinate of the domain (1000 times the envelope's own margin).
pub(crate) const ROUNDING_REL: f64 = 1e-9;

/// The trimmed triangles of one envelope and the bounds.
#[derive(Debug, Clone)]
pub(crate) struct Trimmed {
    cells_s: usize,
    /// Per row `g` and column `h` in `0..=cells_s`, at `g * (cells_s + 1) +
    /// h`: the index in `cells` of the row's first cell at or right of `h`.
    first_at: Vec<usize>,
    /// Every cell with a trimmed triangle, row by row, by column.
    cells: Vec<TrimmedCell>,
    /// Every trimmed triangle, cell by cell.
    triangles: Vec<TrimmedTriangle>,
    /// Row-major `g * cells_s + h`: the rectangle gap to the nearest cell
    /// with a trimmed triangle (0 for such a cell, infinite without any).
    gaps: Vec<f64>,
    /// What every bound is reduced by against rounding (m).
    pub(crate) rounding: f64,
}

/// A trimmed triangle: its frame corners, as [`triangle_corners`] gives
/// them, and their bounding box.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TrimmedTriangle {
    pub corners: [P2; 3],
    pub lo: P2,
    pub hi: P2,
}

/// A cell with trimmed triangles: its column, the bounding box of those
/// triangles, and their range in [`Trimmed::triangles`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct TrimmedCell {
    pub h: usize,
    pub lo: P2,
    pub hi: P2,
    triangles: [usize; 2],
}

/// Whether cell bits leave a triangle trimmed away.
#[inline]
pub(crate) fn has_trimmed(bits: u8) -> bool {
    bits & ALL != ALL
}

impl Trimmed {
    /// The trimmed triangles of `trim` over `domain`'s cells (`cells_s` x
    /// `cells_t`) and their bounds.
    pub(crate) fn new(trim: &TrimMask, domain: &Domain, cells: (usize, usize)) -> Self {
        let u_max = domain.u_min + cells.0 as f64 * domain.u_step;
        let v_max = domain.v_min + cells.1 as f64 * domain.v_step;
        let scale = [domain.u_min, domain.v_min, u_max, v_max]
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let mut trimmed = Self {
            cells_s: cells.0,
            first_at: Vec::with_capacity((cells.0 + 1) * cells.1),
            cells: Vec::new(),
            triangles: Vec::new(),
            gaps: gaps_to_trimmed(trim, [domain.u_step, domain.v_step], cells),
            rounding: ROUNDING_REL * (1.0 + scale),
        };
        for g in 0..cells.1 {
            for h in 0..cells.0 {
                trimmed.first_at.push(trimmed.cells.len());
                trimmed.push_cell(domain, h, g, trim.cell_bits(h, g));
            }
            trimmed.first_at.push(trimmed.cells.len());
        }
        trimmed
    }

    /// Lays out the trimmed triangles of cell `(h, g)`, if it has any.
    fn push_cell(&mut self, domain: &Domain, h: usize, g: usize, kept: u8) {
        if !has_trimmed(kept) {
            return;
        }
        let start = self.triangles.len();
        self.triangles.extend(
            TRIANGLES
                .iter()
                .filter(|(bit, _)| kept & bit == 0)
                .map(|(_, t)| {
                    let corners = triangle_corners(domain, h, g, t);
                    let lo = corners[0].min(corners[1]).min(corners[2]);
                    let hi = corners[0].max(corners[1]).max(corners[2]);
                    TrimmedTriangle { corners, lo, hi }
                }),
        );
        let mine = &self.triangles[start..];
        self.cells.push(TrimmedCell {
            h,
            lo: mine.iter().fold(P2::INFINITY, |m, t| m.min(t.lo)),
            hi: mine.iter().fold(P2::NEG_INFINITY, |m, t| m.max(t.hi)),
            triangles: [start, self.triangles.len()],
        });
    }

    /// Lower bound on the computed distance from any point of the cells
    /// `h[0]..=h[1]` x `g[0]..=g[1]` (and within rounding of them) to a
    /// trimmed triangle.
    pub(crate) fn lower_bound(&self, h: [usize; 2], g: [usize; 2]) -> f64 {
        // Half-open ranges: an inclusive one checks more on every step.
        let nearest = (g[0]..g[1] + 1)
            .flat_map(|g| &self.gaps[g * self.cells_s + h[0]..g * self.cells_s + h[1] + 1])
            .fold(f64::INFINITY, |m, &x| m.min(x));
        nearest - self.rounding
    }
}

impl Trimmed {
    /// The cells of row `g` whose column is in `h[0]..=h[1]` and that have
    /// a trimmed triangle, with those triangles: nearest to column `from`
    /// first.
    pub(crate) fn row(
        &self,
        g: usize,
        h: [usize; 2],
        from: usize,
    ) -> impl Iterator<Item = (&TrimmedCell, &[TrimmedTriangle])> {
        let at = |column: usize| self.first_at[g * (self.cells_s + 1) + column];
        let from = from.clamp(h[0], h[1]);
        let (first, last) = (at(h[0]), at(h[1] + 1));
        let cells = &self.cells[first..last];
        // `cells[..left]` lie left of `from` and `cells[right..]` right of
        // it, both still to come.
        let split = at(from) - first;
        let (mut left, mut right) = (split, split);
        std::iter::from_fn(move || {
            let on_left = left.checked_sub(1).map(|l| from - cells[l].h);
            let on_right = cells.get(right).map(|c| c.h - from);
            let k = match (on_left, on_right) {
                (Some(l), Some(r)) if r <= l => {
                    right += 1;
                    right - 1
                }
                (Some(_), _) => {
                    left -= 1;
                    left
                }
                (None, Some(_)) => {
                    right += 1;
                    right - 1
                }
                (None, None) => return None,
            };
            let [start, end] = cells[k].triangles;
            Some((&cells[k], &self.triangles[start..end]))
        })
    }
}

/// Euclidean gap between the rectangles `u` x `v` and `lo..=hi` (0 when
/// they meet).
#[inline]
pub(crate) fn rect_gap(u: [f64; 2], v: [f64; 2], lo: P2, hi: P2) -> f64 {
    let du = (lo[0] - u[1]).max(u[0] - hi[0]).max(0.0);
    let dv = (lo[1] - v[1]).max(v[0] - hi[1]).max(0.0);
    (du * du + dv * dv).sqrt()
}

/// Frame corners of a triangle of cell `(h, g)` given in local coordinates.
pub(crate) fn triangle_corners(domain: &Domain, h: usize, g: usize, local: &[P2; 3]) -> [P2; 3] {
    local.map(|p| {
        P2::new(
            domain.u_min + (h as f64 + p[0]) * domain.u_step,
            domain.v_min + (g as f64 + p[1]) * domain.v_step,
        )
    })
}

/// Rows searched on each side of a cell for the nearest trimmed cell. Beyond
/// them the gap is bounded below by the rows alone, which keeps building an
/// envelope linear in its cells (a 1024 x 1024 grid would otherwise cost
/// 10^9 steps per surrogate) at the price of a looser bound for cells more
/// than this many rows from any trimmed one.
const ROWS_SEARCHED: usize = 32;

/// Per cell, row-major, a lower bound on the rectangle gap to the nearest
/// cell with a trimmed triangle: per row the nearest such column, then the
/// nearest over the rows within [`ROWS_SEARCHED`]; exact when that cell lies
/// within them, else the gap those rows alone leave.
fn gaps_to_trimmed(
    trim: &TrimMask,
    steps: [f64; 2],
    (cells_s, cells_t): (usize, usize),
) -> Vec<f64> {
    let rows: Vec<Vec<Option<usize>>> = (0..cells_t)
        .map(|g| columns_to_trimmed((0..cells_s).map(|h| trim.cell_bits(h, g))))
        .collect();
    let beyond = cells_apart(ROWS_SEARCHED + 1) * steps[1];
    let nearest = |h: usize, g: usize| {
        let near = g.saturating_sub(ROWS_SEARCHED)..(g + ROWS_SEARCHED + 1).min(cells_t);
        let nearest2 = rows[near.clone()]
            .iter()
            .zip(near)
            .filter_map(|(row, other)| {
                let du = cells_apart(row[h]?) * steps[0];
                let dv = cells_apart(g.abs_diff(other)) * steps[1];
                Some(du * du + dv * dv)
            })
            .fold(f64::INFINITY, f64::min);
        nearest2.sqrt().min(beyond)
    };
    (0..cells_t)
        .flat_map(|g| (0..cells_s).map(move |h| (h, g)))
        .map(|(h, g)| nearest(h, g))
        .collect()
}

/// Rectangle gap, in steps, between cells `k` apart (neighbours touch).
fn cells_apart(k: usize) -> f64 {
    k.saturating_sub(1) as f64
}

/// Per cell of a row, how many cells away the nearest cell with a trimmed
/// triangle is (`None` when the row has none): a sweep each way.
fn columns_to_trimmed(bits: impl Iterator<Item = u8>) -> Vec<Option<usize>> {
    let mut last: Option<usize> = None;
    let mut out: Vec<Option<usize>> = bits
        .enumerate()
        .map(|(h, b)| {
            if has_trimmed(b) {
                last = Some(h);
            }
            last.map(|l| h - l)
        })
        .collect();
    let mut next: Option<usize> = None;
    for h in (0..out.len()).rev() {
        if out[h] == Some(0) {
            next = Some(h);
        }
        if let Some(n) = next {
            out[h] = Some(out[h].map_or(n - h, |d| d.min(n - h)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Every cell's gap is at most the true gap to the nearest trimmed cell
    /// (a lower bound, so a skip it allows is sound), and equal to it when
    /// that cell is within the rows searched.
    #[test]
    fn gaps_bound_the_true_gap_and_match_it_nearby() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let (cells_s, cells_t) = (7, 3 * ROWS_SEARCHED);
        let steps = [0.3, 0.2];
        for _ in 0..20 {
            let mut trim = TrimMask::full(cells_s, cells_t);
            let trimmed: Vec<(usize, usize)> = (0..rng.random_range(1..4))
                .map(|_| (rng.random_range(0..cells_s), rng.random_range(0..cells_t)))
                .collect();
            for &(h, g) in &trimmed {
                trim.bits[g * cells_s + h] = 0;
            }
            let gaps = gaps_to_trimmed(&trim, steps, (cells_s, cells_t));
            for g in 0..cells_t {
                for h in 0..cells_s {
                    let (truth, rows_away) = trimmed
                        .iter()
                        .map(|&(h2, g2)| {
                            let du = cells_apart(h.abs_diff(h2)) * steps[0];
                            let dv = cells_apart(g.abs_diff(g2)) * steps[1];
                            ((du * du + dv * dv).sqrt(), g.abs_diff(g2))
                        })
                        .fold((f64::INFINITY, 0), |m, x| if x.0 < m.0 { x } else { m });
                    let gap = gaps[g * cells_s + h];
                    assert!(gap <= truth, "({h}, {g}): {gap} > {truth}");
                    if rows_away <= ROWS_SEARCHED {
                        assert_eq!(gap, truth, "({h}, {g})");
                    }
                }
            }
        }
    }

    /// A row yields every cell with a trimmed triangle in the column range,
    /// with its triangles, nearest to the given column first.
    #[test]
    fn rows_yield_their_trimmed_cells_nearest_first() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        for _ in 0..300 {
            let (cells_s, cells_t) = (rng.random_range(1..9), rng.random_range(1..4));
            let mut trim = TrimMask::full(cells_s, cells_t);
            trim.bits
                .iter_mut()
                .for_each(|b| *b = rng.random_range(0..16));
            let domain = Domain {
                u_min: -1.0,
                v_min: 2.0,
                u_step: 0.3,
                v_step: 0.2,
                cols: cells_s + 3,
                rows: cells_t + 3,
            };
            let trimmed = Trimmed::new(&trim, &domain, (cells_s, cells_t));
            let g = rng.random_range(0..cells_t);
            let h0 = rng.random_range(0..cells_s);
            let h = [h0, rng.random_range(h0..cells_s)];
            let from = rng.random_range(h[0]..=h[1]);
            let got: Vec<(usize, usize)> = trimmed
                .row(g, h, from)
                .map(|(cell, triangles)| (cell.h, triangles.len()))
                .collect();
            let mut want: Vec<(usize, usize)> = (h[0]..=h[1])
                .map(|c| (c, 4 - (trim.cell_bits(c, g) & ALL).count_ones() as usize))
                .filter(|&(_, n)| n > 0)
                .collect();
            want.sort_by_key(|&(c, _)| (c.abs_diff(from), c < from));
            assert_eq!(got, want, "{:?} row {g} {h:?} from {from}", trim.bits);
        }
    }

    /// The row sweeps agree with a scan of every pair.
    #[test]
    fn columns_to_trimmed_is_the_nearest_trimmed_column() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        for _ in 0..500 {
            let n = rng.random_range(1..12);
            let bits: Vec<u8> = (0..n)
                .map(|_| if rng.random_bool(0.2) { 0 } else { ALL })
                .collect();
            let got = columns_to_trimmed(bits.iter().copied());
            for (h, d) in got.iter().enumerate() {
                let want = (0..n)
                    .filter(|&k| has_trimmed(bits[k]))
                    .map(|k| k.abs_diff(h))
                    .min();
                assert_eq!(*d, want, "{bits:?} at {h}");
            }
        }
    }
}
