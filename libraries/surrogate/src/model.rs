//! The result types: a surrogate is a frame, a parameter domain, a trim region and
//! one or two certified spline surfaces.

use super::trim::TrimMask;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use shroud_geometry::math::Frame;
use shroud_geometry::spline::UniformCubicSurface;
pub(crate) use shroud_msg::{Certificate, Domain, FitStats, Side};
use std::str::FromStr;

/// Which surfaces to fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sides {
    Upper,
    Lower,
    /// Both, adjusted so that they never cross inside the trimmed domain.
    Sandwich,
}

impl Sides {
    pub fn list(self) -> &'static [Side] {
        match self {
            Sides::Upper => &[Side::Upper],
            Sides::Lower => &[Side::Lower],
            Sides::Sandwich => &[Side::Upper, Side::Lower],
        }
    }
}

impl FromStr for Sides {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "upper" => Ok(Sides::Upper),
            "lower" => Ok(Sides::Lower),
            "sandwich" => Ok(Sides::Sandwich),
            other => Err(format!(
                "unknown side '{other}': expected upper, lower or sandwich"
            )),
        }
    }
}

/// Where a world point falls on a [`Domain`]: its spline parameters and
/// height in a frame. A trait because the domain is a wire type
/// (`shroud_msg`) that knows no frames.
pub trait DomainLocate {
    /// The point-to-parameter map with its divisions precomputed. Fitting,
    /// certification and queries all locate points through a `Locator`, so they
    /// agree to the bit.
    fn locator(&self, frame: &Frame) -> Locator;

    /// `(s, t, w)` of a world point (see [`Locator`]).
    fn locate(&self, frame: &Frame, p: DVec3) -> (f64, f64, f64) {
        self.locator(frame).locate(p)
    }

    fn locate_f32(&self, frame: &Frame, p: &[f32; 3]) -> (f64, f64, f64) {
        self.locator(frame).locate_f32(p)
    }
}

impl DomainLocate for Domain {
    fn locator(&self, frame: &Frame) -> Locator {
        Locator {
            u: frame.u,
            v: frame.v,
            w: frame.w,
            u_min: self.u_min,
            v_min: self.v_min,
            inv_u: 1.0 / self.u_step,
            inv_v: 1.0 / self.v_step,
        }
    }
}

/// Maps world points to `(s, t, w)`: spline parameters and height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Locator {
    u: DVec3,
    v: DVec3,
    w: DVec3,
    u_min: f64,
    v_min: f64,
    inv_u: f64,
    inv_v: f64,
}

impl Locator {
    #[inline]
    pub fn locate(&self, p: DVec3) -> (f64, f64, f64) {
        (
            (p.dot(self.u) - self.u_min) * self.inv_u,
            (p.dot(self.v) - self.v_min) * self.inv_v,
            p.dot(self.w),
        )
    }

    #[inline]
    pub fn locate_f32(&self, p: &[f32; 3]) -> (f64, f64, f64) {
        self.locate(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
    }
}

/// One certified surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SafeSurface {
    pub side: Side,
    pub surface: UniformCubicSurface,
    pub certificate: Certificate,
}

/// A safe spline surrogate of a point cloud.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Surrogate {
    pub frame: Frame,
    pub domain: Domain,
    pub trim: TrimMask,
    pub upper: Option<SafeSurface>,
    pub lower: Option<SafeSurface>,
    pub stats: FitStats,
}

impl Surrogate {
    /// The certified surfaces, upper first.
    pub fn surfaces(&self) -> impl Iterator<Item = &SafeSurface> {
        self.upper.iter().chain(self.lower.iter())
    }

    pub fn surface(&self, side: Side) -> Option<&SafeSurface> {
        match side {
            Side::Upper => self.upper.as_ref(),
            Side::Lower => self.lower.as_ref(),
        }
    }

    /// World point on the surface of `side` at parameters `(s, t)`.
    pub fn world_point(&self, side: Side, s: f64, t: f64) -> Option<DVec3> {
        let surf = self.surface(side)?;
        let (u, v) = self.domain.frame_uv(s, t);
        Some(
            self.frame
                .to_world(DVec3::new(u, v, surf.surface.eval(s, t))),
        )
    }
}
