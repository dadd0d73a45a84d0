//! Per cell of an envelope, a lower bound on the distance from anywhere in
//! the cell to the nearest trimmed triangle, built once per surrogate: the
//! unseen search (`guard::unseen`) skips a shape that no trimmed triangle
//! can come near without looking at a single cell.
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

use shroud_surrogate::trim::ALL;
use shroud_surrogate::{Domain, TrimMask};

/// Rounding allowance of every bound here, relative to the largest
/// coordinate of the domain (1000 times the envelope's own margin).
pub(crate) const ROUNDING_REL: f64 = 1e-9;

/// The lower bounds of one envelope.
#[derive(Debug, Clone)]
pub(crate) struct TrimmedGaps {
    cells_s: usize,
    /// Row-major `g * cells_s + h`: the rectangle gap to the nearest cell
    /// with a trimmed triangle (0 for such a cell, infinite without any).
    gaps: Vec<f64>,
    /// What every bound is reduced by against rounding (m).
    pub(crate) rounding: f64,
}

/// Whether cell bits leave a triangle trimmed away.
#[inline]
pub(crate) fn has_trimmed(bits: u8) -> bool {
    bits & ALL != ALL
}

impl TrimmedGaps {
    /// The bounds of `trim` over `domain`'s cells (`cells_s` x `cells_t`).
    pub(crate) fn new(
        trim: &TrimMask,
        domain: &Domain,
        (cells_s, cells_t): (usize, usize),
    ) -> Self {
        let steps = [domain.u_step, domain.v_step];
        let rows: Vec<Vec<Option<usize>>> = (0..cells_t)
            .map(|g| columns_to_trimmed((0..cells_s).map(|h| trim.cell_bits(h, g))))
            .collect();
        let mut gaps = Vec::with_capacity(cells_s * cells_t);
        for g in 0..cells_t {
            for h in 0..cells_s {
                let nearest2 = rows
                    .iter()
                    .enumerate()
                    .filter_map(|(other, row)| {
                        let du = cells_apart(row[h]?) * steps[0];
                        let dv = cells_apart(g.abs_diff(other)) * steps[1];
                        Some(du * du + dv * dv)
                    })
                    .fold(f64::INFINITY, f64::min);
                gaps.push(nearest2.sqrt());
            }
        }
        let u_max = domain.u_min + cells_s as f64 * domain.u_step;
        let v_max = domain.v_min + cells_t as f64 * domain.v_step;
        let scale = [domain.u_min, domain.v_min, u_max, v_max]
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        Self {
            cells_s,
            gaps,
            rounding: ROUNDING_REL * (1.0 + scale),
        }
    }

    /// Lower bound on the computed distance from any point of the cells
    /// `h[0]..=h[1]` x `g[0]..=g[1]` (and within rounding of them) to a
    /// trimmed triangle.
    pub(crate) fn lower_bound(&self, h: [usize; 2], g: [usize; 2]) -> f64 {
        let nearest = (g[0]..=g[1])
            .flat_map(|g| &self.gaps[g * self.cells_s + h[0]..=g * self.cells_s + h[1]])
            .fold(f64::INFINITY, |m, &x| m.min(x));
        nearest - self.rounding
    }
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
