//! Least-squares planes through point sets (principal component analysis), used for
//! point normals, the polygon of interest's plane P_f and the drop normal V_T
//! (Zou et al., Sections 3.2 and 4).
// Small fixed-size matrices and nets are clearer with explicit indices.
#![allow(clippy::needless_range_loop)]

use glam::DVec3;

/// An oriented plane: the points `x` with `(x - origin) . normal = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    pub origin: DVec3,
    /// Unit normal.
    pub normal: DVec3,
}

impl Plane {
    /// Signed distance of `p` to the plane, positive on the normal's side.
    pub fn height(&self, p: DVec3) -> f64 {
        (p - self.origin).dot(self.normal)
    }

    /// Orthogonal projection of `p` onto the plane.
    pub fn project(&self, p: DVec3) -> DVec3 {
        p - self.height(p) * self.normal
    }

    /// The same plane with its normal reversed.
    pub fn flipped(&self) -> Self {
        Self {
            origin: self.origin,
            normal: -self.normal,
        }
    }

    /// A deterministic right-handed frame `(u, v, normal)` of the plane.
    pub fn basis(&self) -> (DVec3, DVec3) {
        self.normal.any_orthonormal_pair()
    }
}

/// A least-squares plane with the spread of the points about it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneFit {
    /// Through the centroid, normal along the least principal axis (sign arbitrary).
    pub plane: Plane,
    /// Eigenvalues of the covariance (mean squared spread), ascending.
    pub spread: [f64; 3],
    /// Principal axes matching `spread`; `axes[0]` is the normal.
    pub axes: [DVec3; 3],
}

impl PlaneFit {
    /// Ratio of the smallest to the middle spread: 0 for perfectly planar points.
    pub fn flatness(&self) -> f64 {
        self.spread[0] / self.spread[1].max(f64::MIN_POSITIVE)
    }

    /// Whether the points spread in two directions (not a point or a line):
    /// the middle spread is at least `ratio` times the largest.
    pub fn is_two_dimensional(&self, ratio: f64) -> bool {
        self.spread[2] > 0.0 && self.spread[1] > ratio * self.spread[2]
    }
}

/// The least-squares plane through `points` (at least 3), or `None` for fewer
/// points or non-finite input. Collinear points still get a plane; check
/// [`PlaneFit::is_two_dimensional`] where that matters.
pub fn fit_plane(points: impl IntoIterator<Item = DVec3> + Clone) -> Option<PlaneFit> {
    let (sum, count) = points
        .clone()
        .into_iter()
        .fold((DVec3::ZERO, 0usize), |(s, n), p| (s + p, n + 1));
    if count < 3 {
        return None;
    }
    let centroid = sum / count as f64;
    let mut c = [[0.0f64; 3]; 3];
    for p in points {
        let d = (p - centroid).to_array();
        for i in 0..3 {
            for j in i..3 {
                c[i][j] += d[i] * d[j];
            }
        }
    }
    for i in 0..3 {
        for j in i..3 {
            c[i][j] /= count as f64;
            c[j][i] = c[i][j];
        }
    }
    if !centroid.is_finite() || c.iter().flatten().any(|v| !v.is_finite()) {
        return None;
    }
    let (values, vectors) = symmetric_eigen3(c);
    Some(PlaneFit {
        plane: Plane {
            origin: centroid,
            normal: vectors[0],
        },
        spread: values,
        axes: vectors,
    })
}

/// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations:
/// eigenvalues ascending with unit eigenvectors.
pub fn symmetric_eigen3(m: [[f64; 3]; 3]) -> ([f64; 3], [DVec3; 3]) {
    let mut a = m;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..32 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let scale = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-15 * scale || off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for k in 0..3 {
                let akp = a[k][p];
                let akq = a[k][q];
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let apk = a[p][k];
                let aqk = a[q][k];
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            for row in &mut v {
                let vp = row[p];
                let vq = row[q];
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| a[i][i].total_cmp(&a[j][j]));
    let values = order.map(|i| a[i][i]);
    let vectors = order.map(|i| DVec3::new(v[0][i], v[1][i], v[2][i]).normalize_or(DVec3::Z));
    (values, vectors)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tilted_plane_is_recovered() {
        let n = DVec3::new(1.0, 2.0, 3.0).normalize();
        let (u, v) = n.any_orthonormal_pair();
        let pts: Vec<DVec3> = (0..50)
            .map(|i| {
                let a = f64::from(i) * 0.37;
                DVec3::new(1.0, 2.0, 3.0) + u * a.cos() * (1.0 + a) + v * a.sin() * 0.5
            })
            .collect();
        let fit = fit_plane(pts.iter().copied()).unwrap();
        assert!(fit.plane.normal.dot(n).abs() > 1.0 - 1e-10);
        assert!(fit.spread[0] < 1e-12 * fit.spread[2]);
        assert!(fit.is_two_dimensional(1e-3));
    }

    #[test]
    fn eigen_of_diagonal_and_rotated() {
        let (values, vectors) =
            symmetric_eigen3([[3.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 2.0]]);
        assert_eq!(values, [1.0, 2.0, 3.0]);
        assert!(vectors[0].dot(DVec3::Y).abs() > 0.999_999);
        let (values, _) = symmetric_eigen3([[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 5.0]]);
        assert!((values[0] - 1.0).abs() < 1e-12 && (values[1] - 3.0).abs() < 1e-12);
    }

    #[test]
    fn too_few_or_collinear() {
        assert!(fit_plane([DVec3::ZERO, DVec3::X]).is_none());
        let line = fit_plane((0..5).map(|i| DVec3::X * f64::from(i))).unwrap();
        assert!(!line.is_two_dimensional(1e-6));
    }
}
