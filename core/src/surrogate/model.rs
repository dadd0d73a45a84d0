//! The result types: a surrogate is a frame, a parameter domain, a trim region and
//! one or two certified spline surfaces.

use super::stats::FitStats;
use super::trim::TrimMask;
use crate::math::Frame;
use crate::spline::UniformCubicSurface;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// Which side of the cloud a surface lies on, seen along the fitting direction.
/// `Upper`: every point is at or below the surface (heights grow toward the
/// viewer, so the surface covers the cloud from the viewer's side). `Lower`: every
/// point is at or above it (the surface is behind the cloud).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    Upper,
    Lower,
}

impl Side {
    /// `upper` or `lower`, as serialised.
    pub fn name(self) -> &'static str {
        match self {
            Side::Upper => "upper",
            Side::Lower => "lower",
        }
    }

    /// `+1` for upper, `-1` for lower: the gap is `sign * (f - w)`.
    #[inline]
    pub fn sign(self) -> f64 {
        match self {
            Side::Upper => 1.0,
            Side::Lower => -1.0,
        }
    }
}

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

/// Affine map from frame coordinates `(u, v)` to spline parameters
/// `s = (u - u_min) / u_step` in `[0, cols-1]`, `t = (v - v_min) / v_step` in `[0, rows-1]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Domain {
    pub u_min: f64,
    pub v_min: f64,
    pub u_step: f64,
    pub v_step: f64,
    pub cols: usize,
    pub rows: usize,
}

/// Slack (in parameter units) under which a parameter just outside `[0, len-1]`
/// still counts as inside: the far edge of the domain is computed by rounding.
pub const DOMAIN_SLACK: f64 = 1e-9;

impl Domain {
    /// The point-to-parameter map with its divisions precomputed. Fitting,
    /// certification and queries all locate points through a `Locator`, so they
    /// agree to the bit.
    pub fn locator(&self, frame: &Frame) -> Locator {
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

    /// `(s, t, w)` of a world point (see [`Locator`]).
    pub fn locate(&self, frame: &Frame, p: DVec3) -> (f64, f64, f64) {
        self.locator(frame).locate(p)
    }

    pub fn locate_f32(&self, frame: &Frame, p: &[f32; 3]) -> (f64, f64, f64) {
        self.locator(frame).locate_f32(p)
    }

    pub fn contains_param(&self, s: f64, t: f64) -> bool {
        let (smax, tmax) = ((self.cols - 1) as f64, (self.rows - 1) as f64);
        (-DOMAIN_SLACK..=smax + DOMAIN_SLACK).contains(&s)
            && (-DOMAIN_SLACK..=tmax + DOMAIN_SLACK).contains(&t)
    }

    /// Frame coordinates `(u, v)` of parameters `(s, t)`.
    pub fn frame_uv(&self, s: f64, t: f64) -> (f64, f64) {
        (self.u_min + s * self.u_step, self.v_min + t * self.v_step)
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

/// The certificate of one surface: every input point was evaluated in f64 against
/// the final surface. `violations` is always 0 in a published surrogate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Certificate {
    pub side: Side,
    /// Unit fitting direction.
    pub direction: [f64; 3],
    pub points_checked: u64,
    pub violations: u64,
    /// Smallest, largest and mean `gap = sign * (f(s,t) - w) >= 0` over all points.
    pub min_gap: f64,
    pub max_gap: f64,
    pub mean_gap: f64,
    /// Points that were on the wrong side before the final monotone correction.
    pub corrected_points: u64,
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
