//! Exact integrals of the cubic B-spline weight products over the four triangles
//! of a cell (the trim pieces of Section 6): the building block of the LP objective.
//!
//! `B_q(u) B_r(v)` has degree 3 in each variable, so it has total degree 6. The
//! collapsed (Duffy) map of a triangle turns it into a polynomial of degree <= 7
//! in each square coordinate, which five-point Gauss-Legendre integrates exactly.

use crate::trim::{BOTTOM, LEFT, RIGHT, TOP};
use shroud_geometry::spline::basis_weights;

/// Five-point Gauss-Legendre on `[0, 1]` (exact to degree 9): nodes and weights.
const GAUSS_NODES: [f64; 5] = [
    0.046_910_077_030_668,
    0.230_765_344_947_158_45,
    0.5,
    0.769_234_655_052_841_6,
    0.953_089_922_969_332,
];
const GAUSS_WEIGHTS: [f64; 5] = [
    0.118_463_442_528_094_54,
    0.239_314_335_249_683_23,
    0.284_444_444_444_444_45,
    0.239_314_335_249_683_23,
    0.118_463_442_528_094_54,
];

/// The triangle bits in the order of [`TriangleMoments::of`].
pub const TRIANGLES: [u8; 4] = [BOTTOM, RIGHT, TOP, LEFT];

/// Corners of one of the four diagonal triangles of the square with lower-left
/// corner `(x, y)` and side `size` (local cell coordinates); the third corner is
/// the square's centre.
pub fn corners(triangle: u8, x: f64, y: f64, size: f64) -> [[f64; 2]; 3] {
    let (x1, y1) = (x + size, y + size);
    let centre = [x + 0.5 * size, y + 0.5 * size];
    match triangle {
        BOTTOM => [[x, y], [x1, y], centre],
        RIGHT => [[x1, y], [x1, y1], centre],
        TOP => [[x1, y1], [x, y1], centre],
        _ => [[x, y1], [x, y], centre],
    }
}

/// `moments[r][q] = ∫_T B_q(u) B_r(v) du dv` for one triangle `T` of the unit cell,
/// indexed like [`shroud_geometry::spline::UniformCubicSurface::cell_coefficients`].
pub type Moments = [[f64; 4]; 4];

/// The moments of all four triangles of a cell (computed once per use site).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleMoments {
    moments: [Moments; 4],
}

impl Default for TriangleMoments {
    fn default() -> Self {
        Self::new()
    }
}

impl TriangleMoments {
    pub fn new() -> Self {
        Self {
            moments: TRIANGLES.map(|t| triangle_moments(corners(t, 0.0, 0.0, 1.0))),
        }
    }

    /// Sum of the moments of the triangles set in `bits` (a cell's trim bits).
    pub fn of(&self, bits: u8) -> Moments {
        let mut sum = [[0.0; 4]; 4];
        for (m, &t) in self.moments.iter().zip(&TRIANGLES) {
            if bits & t != 0 {
                for r in 0..4 {
                    for q in 0..4 {
                        sum[r][q] += m[r][q];
                    }
                }
            }
        }
        sum
    }
}

/// Collapsed-coordinate Gauss-Legendre over the triangle `p0, p1, p2`:
/// `x = p0 + a (p1 - p0) + a b (p2 - p1)`, Jacobian `2 |T| a`.
pub fn triangle_moments([p0, p1, p2]: [[f64; 2]; 3]) -> Moments {
    let cross = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
    let mut m = [[0.0; 4]; 4];
    for (&a, &wa) in GAUSS_NODES.iter().zip(&GAUSS_WEIGHTS) {
        for (&b, &wb) in GAUSS_NODES.iter().zip(&GAUSS_WEIGHTS) {
            let u = p0[0] + a * (p1[0] - p0[0]) + a * b * (p2[0] - p1[0]);
            let v = p0[1] + a * (p1[1] - p0[1]) + a * b * (p2[1] - p1[1]);
            let weight = wa * wb * cross.abs() * a;
            let (bu, bv) = (basis_weights(u), basis_weights(v));
            for r in 0..4 {
                for q in 0..4 {
                    m[r][q] += weight * bu[q] * bv[r];
                }
            }
        }
    }
    m
}

/// `∫_a^b B_q(u) du` for the four weights of [`basis_weights`], exactly (from
/// their antiderivatives).
pub fn interval_moments(a: f64, b: f64) -> [f64; 4] {
    let (x, y) = (basis_antiderivatives(a), basis_antiderivatives(b));
    [0, 1, 2, 3].map(|q| y[q] - x[q])
}

/// Antiderivatives vanishing at 0 of the four weights of [`basis_weights`].
fn basis_antiderivatives(u: f64) -> [f64; 4] {
    let (u2, u3, u4) = (u * u, u * u * u, u * u * u * u);
    let w = 1.0 - u;
    [
        (1.0 - w * w * w * w) / 24.0,
        (0.75 * u4 - 2.0 * u3 + 4.0 * u) / 6.0,
        (-0.75 * u4 + u3 + 1.5 * u2 + u) / 6.0,
        u4 / 24.0,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Supersampled midpoint rule on a fine grid of the unit cell. The samples sit
    /// at `(±a, ±2a)` around each pixel centre, so a pixel the diagonals cut through
    /// its centre gives exactly half its samples to each side.
    fn brute_force(triangle: u8) -> Moments {
        let n = 400;
        let a = 0.2 / n as f64;
        let mut m = [[0.0; 4]; 4];
        for i in 0..n {
            for k in 0..n {
                let (cu, cv) = ((i as f64 + 0.5) / n as f64, (k as f64 + 0.5) / n as f64);
                for (du, dv) in [(a, 2.0 * a), (-a, -2.0 * a), (a, -2.0 * a), (-a, 2.0 * a)] {
                    let (u, v) = (cu + du, cv + dv);
                    if crate::trim::triangle_of(u, v) != triangle {
                        continue;
                    }
                    let (bu, bv) = (basis_weights(u), basis_weights(v));
                    for r in 0..4 {
                        for q in 0..4 {
                            m[r][q] += bu[q] * bv[r] / (4 * n * n) as f64;
                        }
                    }
                }
            }
        }
        m
    }

    #[test]
    fn triangle_moments_match_a_fine_midpoint_rule() {
        let moments = TriangleMoments::new();
        for t in TRIANGLES {
            let (exact, approx) = (moments.of(t), brute_force(t));
            for r in 0..4 {
                for q in 0..4 {
                    assert!(
                        (exact[r][q] - approx[r][q]).abs() < 2e-6,
                        "triangle {t} [{r}][{q}]: {} vs {}",
                        exact[r][q],
                        approx[r][q]
                    );
                }
            }
        }
    }

    #[test]
    fn the_four_triangles_add_up_to_the_cell_integrals() {
        let whole = TriangleMoments::new().of(0b1111);
        let cell = interval_moments(0.0, 1.0);
        for r in 0..4 {
            for q in 0..4 {
                assert!(
                    (whole[r][q] - cell[q] * cell[r]).abs() < 1e-15,
                    "[{r}][{q}]"
                );
            }
        }
        // 1/24, 11/24, 11/24, 1/24: the integrals of the uniform cubic B-spline pieces.
        let expected = [1.0 / 24.0, 11.0 / 24.0, 11.0 / 24.0, 1.0 / 24.0];
        cell.iter()
            .zip(&expected)
            .for_each(|(a, b)| assert!((a - b).abs() < 1e-15));
    }

    #[test]
    fn interval_moments_match_the_midpoint_rule() {
        let (a, b, n) = (0.2, 0.7, 20_000);
        let mut approx = [0.0; 4];
        for i in 0..n {
            let w = basis_weights(a + (i as f64 + 0.5) * (b - a) / n as f64);
            (0..4).for_each(|q| approx[q] += w[q] * (b - a) / n as f64);
        }
        let exact = interval_moments(a, b);
        (0..4).for_each(|q| assert!((exact[q] - approx[q]).abs() < 1e-9));
    }
}
