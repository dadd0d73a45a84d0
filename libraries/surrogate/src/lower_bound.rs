//! The piecewise-linear lower bounds of Lemma 4.1 and Lemma 5.1.
//!
//! On a knot interval `[h, h+1]` the Lemma 5.1 bound is
//! `L(u) = (1-u) b_h + u b_{h+1} + g(u) min(Δ_h b, 0) + g(1-u) min(Δ_{h+1} b, 0)`
//! with `g(u) = (1-u)^3 / 6`. The paper evaluates `g` at break knots and
//! interpolates linearly (`ḡ >= g`); at the break knots themselves `ḡ = g`.
//!
//! **Concavity (why only upper-hull points can bind).** `g` is convex on `[0, 1]`
//! (`g'' = (1-u) >= 0`) and so is `g(1-u)`; multiplied by the non-positive
//! `min(Δ, 0)` they become concave, and adding the linear part keeps `L` concave
//! on each knot interval. A concave function that lies above every vertex of the
//! upper convex hull of a point set lies above the hull's piecewise-linear upper
//! boundary, hence above every point of the set. So a fit constrained at the
//! upper-hull vertices of each (line, interval) cell is safe for the whole cell:
//! see `tests::bound_above_hull_vertices_covers_all_points`.

use shroud_geometry::spline::{knot_interval, second_difference};

/// Lemma 4.1: breakpoints `ℓ_i = b_i + min(Δ_i b, 0) / 6`, eq. (3).
pub fn broken_line_lower_bound(b: &[f64]) -> Vec<f64> {
    (0..b.len())
        .map(|i| b[i] + second_difference(b, i).min(0.0) / 6.0)
        .collect()
}

/// `min(Δ_i b, 0)` for every `i`, precomputed for repeated bound evaluation.
pub fn negative_differences(b: &[f64]) -> Vec<f64> {
    (0..b.len())
        .map(|i| second_difference(b, i).min(0.0))
        .collect()
}

/// Lemma 5.1 bound (5) at `s`, given `neg = negative_differences(b)`.
#[inline]
pub fn scattered_lower_bound(b: &[f64], neg: &[f64], s: f64) -> f64 {
    let (h, u) = knot_interval(s, b.len());
    let w = 1.0 - u;
    w * b[h] + u * b[h + 1] + (w * w * w * neg[h] + u * u * u * neg[h + 1]) / 6.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::upper_hull::upper_hull;
    use rand::{Rng, SeedableRng};
    use shroud_geometry::spline::UniformCubicCurve;

    fn random_coefficients(rng: &mut rand_pcg::Pcg64, n: usize) -> Vec<f64> {
        (0..n).map(|_| rng.random_range(-5.0..5.0)).collect()
    }

    #[test]
    fn lemma_4_1_broken_line_is_below_spline() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(1);
        for _ in 0..200 {
            let b = random_coefficients(&mut rng, 9);
            let ell = broken_line_lower_bound(&b);
            let curve = UniformCubicCurve::new(b.clone()).unwrap();
            for i in 0..=800 {
                let s = i as f64 * 8.0 / 800.0;
                let (h, u) = knot_interval(s, 9);
                let line = (1.0 - u) * ell[h] + u * ell[h + 1];
                assert!(curve.eval(s) >= line - 1e-12, "s={s}");
            }
        }
    }

    #[test]
    fn lemma_5_1_bound_is_below_spline_and_concave_per_interval() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(2);
        for _ in 0..200 {
            let b = random_coefficients(&mut rng, 7);
            let neg = negative_differences(&b);
            let curve = UniformCubicCurve::new(b.clone()).unwrap();
            for h in 0..6 {
                let at = |u: f64| scattered_lower_bound(&b, &neg, h as f64 + u);
                for i in 1..50 {
                    let u = i as f64 / 50.0;
                    assert!(curve.eval(h as f64 + u) >= at(u) - 1e-12);
                    // Midpoint concavity on the interval.
                    let e = 0.01f64.min(u).min(1.0 - u);
                    assert!(at(u) >= 0.5 * (at(u - e) + at(u + e)) - 1e-12);
                }
            }
        }
    }

    #[test]
    fn bound_above_hull_vertices_covers_all_points() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        for _ in 0..300 {
            let b = random_coefficients(&mut rng, 6);
            let neg = negative_differences(&b);
            let h = rng.random_range(0..5) as f64;
            let mut pts: Vec<(f64, f64)> = (0..40)
                .map(|_| {
                    let s = h + rng.random_range(0.0..1.0);
                    (
                        s,
                        scattered_lower_bound(&b, &neg, s) - rng.random_range(0.0..2.0),
                    )
                })
                .collect();
            pts.sort_by(|a, c| a.0.total_cmp(&c.0));
            let hull = upper_hull(&pts);
            // Lift the points so that the hull vertices sit exactly on or below L...
            let lift = hull
                .iter()
                .map(|&(s, y)| scattered_lower_bound(&b, &neg, s) - y)
                .fold(f64::INFINITY, f64::min);
            // ...then every point of the cell is below L as well.
            for &(s, y) in &pts {
                assert!(scattered_lower_bound(&b, &neg, s) >= y + lift - 1e-9);
            }
        }
    }
}
