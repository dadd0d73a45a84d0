//! Validated, borrowed views of a surrogate. A surrogate may come from a file, so
//! its parts are checked against each other once, when the view is made; every
//! query afterwards indexes without panicking and allocates nothing.

use super::error::QueryError;
use crate::DomainLocate;
use crate::{Domain, SafeSurface, Side, Surrogate, TrimMask};
use glam::DVec3;
use shroud_geometry::math::Frame;
use shroud_geometry::spline::UniformCubicSurface;

/// One certified surface with the frame, domain and trim it lives in.
#[derive(Debug, Clone, Copy)]
pub struct SideView<'a> {
    frame: &'a Frame,
    domain: &'a Domain,
    trim: &'a TrimMask,
    side: Side,
    surface: &'a SafeSurface,
}

/// Which surfaces a surrogate holds: never none.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Present<'a> {
    One(SideView<'a>),
    Sandwich {
        upper: SideView<'a>,
        lower: SideView<'a>,
    },
}

/// All surfaces of a surrogate.
#[derive(Debug, Clone, Copy)]
pub struct SurrogateView<'a> {
    present: Present<'a>,
}

impl<'a> SurrogateView<'a> {
    /// Checks that frame, domain, trim mask and surfaces agree.
    pub fn new(surrogate: &'a Surrogate) -> Result<Self, QueryError> {
        check_frame(&surrogate.frame)?;
        check_domain(&surrogate.domain)?;
        check_trim(&surrogate.trim, &surrogate.domain)?;
        let view = |slot: Side, safe: &'a SafeSurface| -> Result<SideView<'a>, QueryError> {
            check_surface(slot, safe, &surrogate.domain)?;
            Ok(SideView {
                frame: &surrogate.frame,
                domain: &surrogate.domain,
                trim: &surrogate.trim,
                side: slot,
                surface: safe,
            })
        };
        let upper = surrogate
            .upper
            .as_ref()
            .map(|s| view(Side::Upper, s))
            .transpose()?;
        let lower = surrogate
            .lower
            .as_ref()
            .map(|s| view(Side::Lower, s))
            .transpose()?;
        let present = match (upper, lower) {
            (Some(upper), Some(lower)) => Present::Sandwich { upper, lower },
            (Some(one), None) | (None, Some(one)) => Present::One(one),
            (None, None) => return Err(QueryError::NoSurface),
        };
        Ok(Self { present })
    }

    /// The upper surface, if present.
    pub fn upper(&self) -> Option<SideView<'a>> {
        self.side(Side::Upper)
    }

    /// The lower surface, if present.
    pub fn lower(&self) -> Option<SideView<'a>> {
        self.side(Side::Lower)
    }

    pub fn side(&self, side: Side) -> Option<SideView<'a>> {
        self.sides().find(|v| v.side == side)
    }

    /// The present surfaces, upper first.
    pub fn sides(&self) -> impl Iterator<Item = SideView<'a>> {
        let (first, second) = match self.present {
            Present::One(one) => (one, None),
            Present::Sandwich { upper, lower } => (upper, Some(lower)),
        };
        std::iter::once(first).chain(second)
    }

    pub(crate) fn present(&self) -> Present<'a> {
        self.present
    }

    /// Any surface (they share frame, domain and trim).
    pub(crate) fn any(&self) -> SideView<'a> {
        match self.present {
            Present::One(one) => one,
            Present::Sandwich { upper, .. } => upper,
        }
    }
}

impl<'a> SideView<'a> {
    /// The view of one side; fails when the surrogate lacks it or is inconsistent.
    pub fn new(surrogate: &'a Surrogate, side: Side) -> Result<Self, QueryError> {
        SurrogateView::new(surrogate)?
            .side(side)
            .ok_or(QueryError::MissingSide(side))
    }

    pub fn side(&self) -> Side {
        self.side
    }

    pub fn frame(&self) -> &'a Frame {
        self.frame
    }

    pub fn domain(&self) -> &'a Domain {
        self.domain
    }

    pub fn trim(&self) -> &'a TrimMask {
        self.trim
    }

    pub fn safe_surface(&self) -> &'a SafeSurface {
        self.surface
    }

    pub fn surface(&self) -> &'a UniformCubicSurface {
        &self.surface.surface
    }

    /// `(s, t, w)` of a world point, by the same map (`Domain::locator`) the fitter
    /// and the certificate use, so results agree with them to the bit.
    pub fn locate(&self, p: DVec3) -> (f64, f64, f64) {
        self.domain.locator(self.frame).locate(p)
    }

    /// [`Self::locate`] with the divisions hoisted, for loops over many points.
    pub fn locator(&self) -> impl Fn(DVec3) -> (f64, f64, f64) + Copy {
        let locator = self.domain.locator(self.frame);
        move |p| locator.locate(p)
    }

    /// Parameters of frame coordinates, with the exact operations of the locator
    /// (so `(u, v) = (p.u, p.v)` gives the parameters of `p` to the bit).
    pub fn params_of_uv(&self, u: f64, v: f64) -> (f64, f64) {
        (
            (u - self.domain.u_min) * (1.0 / self.domain.u_step),
            (v - self.domain.v_min) * (1.0 / self.domain.v_step),
        )
    }

    /// Cells along s and t.
    pub fn cells(&self) -> (usize, usize) {
        (self.domain.cols - 1, self.domain.rows - 1)
    }
}

fn check_frame(frame: &Frame) -> Result<(), QueryError> {
    let finite = frame.u.is_finite() && frame.v.is_finite() && frame.w.is_finite();
    finite.then_some(()).ok_or(QueryError::BadFrame)
}

fn check_domain(d: &Domain) -> Result<(), QueryError> {
    let step_ok = |x: f64| x.is_finite() && x > 0.0 && (1.0 / x).is_finite();
    let ok = d.cols >= 2
        && d.rows >= 2
        && d.u_min.is_finite()
        && d.v_min.is_finite()
        && step_ok(d.u_step)
        && step_ok(d.v_step);
    ok.then_some(()).ok_or(QueryError::BadDomain(*d))
}

fn check_trim(trim: &TrimMask, d: &Domain) -> Result<(), QueryError> {
    let (expected_s, expected_t) = (d.cols - 1, d.rows - 1);
    let ok = trim.cells_s == expected_s
        && trim.cells_t == expected_t
        && Some(trim.bits.len()) == expected_s.checked_mul(expected_t);
    ok.then_some(()).ok_or(QueryError::TrimMismatch {
        cells_s: trim.cells_s,
        cells_t: trim.cells_t,
        bits: trim.bits.len(),
        expected_s,
        expected_t,
    })
}

fn check_surface(slot: Side, safe: &SafeSurface, d: &Domain) -> Result<(), QueryError> {
    if safe.side != slot {
        return Err(QueryError::SideMismatch {
            slot,
            stored: safe.side,
        });
    }
    let s = &safe.surface;
    if s.cols != d.cols
        || s.rows != d.rows
        || Some(s.coefficients.len()) != s.cols.checked_mul(s.rows)
    {
        return Err(QueryError::GridMismatch {
            side: slot,
            surface_cols: s.cols,
            surface_rows: s.rows,
            coefficients: s.coefficients.len(),
            domain_cols: d.cols,
            domain_rows: d.rows,
        });
    }
    match s.coefficients.iter().position(|c| !c.is_finite()) {
        Some(index) => Err(QueryError::NonFiniteCoefficient { side: slot, index }),
        None => Ok(()),
    }
}
