//! The first root of a Bernstein polynomial on `[0, 1]` by subdivision: a piece
//! whose coefficients are all positive (or all negative) has no root (convex
//! hull property) and is discarded; the leftmost piece that cannot be discarded
//! at the finest level is reported. Touching roots (double roots) and values
//! within the rounding margin of zero are therefore reported, never missed.

use super::bernstein::Bernstein6;

/// Deepest subdivision: pieces of `2^-52` are at the resolution of `f64` on `[0, 1]`.
pub const MAX_DEPTH: u32 = 52;

/// Subdivision depth that makes pieces no longer than `resolution` (in units of
/// the interval `[0, 1]`).
#[inline]
pub fn depth_for(resolution: f64) -> u32 {
    if resolution >= 1.0 {
        0
    } else if resolution > 0.0 {
        ((-resolution.log2()).ceil() as u32).min(MAX_DEPTH)
    } else {
        MAX_DEPTH
    }
}

/// Left end of the first piece of width `2^-depth` on which `poly` may vanish,
/// i.e. a lower bound (within one piece) of its first root; `None` is a proof
/// that `|poly| > margin` on all of `[0, 1]`. `margin` covers the rounding of the
/// coefficients: a coefficient within it of zero is not trusted for its sign.
pub fn first_root(poly: &Bernstein6, depth: u32, margin: f64) -> Option<f64> {
    let depth = depth.min(MAX_DEPTH);
    // Depth-first, left child first; the stack holds at most one pending right
    // sibling per level, so a fixed array suffices and nothing is allocated.
    let mut pending = [(Bernstein6([0.0; 7]), 0.0, 0u32); MAX_DEPTH as usize + 1];
    let mut len = 0;
    let mut current = (*poly, 0.0f64, 0u32);
    loop {
        let (piece, start, level) = current;
        if piece.0[0].abs() <= margin {
            // The first coefficient is the value at the piece's left end.
            return Some(start);
        }
        let (lo, hi) = piece.hull();
        let excluded = lo > margin || hi < -margin;
        if !excluded {
            if level >= depth {
                return Some(start);
            }
            let (left, right) = piece.split_half();
            let half = 0.5f64.powi(level as i32 + 1);
            match pending.get_mut(len) {
                Some(slot) => *slot = (right, start + half, level + 1),
                // Cannot happen (one pending piece per level); if it did, the
                // right half would go unexamined, so report instead of skipping.
                None => return Some(start),
            }
            len += 1;
            current = (left, start, level + 1);
            continue;
        }
        if len == 0 {
            return None;
        }
        len -= 1;
        current = pending[len];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bernstein form of a polynomial given by power coefficients `a_j x^j`:
    /// `c_k = sum_{j <= k} C(k, j) / C(6, j) a_j`.
    fn from_power(a: [f64; 7]) -> Bernstein6 {
        let binom =
            |n: usize, k: usize| (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64);
        let mut c = [0.0; 7];
        for (k, ck) in c.iter_mut().enumerate() {
            *ck = (0..=k).map(|j| binom(k, j) / binom(6, j) * a[j]).sum();
        }
        Bernstein6(c)
    }

    /// `(x - r1)(x - r2) + lift`.
    fn quadratic(r1: f64, r2: f64, lift: f64) -> Bernstein6 {
        from_power([r1 * r2 + lift, -(r1 + r2), 1.0, 0.0, 0.0, 0.0, 0.0])
    }

    #[test]
    fn finds_the_first_of_two_simple_roots() {
        let poly = quadratic(0.3, 0.7, 0.0);
        assert!((poly.eval(0.3)).abs() < 1e-15);
        let root = first_root(&poly, 40, 1e-15).unwrap();
        assert!(root <= 0.3 && 0.3 - root < 1e-11, "root {root}");
    }

    #[test]
    fn double_roots_are_hits_and_near_misses_are_proved() {
        let touch = quadratic(0.4, 0.4, 0.0);
        let root = first_root(&touch, 40, 1e-15).unwrap();
        assert!(
            (root - 0.4).abs() < 1e-7,
            "a touching root resolves to about sqrt(margin): {root}"
        );
        assert_eq!(first_root(&quadratic(0.4, 0.4, 1e-6), 40, 1e-15), None);
        let negative = from_power([-1.0, 0.5, -2.0, 0.0, 0.0, 0.0, 0.3]);
        assert_eq!(first_root(&negative, 40, 1e-15), None);
    }

    #[test]
    fn values_at_the_start_and_end_count() {
        assert_eq!(first_root(&quadratic(0.0, 2.0, 0.0), 40, 1e-15), Some(0.0));
        let end = first_root(&quadratic(1.0, 3.0, 0.0), 40, 1e-15).unwrap();
        assert!(1.0 - end < 1e-11);
    }

    #[test]
    fn depth_matches_resolution() {
        assert_eq!(depth_for(2.0), 0);
        assert_eq!(depth_for(0.25), 2);
        assert_eq!(depth_for(0.2), 3);
        assert_eq!(depth_for(0.0), MAX_DEPTH);
        assert_eq!(depth_for(1e-300), MAX_DEPTH);
    }
}
