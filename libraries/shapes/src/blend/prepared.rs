//! Clouds prepared once per drag session (Zou et al., Section 2: M_p and M_c):
//! the kd-tree, sampling spacing and oriented normals of the parent, plus for the
//! child its polygon of interest and initial pair (P_I, V_I). Every placement then
//! reuses them.

use super::error::BlendError;
use super::polygon::PolygonOfInterest;
use super::transform::{drop_transform, AdjustTransform, RigidTransform};
use glam::DVec3;
use shroud_geometry::cloud::{
    default_orientation, fit_plane, oriented_normals, to_dvec3, BoundaryParams, NeighbourIndex,
    Orientation,
};
use shroud_msg::LocalAdjust;

/// Clouds smaller than this cannot be blended.
pub const MIN_CLOUD_POINTS: usize = 32;

/// A cloud with its neighbour index, spacing and normals.
#[derive(Debug)]
pub struct Prepared {
    pub index: NeighbourIndex,
    pub normals: Vec<DVec3>,
    /// Median nearest-neighbour distance.
    pub spacing: f64,
}

impl Prepared {
    /// Validates `points` (enough of them, finite, not all coincident), builds the
    /// index and estimates normals from `k` neighbours, made consistent by
    /// propagation and oriented by [`default_orientation`].
    pub fn new(points: &[[f32; 3]], what: &'static str, k: usize) -> Result<Self, BlendError> {
        Self::with_orientation(points, what, k, None)
    }

    /// [`Prepared::new`] with an explicit idea of "outside" (`None`: the default).
    pub fn with_orientation(
        points: &[[f32; 3]],
        what: &'static str,
        k: usize,
        orientation: Option<Orientation>,
    ) -> Result<Self, BlendError> {
        let points = checked(points, what)?;
        let orientation = orientation.unwrap_or_else(|| default_orientation(&points));
        let index = NeighbourIndex::new(points);
        let normals = oriented_normals(&index, k, orientation);
        Self::finish(index, normals, what)
    }

    /// A cloud that already has normals (e.g. the result of an earlier blend).
    pub fn with_normals(
        points: Vec<DVec3>,
        normals: Vec<DVec3>,
        what: &'static str,
    ) -> Result<Self, BlendError> {
        if points.len() < MIN_CLOUD_POINTS {
            return Err(BlendError::TooFewPoints {
                what,
                count: points.len(),
                min: MIN_CLOUD_POINTS,
            });
        }
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return Err(BlendError::NonFinite { what, index });
        }
        let mut normals = normals;
        normals.resize(points.len(), DVec3::ZERO);
        Self::finish(NeighbourIndex::new(points), normals, what)
    }

    fn finish(
        index: NeighbourIndex,
        normals: Vec<DVec3>,
        what: &'static str,
    ) -> Result<Self, BlendError> {
        let spacing = index.spacing(1024);
        if !(spacing > 0.0) {
            return Err(BlendError::Coincident { what });
        }
        Ok(Self {
            index,
            normals,
            spacing,
        })
    }

    pub fn points(&self) -> &[DVec3] {
        self.index.points()
    }

    /// A point on the surface near `at` and its normal: `at` projected on the
    /// least-squares plane of its `k` nearest points, the normal oriented like
    /// the cloud's normal at the nearest point (the `--at` form of the CLI).
    pub fn surface_pair(&self, at: DVec3, k: usize) -> Result<(DVec3, DVec3), BlendError> {
        if !at.is_finite() {
            return Err(BlendError::NotOnSurface);
        }
        let near = self.index.nearest(at, k.max(3));
        let pts = self.points();
        let fit = fit_plane(near.iter().map(|&(i, _)| pts[i]))
            .filter(|f| f.is_two_dimensional(1e-6))
            .ok_or(BlendError::NoTargetNormal)?;
        let reference = near.first().map_or(DVec3::ZERO, |&(i, _)| self.normals[i]);
        let normal = if fit.plane.normal.dot(reference) < 0.0 {
            -fit.plane.normal
        } else {
            fit.plane.normal
        };
        Ok((fit.plane.project(at), normal))
    }
}

fn checked(points: &[[f32; 3]], what: &'static str) -> Result<Vec<DVec3>, BlendError> {
    if points.len() < MIN_CLOUD_POINTS {
        return Err(BlendError::TooFewPoints {
            what,
            count: points.len(),
            min: MIN_CLOUD_POINTS,
        });
    }
    if let Some(index) = points.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
        return Err(BlendError::NonFinite { what, index });
    }
    Ok(points.iter().map(|&p| to_dvec3(p)).collect())
}

/// The child model M_c: its cloud, its polygon of interest and (P_I, V_I).
#[derive(Debug)]
pub struct Child {
    pub cloud: Prepared,
    pub polygon: PolygonOfInterest,
    /// P_I: centroid of the polygon of interest.
    pub p_i: DVec3,
    /// V_I: normal of its least-squares plane, toward the child's body.
    pub v_i: DVec3,
}

impl Child {
    /// Takes `polygon` as P_inter, or detects the longest open boundary loop.
    pub fn new(
        cloud: Prepared,
        polygon: Option<PolygonOfInterest>,
        boundary: &BoundaryParams,
    ) -> Result<Self, BlendError> {
        let polygon = match polygon {
            Some(p) => p,
            None => PolygonOfInterest::detect(&cloud.index, boundary, "child")?,
        };
        let plane = polygon.plane_toward(cloud.points());
        Ok(Self {
            p_i: plane.origin,
            v_i: plane.normal,
            polygon,
            cloud,
        })
    }

    /// The transform dropping the child at (P_T, V_T) (Section 3.2) followed by
    /// the local adjustment (Section 3.3).
    pub fn placement(&self, p_t: DVec3, v_t: DVec3, adjust: &LocalAdjust) -> RigidTransform {
        adjust
            .transform(p_t, v_t)
            .after(&drop_transform(self.p_i, self.v_i, p_t, v_t))
    }
}
