//! The vocabulary of a certified surface on the wire: which side of the cloud
//! it lies on, the parameter domain of its grid, and its f64 certificate
//! (paper 000, Section 6).

use serde::{Deserialize, Serialize};

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
