//! The polygon of interest P_inter (Zou et al., Section 3.1): a detected open
//! boundary loop of the child or a given polyline. Its centroid is P_I and the
//! normal of its least-squares plane is V_I.

use super::error::BlendError;
use super::polygon2d::Polygon2;
use glam::{DVec2, DVec3};
use shroud_geometry::cloud::{find_rim, fit_plane, BoundaryParams, NeighbourIndex, Plane};

/// Closed polyline in 3D, validated as non-degenerate (it spans an area).
#[derive(Debug, Clone, PartialEq)]
pub struct PolygonOfInterest {
    vertices: Vec<DVec3>,
}

/// Loops are resampled to at most this many vertices by arc length.
pub const MAX_POLYGON_VERTICES: usize = 128;

impl PolygonOfInterest {
    /// A given polyline (implicitly closed). Errors if it has fewer than three
    /// vertices, a non-finite one, or does not enclose an area in its plane.
    pub fn from_polyline(vertices: Vec<DVec3>) -> Result<Self, BlendError> {
        let degenerate = |reason: &str| BlendError::DegeneratePolygon {
            reason: reason.to_owned(),
        };
        if vertices.len() < 3 {
            return Err(degenerate("fewer than three vertices"));
        }
        if vertices.iter().any(|v| !v.is_finite()) {
            return Err(degenerate("a vertex is not finite"));
        }
        let poly = Self { vertices };
        let fit = fit_plane(poly.vertices.iter().copied())
            .ok_or_else(|| degenerate("no least-squares plane"))?;
        if !fit.is_two_dimensional(1e-8) {
            return Err(degenerate("the vertices are collinear or coincide"));
        }
        let outline = poly.project(&fit.plane);
        let area = outline.as_ref().map_or(0.0, Polygon2::area);
        let perimeter = outline.as_ref().map_or(0.0, Polygon2::perimeter);
        if !(area > 1e-4 * perimeter * perimeter) {
            return Err(degenerate(
                "the outline encloses (almost) no area in its least-squares plane",
            ));
        }
        Ok(poly)
    }

    /// The loop `indices` of `points`, resampled by arc length to at most
    /// `max_vertices` vertices (which also smooths the boundary band's zigzag).
    pub fn from_loop(
        points: &[DVec3],
        indices: &[usize],
        max_vertices: usize,
    ) -> Result<Self, BlendError> {
        let loop_points: Vec<DVec3> = indices
            .iter()
            .filter_map(|&i| points.get(i).copied())
            .collect();
        Self::from_polyline(resample_closed(&loop_points, max_vertices.max(3)))
    }

    /// The rim of the cloud in `index` (its longest open-boundary loop, see
    /// [`find_rim`]); `what` names the cloud in the error.
    pub fn detect(
        index: &NeighbourIndex,
        params: &BoundaryParams,
        what: &'static str,
    ) -> Result<Self, BlendError> {
        let rim = find_rim(index, params)
            .map_err(|reason| BlendError::NoBoundaryLoop { what, reason })?;
        Self::from_loop(index.points(), &rim.indices, MAX_POLYGON_VERTICES)
    }

    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// P_I: the centroid of the vertices.
    pub fn centroid(&self) -> DVec3 {
        self.vertices.iter().copied().sum::<DVec3>() / self.vertices.len() as f64
    }

    /// The least-squares plane P_f through the vertices, through their centroid.
    /// Its normal's sign is that of the fit; see [`PolygonOfInterest::plane_toward`].
    pub fn plane(&self) -> Plane {
        fit_plane(self.vertices.iter().copied())
            .map(|f| f.plane)
            .unwrap_or(Plane {
                origin: self.centroid(),
                normal: DVec3::Z,
            })
    }

    /// P_f with its normal pointing to the side where `body` (the child's points)
    /// mostly lies: V_I, so that dropping turns the child's body onto the
    /// parent's outward normal.
    pub fn plane_toward(&self, body: &[DVec3]) -> Plane {
        let plane = self.plane();
        let side: f64 = body.iter().map(|&p| plane.height(p)).sum();
        if side < 0.0 {
            plane.flipped()
        } else {
            plane
        }
    }

    /// The outline projected into `plane`'s frame (counter-clockwise), or `None`
    /// when it encloses no area there.
    pub fn project(&self, plane: &Plane) -> Option<Polygon2> {
        let (u, v) = plane.basis();
        Polygon2::new(
            self.vertices
                .iter()
                .map(|&p| {
                    let d = p - plane.origin;
                    DVec2::new(d.dot(u), d.dot(v))
                })
                .collect(),
        )
    }

    /// The polygon moved by `t`.
    pub fn transformed(&self, t: &super::transform::RigidTransform) -> Self {
        Self {
            vertices: self.vertices.iter().map(|&p| t.apply(p)).collect(),
        }
    }
}

/// `count` points evenly spaced by arc length along the closed polyline `points`
/// (returned unchanged when it has at most `count` points).
fn resample_closed(points: &[DVec3], count: usize) -> Vec<DVec3> {
    let n = points.len();
    if n <= count {
        return points.to_vec();
    }
    let mut cumulative = Vec::with_capacity(n + 1);
    cumulative.push(0.0);
    for i in 0..n {
        let step = points[i].distance(points[(i + 1) % n]);
        cumulative.push(cumulative[i] + step);
    }
    let total = cumulative[n];
    if !(total > 0.0) {
        return points[..count].to_vec();
    }
    let mut out = Vec::with_capacity(count);
    let mut seg = 0;
    for k in 0..count {
        let s = total * k as f64 / count as f64;
        while seg + 1 < n && cumulative[seg + 1] < s {
            seg += 1;
        }
        let len = cumulative[seg + 1] - cumulative[seg];
        let t = if len > 0.0 {
            (s - cumulative[seg]) / len
        } else {
            0.0
        };
        out.push(points[seg].lerp(points[(seg + 1) % n], t));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_is_accepted_and_resampled() {
        let circle: Vec<DVec3> = (0..500)
            .map(|i| {
                let a = f64::from(i) * std::f64::consts::TAU / 500.0;
                DVec3::new(a.cos(), a.sin(), 0.2)
            })
            .collect();
        let idx: Vec<usize> = (0..500).collect();
        let poly = PolygonOfInterest::from_loop(&circle, &idx, 64).unwrap();
        assert_eq!(poly.vertices().len(), 64);
        assert!((poly.centroid() - DVec3::new(0.0, 0.0, 0.2)).length() < 1e-9);
        let body = [DVec3::new(0.0, 0.0, 1.0)];
        assert!(poly.plane_toward(&body).normal.dot(DVec3::Z) > 0.999);
    }

    #[test]
    fn degenerate_outlines_are_errors() {
        let line: Vec<DVec3> = (0..5).map(|i| DVec3::X * f64::from(i)).collect();
        assert!(matches!(
            PolygonOfInterest::from_polyline(line),
            Err(BlendError::DegeneratePolygon { .. })
        ));
        let two = vec![DVec3::ZERO, DVec3::X];
        assert!(PolygonOfInterest::from_polyline(two).is_err());
        let nan = vec![DVec3::ZERO, DVec3::X, DVec3::new(0.0, f64::NAN, 0.0)];
        assert!(PolygonOfInterest::from_polyline(nan).is_err());
        // A "bow tie" back and forth along a line with a tiny wiggle: no area.
        let sliver = vec![
            DVec3::ZERO,
            DVec3::new(1.0, 1e-7, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(1.0, -1e-7, 0.0),
        ];
        assert!(PolygonOfInterest::from_polyline(sliver).is_err());
    }
}
