//! Planar polygons in the coordinates of the plane P_f: inside tests, distance to
//! the boundary, and the paper's equidistant scaling (Section 4, Fig. 8).

use glam::DVec2;
use shroud_geometry::math::segment_distance;

/// A simple polygon, counter-clockwise, with at least three vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon2 {
    vertices: Vec<DVec2>,
    centroid: DVec2,
    /// Largest distance from the vertex centroid to a vertex (for quick rejection).
    radius: f64,
}

impl Polygon2 {
    /// Makes the polygon counter-clockwise; `None` for fewer than three vertices,
    /// non-finite ones or zero area.
    pub fn new(mut vertices: Vec<DVec2>) -> Option<Self> {
        if vertices.len() < 3 || vertices.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let area = signed_area(&vertices);
        if area == 0.0 || !area.is_finite() {
            return None;
        }
        if area < 0.0 {
            vertices.reverse();
        }
        let centroid = vertices.iter().copied().sum::<DVec2>() / vertices.len() as f64;
        let radius = vertices
            .iter()
            .map(|v| v.distance(centroid))
            .fold(0.0, f64::max);
        Some(Self {
            vertices,
            centroid,
            radius,
        })
    }

    pub fn vertices(&self) -> &[DVec2] {
        &self.vertices
    }

    /// Mean of the vertices.
    pub fn centroid(&self) -> DVec2 {
        self.centroid
    }

    /// Largest vertex distance from the centroid.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Enclosed area (positive).
    pub fn area(&self) -> f64 {
        signed_area(&self.vertices)
    }

    /// Length of the closed boundary.
    pub fn perimeter(&self) -> f64 {
        self.edges().map(|(a, b)| a.distance(b)).sum()
    }

    fn edges(&self) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        let n = self.vertices.len();
        (0..n).map(move |i| (self.vertices[i], self.vertices[(i + 1) % n]))
    }

    /// Whether `q` is inside (even-odd rule).
    pub fn contains(&self, q: DVec2) -> bool {
        if q.distance(self.centroid) > self.radius {
            return false;
        }
        let mut inside = false;
        for (a, b) in self.edges() {
            if (a.y > q.y) != (b.y > q.y) {
                let x = a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if q.x < x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// Distance from `q` to the boundary.
    pub fn boundary_distance(&self, q: DVec2) -> f64 {
        self.edges()
            .map(|(a, b)| segment_distance(q, a, b))
            .fold(f64::INFINITY, f64::min)
    }

    /// Signed distance to the boundary: negative inside, positive outside. The
    /// level sets `d = s > 0` are the exact equidistant scalings of the polygon,
    /// which is how membership in P_in and P_out is decided (no self-intersection
    /// even for concave polygons).
    pub fn signed_distance(&self, q: DVec2) -> f64 {
        let d = self.boundary_distance(q);
        if self.contains(q) {
            -d
        } else {
            d
        }
    }

    /// [`Polygon2::signed_distance`] when it is at most `cap`; otherwise some
    /// value above `cap`, found cheaply from the circumscribed circle.
    pub fn signed_distance_capped(&self, q: DVec2, cap: f64) -> f64 {
        let far = q.distance(self.centroid) - self.radius;
        if far > cap {
            far
        } else {
            self.signed_distance(q)
        }
    }

    /// The paper's equidistant scaling: every edge moved outward by `s` (inward
    /// for negative `s`), `P_k' = P_k + (E_(k-1)k x N_plane) S` generalised to a
    /// mitred corner so both edges at a vertex move by the same distance. Used to
    /// draw P_in and P_out; membership tests use [`Polygon2::signed_distance`].
    pub fn equidistant_offset(&self, s: f64) -> Vec<DVec2> {
        let n = self.vertices.len();
        (0..n)
            .map(|k| {
                let prev = self.vertices[(k + n - 1) % n];
                let here = self.vertices[k];
                let next = self.vertices[(k + 1) % n];
                let n1 = outward_normal(prev, here);
                let n2 = outward_normal(here, next);
                let bisector = (n1 + n2).normalize_or(n1);
                let cos = bisector.dot(n1).max(0.25);
                here + bisector * (s / cos)
            })
            .collect()
    }
}

/// Outward unit normal of the counter-clockwise edge `a -> b`.
fn outward_normal(a: DVec2, b: DVec2) -> DVec2 {
    let e = b - a;
    DVec2::new(e.y, -e.x).normalize_or_zero()
}

/// Shoelace area, positive for counter-clockwise vertices.
pub fn signed_area(v: &[DVec2]) -> f64 {
    let n = v.len();
    0.5 * (0..n).map(|i| v[i].perp_dot(v[(i + 1) % n])).sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Polygon2 {
        // Clockwise on purpose: `new` must reorient it.
        Polygon2::new(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(0.0, 2.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(2.0, 0.0),
        ])
        .unwrap()
    }

    #[test]
    fn inside_distance_and_offset() {
        let sq = square();
        assert!((sq.area() - 4.0).abs() < 1e-12);
        assert!(sq.contains(DVec2::new(1.0, 1.0)) && !sq.contains(DVec2::new(3.0, 1.0)));
        assert!((sq.signed_distance(DVec2::new(1.0, 1.5)) + 0.5).abs() < 1e-12);
        assert!((sq.signed_distance(DVec2::new(3.0, 1.0)) - 1.0).abs() < 1e-12);
        let grown = Polygon2::new(sq.equidistant_offset(0.5)).unwrap();
        assert!((grown.area() - 9.0).abs() < 1e-9);
        let shrunk = Polygon2::new(sq.equidistant_offset(-0.5)).unwrap();
        assert!((shrunk.area() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn degenerate_polygons_are_rejected() {
        assert!(Polygon2::new(vec![DVec2::ZERO, DVec2::X]).is_none());
        assert!(Polygon2::new(vec![DVec2::ZERO, DVec2::X, DVec2::X * 2.0]).is_none());
        assert!(Polygon2::new(vec![DVec2::ZERO, DVec2::X, DVec2::new(f64::NAN, 1.0)]).is_none());
    }
}
