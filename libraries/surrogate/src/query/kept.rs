//! The kept region of a trim mask as a *closed* set: the union of the closed kept
//! triangles (Section 6, Figure 7). Queries use it instead of the half-open
//! `TrimMask::contains`, so that a point on an edge shared by a kept and a
//! trimmed triangle counts as kept: a guard must see a surface up to its border.
//! Every point `contains` accepts is accepted here too.

use crate::trim::{BOTTOM, LEFT, RIGHT, TOP};
use crate::TrimMask;

/// Whether `(s, t)` lies in a closed kept triangle. Parameters are clamped to the
/// domain first (callers test `Domain::contains_param`, which allows a slack).
#[inline]
pub fn kept_closed(trim: &TrimMask, s: f64, t: f64) -> bool {
    if !(s.is_finite() && t.is_finite()) {
        return false;
    }
    let s = s.clamp(0.0, trim.cells_s as f64);
    let t = t.clamp(0.0, trim.cells_t as f64);
    let (h_lo, h_hi) = cells_touching(s, trim.cells_s);
    let (g_lo, g_hi) = cells_touching(t, trim.cells_t);
    for g in g_lo..=g_hi {
        for h in h_lo..=h_hi {
            let bits = trim.cell_bits(h, g);
            if bits != 0 && bits & closed_triangles(s - h as f64, t - g as f64) != 0 {
                return true;
            }
        }
    }
    false
}

/// The cells whose closed interval contains `x in [0, n]`: two on an interior knot.
#[inline]
fn cells_touching(x: f64, n: usize) -> (usize, usize) {
    let f = x.floor();
    let hi = (f as usize).min(n - 1);
    let lo = if x == f && f >= 1.0 {
        (f as usize - 1).min(hi)
    } else {
        hi
    };
    (lo, hi)
}

/// Triangle bits whose closure contains local `(u, v)` (diagonals and cell edges
/// belong to every triangle that touches them).
#[inline]
pub fn closed_triangles(u: f64, v: f64) -> u8 {
    let (below_main, above_main) = (v <= u, v >= u);
    let (below_anti, above_anti) = (u + v <= 1.0, u + v >= 1.0);
    let mut bits = 0;
    if below_main && below_anti {
        bits |= BOTTOM;
    }
    if below_main && above_anti {
        bits |= RIGHT;
    }
    if above_main && above_anti {
        bits |= TOP;
    }
    if above_main && below_anti {
        bits |= LEFT;
    }
    bits
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn closed_region_contains_every_point_the_mask_contains() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let mut trim = TrimMask::empty(5, 4);
        trim.bits
            .iter_mut()
            .for_each(|b| *b = rng.random_range(0..16u8));
        for i in 0..20_000 {
            // Every fourth sample sits on a knot line or a diagonal.
            let (mut s, mut t): (f64, f64) =
                (rng.random_range(0.0..5.0), rng.random_range(0.0..4.0));
            match i % 4 {
                1 => s = s.round(),
                2 => t = t.floor() + (s - s.floor()),
                3 => t = t.floor() + 1.0 - (s - s.floor()),
                _ => {}
            }
            if trim.contains(s, t) {
                assert!(kept_closed(&trim, s, t), "({s}, {t})");
            }
        }
    }

    #[test]
    fn shared_edges_are_kept_from_either_side() {
        let mut trim = TrimMask::empty(2, 1);
        trim.bits[0] = RIGHT; // cell 0 keeps only the triangle touching s = 1
        assert!(
            kept_closed(&trim, 1.0, 0.5),
            "edge shared with the trimmed cell 1"
        );
        assert!(!trim.contains(1.0, 0.5), "contains is half-open there");
        assert!(kept_closed(&trim, 0.75, 0.5));
        assert!(
            kept_closed(&trim, 0.5, 0.5),
            "cell centre is a vertex of every triangle"
        );
        assert!(!kept_closed(&trim, 0.25, 0.5));
        assert!(!kept_closed(&trim, 1.5, 0.5));
        assert!(!kept_closed(&trim, f64::NAN, 0.5));
    }

    #[test]
    fn closed_triangles_cover_diagonals_twice_and_centre_four_times() {
        assert_eq!(closed_triangles(0.5, 0.1), BOTTOM);
        assert_eq!(closed_triangles(0.3, 0.3), BOTTOM | LEFT);
        assert_eq!(closed_triangles(0.8, 0.2), BOTTOM | RIGHT);
        assert_eq!(closed_triangles(0.5, 0.5), BOTTOM | RIGHT | TOP | LEFT);
    }
}
