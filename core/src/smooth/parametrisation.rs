//! How a 3D point becomes a sample of a smooth fit: over a planar domain the
//! point's (x, y) is located and z is the value (a graph); over the
//! cube-sphere the point's direction is located and its distance from the
//! origin is the value (a radial function).

use super::error::SmoothError;
use super::fit::Sample;
use super::locate::PlanarLocator;
use super::sphere::SphereLocator;
use crate::mesh::QuadMesh;

/// A domain's way of turning points into (sample, value) pairs.
#[derive(Debug, Clone)]
pub enum Parametrisation {
    Graph(PlanarLocator),
    Radial(SphereLocator),
}

impl Parametrisation {
    pub fn graph(mesh: &QuadMesh) -> Result<Self, SmoothError> {
        Ok(Self::Graph(PlanarLocator::new(mesh)?))
    }

    pub fn radial(mesh: &QuadMesh) -> Self {
        Self::Radial(SphereLocator::new(mesh))
    }

    /// `"graph"` or `"radial"`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Graph(_) => "graph",
            Self::Radial(_) => "radial",
        }
    }

    /// The sample and value of `p`, or `None` when `p` is outside the domain
    /// (or at the origin of a radial domain, or not finite).
    pub fn sample(&self, p: [f64; 3]) -> Option<(Sample, f64)> {
        if p.iter().any(|x| !x.is_finite()) {
            return None;
        }
        match self {
            Self::Graph(locator) => locator.locate(p[0], p[1]).map(|s| (s, p[2])),
            Self::Radial(locator) => {
                let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                locator.locate(p).map(|s| (s, r))
            }
        }
    }

    /// Samples and values of `points`; the first point outside the domain is
    /// an error.
    pub fn sample_all(&self, points: &[[f64; 3]]) -> Result<(Vec<Sample>, Vec<f64>), SmoothError> {
        let mut samples = Vec::with_capacity(points.len());
        let mut values = Vec::with_capacity(points.len());
        for (index, &p) in points.iter().enumerate() {
            let (s, v) = self.sample(p).ok_or(match self {
                Self::Graph(_) => SmoothError::OutsideDomain {
                    index,
                    x: p[0],
                    y: p[1],
                },
                Self::Radial(_) => SmoothError::NoDirection { index },
            })?;
            samples.push(s);
            values.push(v);
        }
        Ok((samples, values))
    }

    /// Samples and values of the points inside the domain, and how many were
    /// outside (a live sensor sees past any domain; the caller counts them).
    pub fn sample_inside(&self, points: &[[f64; 3]]) -> (Vec<Sample>, Vec<f64>, usize) {
        let mut samples = Vec::with_capacity(points.len());
        let mut values = Vec::with_capacity(points.len());
        for &p in points {
            if let Some((s, v)) = self.sample(p) {
                samples.push(s);
                values.push(v);
            }
        }
        let outside = points.len() - samples.len();
        (samples, values, outside)
    }
}
