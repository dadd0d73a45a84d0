//! How a 3D point becomes a sample of a smooth fit: over a planar domain the
//! point's (x, y) is located and z is the value (a graph); over the
//! cube-sphere the point's direction is located and its distance from the
//! origin is the value (a radial function); around a domain mesh in space the
//! point's foot point on the mesh gives the parameters and the point itself
//! is the value (a parametric surface in R^3, refined by parameter
//! correction).

use super::error::SmoothError;
use super::locate::PlanarLocator;
use super::sample::Sample;
use super::sphere::SphereLocator;
use super::surface_locator::SurfaceLocator;
use crate::mesh::QuadMesh;

/// A domain's way of turning points into (sample, value) pairs.
#[derive(Debug)]
pub enum Parametrisation {
    Graph(PlanarLocator),
    Radial(SphereLocator),
    Parametric(SurfaceLocator),
}

impl Parametrisation {
    pub fn graph(mesh: &QuadMesh) -> Result<Self, SmoothError> {
        Ok(Self::Graph(PlanarLocator::new(mesh)?))
    }

    pub fn radial(mesh: &QuadMesh) -> Self {
        Self::Radial(SphereLocator::new(mesh))
    }

    pub fn parametric(mesh: &QuadMesh) -> Result<Self, SmoothError> {
        Ok(Self::Parametric(SurfaceLocator::new(mesh)?))
    }

    /// `"graph"`, `"radial"` or `"parametric"`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Graph(_) => "graph",
            Self::Radial(_) => "radial",
            Self::Parametric(_) => "parametric",
        }
    }

    /// Components of each fitted value: 1 (a height or a radius) or 3.
    pub fn dim(&self) -> usize {
        match self {
            Self::Parametric(_) => 3,
            _ => 1,
        }
    }

    /// The sample and value of `p` (its first `dim()` entries), or `None` when
    /// `p` is outside the domain (or at the origin of a radial domain, or not
    /// finite).
    pub fn sample(&self, p: [f64; 3]) -> Option<(Sample, [f64; 3])> {
        if p.iter().any(|x| !x.is_finite()) {
            return None;
        }
        match self {
            Self::Graph(locator) => locator.locate(p[0], p[1]).map(|s| (s, [p[2], 0.0, 0.0])),
            Self::Radial(locator) => {
                let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                locator.locate(p).map(|s| (s, [r, 0.0, 0.0]))
            }
            Self::Parametric(locator) => locator.locate(p).map(|s| (s, p)),
        }
    }

    /// Samples and values (`dim()` per sample) of `points`; the first point
    /// outside the domain is an error.
    pub fn sample_all(&self, points: &[[f64; 3]]) -> Result<(Vec<Sample>, Vec<f64>), SmoothError> {
        let located = self.locate_many(points);
        let mut samples = Vec::with_capacity(points.len());
        let mut values = Vec::with_capacity(points.len() * self.dim());
        for (index, (p, found)) in points.iter().zip(located).enumerate() {
            let (s, v) = found.ok_or(match self {
                _ if p.iter().any(|x| !x.is_finite()) => SmoothError::NonFinitePoint { index },
                Self::Graph(_) => SmoothError::OutsideDomain {
                    index,
                    x: p[0],
                    y: p[1],
                },
                Self::Radial(_) => SmoothError::NoDirection { index },
                Self::Parametric(_) => SmoothError::NonFinitePoint { index },
            })?;
            samples.push(s);
            values.extend_from_slice(&v[..self.dim()]);
        }
        Ok((samples, values))
    }

    /// Samples and values of the points inside the domain, and how many were
    /// outside (a live sensor sees past any domain; the caller counts them).
    pub fn sample_inside(&self, points: &[[f64; 3]]) -> (Vec<Sample>, Vec<f64>, usize) {
        let mut samples = Vec::with_capacity(points.len());
        let mut values = Vec::with_capacity(points.len() * self.dim());
        for (s, v) in self.locate_many(points).into_iter().flatten() {
            samples.push(s);
            values.extend_from_slice(&v[..self.dim()]);
        }
        let outside = points.len() - samples.len();
        (samples, values, outside)
    }

    /// Locates every point, in parallel (foot points are the costly part of a
    /// parametric fit's set-up).
    fn locate_many(&self, points: &[[f64; 3]]) -> Vec<Option<(Sample, [f64; 3])>> {
        use rayon::prelude::*;
        points.par_iter().map(|&p| self.sample(p)).collect()
    }
}
