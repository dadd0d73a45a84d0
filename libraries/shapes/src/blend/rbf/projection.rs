//! The null space of Eq. 1's side condition `P^T lambda = 0`, spanned by local
//! vectors (Beatson, Light and Billings, "Fast solution of the radial basis
//! function interpolation equations: domain decomposition methods", 2000): four
//! base centres `b_1..b_4` in general position carry the linear polynomials,
//! and every other centre `j` gives the column `q_j = e_j - sum_k l_k(x_j) e_(b_k)`
//! with `l_k` the linear Lagrange basis on the base centres, so `P^T q_j = 0`.
//! Since `|r|^3` is conditionally positive definite of order 2, `Q^T A Q` is
//! positive definite: a Cholesky factor exists, and a new centre only appends a
//! row and a column, so the factor can grow with the greedy fit.

use glam::{DMat4, DVec3, DVec4};

/// `|a - b|^3`, the kernel of Eq. 1; the dense solve's matrix uses it too, so
/// the grown factor and its fallback see the same entries.
#[inline(always)]
pub(super) fn cube(a: DVec3, b: DVec3) -> f64 {
    let s = a.distance_squared(b);
    s * s.sqrt()
}

/// What one non-base centre contributes to the projected matrix.
#[derive(Debug, Clone, Copy)]
pub(super) struct Projected {
    pub(super) point: DVec3,
    /// `l_k(x_j)`: the Lagrange weights of the base centres at this centre.
    pub(super) lagrange: [f64; 4],
    /// `|x_j - b_k|^3`.
    pub(super) to_base: [f64; 4],
    /// `A_bb l(x_j)`, with `A_bb` the kernel among the base centres.
    pub(super) base_mix: [f64; 4],
}

/// The base centres and their Lagrange basis.
#[derive(Debug, Clone)]
pub(super) struct Projection {
    pub(super) base: [DVec3; 4],
    /// Maps `[1, x, y, z]` to the Lagrange weights `l(x)`.
    to_lagrange: DMat4,
    /// `A_bb`.
    pub(super) base_kernel: [[f64; 4]; 4],
}

fn dot(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

impl Projection {
    /// The projection on `base` (scaled coordinates), or `None` when the base
    /// centres are (nearly) coplanar: their tetrahedron's volume is below
    /// `1e-9` of the unit ball's scale, and the Lagrange weights would blow up.
    pub(super) fn new(base: [DVec3; 4]) -> Option<Self> {
        let columns = base.map(|b| DVec4::new(1.0, b.x, b.y, b.z));
        let nodes = DMat4::from_cols(columns[0], columns[1], columns[2], columns[3]);
        // det = 6 x the tetrahedron's volume.
        if !(nodes.determinant().abs() > 1e-9) {
            return None;
        }
        let base_kernel = std::array::from_fn(|k| std::array::from_fn(|l| cube(base[k], base[l])));
        Some(Self {
            base,
            to_lagrange: nodes.inverse(),
            base_kernel,
        })
    }

    /// `l(x)`: `sum_k l_k(x) [1, b_k] = [1, x]`.
    pub(super) fn lagrange(&self, x: DVec3) -> [f64; 4] {
        (self.to_lagrange * DVec4::new(1.0, x.x, x.y, x.z)).to_array()
    }

    pub(super) fn project(&self, point: DVec3) -> Projected {
        let lagrange = self.lagrange(point);
        let base_mix = self.base_kernel.map(|row| dot(&row, &lagrange));
        Projected {
            point,
            lagrange,
            to_base: self.base.map(|b| cube(point, b)),
            base_mix,
        }
    }

    /// `(Q^T A Q)_ij = A_ij - l_i . A_(b,j) - A_(i,b) . l_j + l_i^T A_bb l_j`.
    #[inline]
    pub(super) fn entry(i: &Projected, j: &Projected) -> f64 {
        cube(i.point, j.point) - dot(&i.lagrange, &j.to_base) - dot(&i.to_base, &j.lagrange)
            + dot(&i.lagrange, &j.base_mix)
    }

    /// The linear polynomial `c` whose values at the base centres are `at_base`:
    /// `[1, b_k] . c = at_base_k`, so `c = (M^T)^-1 at_base` with `M^-1` the
    /// Lagrange map.
    pub(super) fn polynomial(&self, at_base: [f64; 4]) -> [f64; 4] {
        (self.to_lagrange.transpose() * DVec4::from_array(at_base)).to_array()
    }

    /// `(Q^T f)_j = f_j - l_j . f_b`.
    pub(super) fn rhs(&self, centre: &Projected, value: f64, base_values: &[f64; 4]) -> f64 {
        value - dot(&centre.lagrange, base_values)
    }
}

/// Four of `points` spanning a large tetrahedron (greedy: the point farthest
/// from the mean, the one farthest from it, the farthest from their line, the
/// farthest from their plane), as indices; `None` for fewer than four points.
pub(super) fn pick_base(points: &[DVec3]) -> Option<[usize; 4]> {
    if points.len() < 4 {
        return None;
    }
    let mean = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let farthest = |score: &dyn Fn(DVec3) -> f64| -> usize {
        let mut best = (0, f64::NEG_INFINITY);
        for (i, &p) in points.iter().enumerate() {
            let s = score(p);
            if s > best.1 {
                best = (i, s);
            }
        }
        best.0
    };
    let a = farthest(&|p| p.distance_squared(mean));
    let b = farthest(&|p| p.distance_squared(points[a]));
    let axis = (points[b] - points[a]).normalize_or_zero();
    let off_line = |p: DVec3| {
        let d = p - points[a];
        (d - d.dot(axis) * axis).length_squared()
    };
    let c = farthest(&off_line);
    let normal = (points[b] - points[a])
        .cross(points[c] - points[a])
        .normalize_or_zero();
    let d = farthest(&|p| (p - points[a]).dot(normal).abs());
    Some([a, b, c, d])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lagrange_weights_reproduce_linear_functions() {
        let base = [
            DVec3::new(0.1, 0.0, 0.0),
            DVec3::new(1.0, 0.2, 0.0),
            DVec3::new(0.0, 0.9, 0.1),
            DVec3::new(0.2, 0.3, 1.0),
        ];
        let projection = Projection::new(base).expect("a tetrahedron");
        let x = DVec3::new(0.4, -0.3, 0.7);
        let l = projection.lagrange(x);
        let linear = |p: DVec3| 1.5 - 2.0 * p.x + 0.5 * p.y + 3.0 * p.z;
        let mixed: f64 = (0..4).map(|k| l[k] * linear(base[k])).sum();
        assert!((mixed - linear(x)).abs() < 1e-12);
        assert!(Projection::new([DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X + DVec3::Y]).is_none());
    }
}
