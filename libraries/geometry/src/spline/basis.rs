//! The uniform cubic B-spline basis on one knot interval, eq. (1) of Section 2.
//!
//! Coefficients are `b_0 .. b_{n-1}` with the end conditions `b_{-1} = b_0` and
//! `b_n = b_{n-1}`; the Greville abscissa of `b_i` is `i`, so the domain is `[0, n-1]`.

/// Knot interval `h` and local parameter `u in [0, 1]` of a parameter `s`, clamped
/// to the domain `[0, n-1]` of a spline with `n >= 2` coefficients. The last
/// interval is closed so that `s = n-1` evaluates with `u = 1`.
#[inline]
pub fn knot_interval(s: f64, n: usize) -> (usize, f64) {
    // NaN and negative parameters fail `s >= 0` and map to 0. The truncating cast
    // is `floor` for non-negative values without a libm call on baseline x86-64
    // (this runs for every point in the hot passes).
    let s = if s >= 0.0 { s.min((n - 1) as f64) } else { 0.0 };
    let h = (s as usize).min(n - 2);
    (h, s - h as f64)
}

/// `Δ_i b = b_{i-1} - 2 b_i + b_{i+1}` with the repeated end coefficients, so the
/// first and last differences are first differences (the rows of `D` in eq. (2)).
#[inline]
pub fn second_difference(b: &[f64], i: usize) -> f64 {
    let n = b.len();
    let prev = b[i.saturating_sub(1)];
    let next = b[(i + 1).min(n - 1)];
    prev - 2.0 * b[i] + next
}

/// Evaluation in the form of eq. (1):
/// `f = (1-u) b_h + u b_{h+1} + (1-u)^3/6 Δ_h b + u^3/6 Δ_{h+1} b`.
/// Kept as the reference the faster weight form is tested against.
pub fn eval_eq1(b: &[f64], s: f64) -> f64 {
    let (h, u) = knot_interval(s, b.len());
    let w = 1.0 - u;
    w * b[h]
        + u * b[h + 1]
        + w * w * w / 6.0 * second_difference(b, h)
        + u * u * u / 6.0 * second_difference(b, h + 1)
}

/// The four B-spline weights of `b_{h-1}, b_h, b_{h+1}, b_{h+2}` at local `u`.
/// They are non-negative and sum to one (the convex hull property used for every
/// conservative bound in `query`).
#[inline]
pub fn basis_weights(u: f64) -> [f64; 4] {
    let w = 1.0 - u;
    let u2 = u * u;
    let u3 = u2 * u;
    [
        w * w * w / 6.0,
        (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0,
        (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0,
        u3 / 6.0,
    ]
}

/// Derivatives with respect to the parameter of the four weights of [`basis_weights`].
#[inline]
pub fn basis_derivative_weights(u: f64) -> [f64; 4] {
    let w = 1.0 - u;
    let u2 = u * u;
    [
        -0.5 * w * w,
        1.5 * u2 - 2.0 * u,
        -1.5 * u2 + u + 0.5,
        0.5 * u2,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_partition_unity_and_match_eq1() {
        let b = [0.3, -1.0, 2.0, 5.0, 4.0, -2.0];
        for i in 0..=50 {
            let s = i as f64 * 5.0 / 50.0;
            let (h, u) = knot_interval(s, b.len());
            let wts = basis_weights(u);
            assert!((wts.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!(wts.iter().all(|&x| x >= 0.0));
            let idx = |k: isize| b[(h as isize + k).clamp(0, b.len() as isize - 1) as usize];
            let f: f64 = (0..4).map(|k| wts[k] * idx(k as isize - 1)).sum();
            assert!((f - eval_eq1(&b, s)).abs() < 1e-12, "s={s}");
        }
    }

    #[test]
    fn derivative_weights_match_finite_differences() {
        for i in 1..20 {
            let u = i as f64 / 20.0;
            let e = 1e-6;
            let (a, c) = (basis_weights(u - e), basis_weights(u + e));
            let d = basis_derivative_weights(u);
            for k in 0..4 {
                assert!(((c[k] - a[k]) / (2.0 * e) - d[k]).abs() < 1e-7);
            }
        }
    }

    #[test]
    fn knot_interval_clamps_and_closes_last_interval() {
        assert_eq!(knot_interval(-1.0, 5), (0, 0.0));
        assert_eq!(knot_interval(4.0, 5), (3, 1.0));
        assert_eq!(knot_interval(9.0, 5), (3, 1.0));
        assert_eq!(knot_interval(2.25, 5), (2, 0.25));
        assert_eq!(knot_interval(1.0, 2), (0, 1.0));
    }
}
