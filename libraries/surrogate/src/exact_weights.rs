//! The cubic B-spline weights of [`basis_weights`] without its four divisions.
//!
//! `basis_weights` divides four numerators by 6; a division costs as much as a
//! dozen multiplications and certification needs eight per point. Markstein's
//! theorem (IBM J. Res. Dev. 34(1), 1990; the division chapter of Muller et al.,
//! Handbook of Floating-Point Arithmetic) gives the correctly rounded quotient from `y = RN(1/6)`, `q = RN(x y)`, the exact
//! remainder `r = x - 6 q` (one FMA) and `RN(q + r y)` (one FMA), provided nothing
//! underflows. Correct rounding is unique, so the weights are the same bits as
//! `basis_weights` gives, which keeps certification bit-identical to
//! `UniformCubicSurface::eval`.

use shroud_geometry::spline::basis_weights;

/// Below this, `x / 6`'s remainder could be subnormal and Markstein's step inexact.
/// Only `u^3` of a parameter within `2^-300` of a knot gets there.
pub(crate) const SMALLEST_EXACT: f64 = 1.0e-270;

/// `x / 6` correctly rounded for `x == 0` or `|x| >= SMALLEST_EXACT` (and finite).
#[inline(always)]
fn div6(x: f64) -> f64 {
    const Y: f64 = 1.0 / 6.0;
    let q = x * Y;
    let r = (-q).mul_add(6.0, x);
    r.mul_add(Y, q)
}

/// Same value as `basis_weights(u)` for `u` in `[0, 1]` unless
/// `0 < u^3 < SMALLEST_EXACT` (see [`needs_division`]).
#[inline(always)]
pub(crate) fn basis_weights_fma(u: f64) -> [f64; 4] {
    let w = 1.0 - u;
    let u2 = u * u;
    let u3 = u2 * u;
    [
        div6(w * w * w),
        div6(3.0 * u3 - 6.0 * u2 + 4.0),
        div6(-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0),
        div6(u3),
    ]
}

/// Whether `basis_weights_fma(u)` may differ from `basis_weights(u)`: only for a
/// positive `u` so small that `u^3` is near the subnormal range. The other three
/// numerators are at least `2^-159` on `[0, 1]` (`1 - u` is a multiple of `2^-53`).
#[inline(always)]
pub(crate) fn needs_division(u: f64) -> bool {
    u > 0.0 && u * u * u < SMALLEST_EXACT
}

/// `basis_weights(u)`, bit for bit, for every `u` in `[0, 1]` but `-0.0` (whose
/// last weight would come out `+0.0`; knot intervals never give it, as
/// `s - floor(s)` is `+0.0` for `s = -0.0`): the divisions are taken only where
/// Markstein's step could be inexact.
#[inline(always)]
pub(crate) fn exact_basis_weights(u: f64) -> [f64; 4] {
    if needs_division(u) {
        basis_weights(u)
    } else {
        basis_weights_fma(u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic stream of doubles in `[0, 1)` (xorshift).
    fn stream(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn division_by_six_is_correctly_rounded_over_many_binades() {
        let mut next = stream(0x9e37_79b9_7f4a_7c15);
        for e in -890..16 {
            let scale = 2f64.powi(e);
            for _ in 0..2000 {
                let x = (1.0 + next()) * scale;
                assert_eq!(div6(x).to_bits(), (x / 6.0).to_bits(), "x = {x:e}");
                assert_eq!(div6(-x).to_bits(), (-x / 6.0).to_bits(), "x = {:e}", -x);
            }
        }
        // Multiples of 6 and their neighbours are the usual hard cases.
        for k in 0..100_000u64 {
            let x = 6.0 * k as f64;
            for y in [
                x,
                f64::from_bits(x.to_bits() + 1),
                f64::from_bits(x.to_bits().saturating_sub(1)),
            ] {
                assert_eq!(div6(y).to_bits(), (y / 6.0).to_bits(), "x = {y:e}");
            }
        }
    }

    #[test]
    fn weights_are_bit_identical_to_basis_weights() {
        let mut next = stream(42);
        let check = |u: f64| {
            assert!(!needs_division(u) || u < 1e-89, "u = {u:e}");
            if !needs_division(u) {
                let (a, b) = (basis_weights_fma(u), basis_weights(u));
                assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "u = {u:e}");
            }
        };
        for _ in 0..1_000_000 {
            check(next());
        }
        // Dyadic parameters (grid-aligned data), both ends and tiny parameters.
        for k in 0..=4096 {
            check(k as f64 / 4096.0);
        }
        for e in 0..1100 {
            let u = 2f64.powi(-e);
            check(u);
            check(1.0 - u);
            check(u * (1.0 + next()));
        }
        check(0.0);
        check(1.0);
    }

    #[test]
    fn only_subnormal_range_cubes_need_the_division() {
        assert!(!needs_division(0.0));
        assert!(!needs_division(1e-80));
        assert!(needs_division(1e-95));
        assert!(needs_division(f64::MIN_POSITIVE));
    }
}
