//! First hit of a world ray with a trimmed safe surface. Along a ray, `s`, `t`
//! and `w` are linear (Section 1 of the paper), so on each cell
//! `F(τ) = f(s(τ), t(τ)) - w(τ)` is a polynomial of degree 6. The ray is cut into
//! pieces lying in one cell and one trim triangle ([`traversal`](super::traversal)),
//! trimmed pieces are skipped, and on each kept piece `F` is built exactly in
//! Bernstein form and searched by subdivision ([`root`](super::root)). A piece is
//! declared hit-free only when every Bernstein coefficient is provably non-zero
//! with one sign, so a crossing is never missed; a tangential touch, or a value
//! within the rounding margin of zero, is reported as a hit. The reported
//! distance never exceeds the true first crossing by more than the resolution.

use super::bernstein::Bernstein6;
use super::error::QueryError;
use super::kept::kept_closed;
use super::root::{depth_for, first_root};
use super::traversal::{clip, walk, ParamLine, Piece};
use super::view::{SideView, SurrogateView};
use crate::{Side, Surrogate};
use glam::DVec3;
use shroud_geometry::spline::{bezier_patch, BezierPatch};
use std::ops::ControlFlow;

/// Hit distances are resolved to this fraction of `max(1, max_distance)`.
pub const HIT_RESOLUTION: f64 = 1e-12;

/// A Bernstein coefficient within this many ulps of the local magnitude of `f`
/// and `w` is not trusted for its sign (it covers the rounding of the blossoms).
const MARGIN_ULPS: f64 = 256.0;

/// A half-line `origin + λ direction / |direction|`, `λ >= 0` in world units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub direction: DVec3,
}

/// Where a ray first meets a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// World distance from the origin (the direction is normalised).
    pub distance: f64,
    pub point: DVec3,
    pub side: Side,
    /// Spline parameters of the hit.
    pub s: f64,
    pub t: f64,
    /// Unit normal of the graph `w = f(u, v)` in world coordinates, oriented toward
    /// `+w` (toward the viewer, i.e. against the fitting direction) for both sides.
    pub normal: DVec3,
}

/// Ray casting against certified surfaces.
pub trait RayCast {
    /// The nearest hit within `max_distance` (world units), or `None`.
    fn first_hit(&self, ray: &Ray, max_distance: f64) -> Result<Option<RayHit>, QueryError>;
}

impl RayCast for SideView<'_> {
    fn first_hit(&self, ray: &Ray, max_distance: f64) -> Result<Option<RayHit>, QueryError> {
        let direction = validate(ray, max_distance)?;
        Ok(cast(self, ray.origin, direction, max_distance))
    }
}

/// The nearest hit with any present surface (`first_hit_any`); upper wins ties.
impl RayCast for SurrogateView<'_> {
    fn first_hit(&self, ray: &Ray, max_distance: f64) -> Result<Option<RayHit>, QueryError> {
        let direction = validate(ray, max_distance)?;
        let mut best: Option<RayHit> = None;
        for side in self.sides() {
            // A later side only matters if it is hit strictly sooner.
            let limit = best.map_or(max_distance, |b| b.distance);
            if let Some(hit) = cast(&side, ray.origin, direction, limit) {
                if best.is_none_or(|b| hit.distance < b.distance) {
                    best = Some(hit);
                }
            }
        }
        Ok(best)
    }
}

/// The nearest hit of `ray` with any surface of `surrogate`.
pub fn first_hit_any(
    surrogate: &Surrogate,
    ray: &Ray,
    max_distance: f64,
) -> Result<Option<RayHit>, QueryError> {
    SurrogateView::new(surrogate)?.first_hit(ray, max_distance)
}

/// The unit direction of a well-formed ray.
fn validate(ray: &Ray, max_distance: f64) -> Result<DVec3, QueryError> {
    let (o, d) = (ray.origin, ray.direction);
    if !o.is_finite() {
        return Err(QueryError::BadRayOrigin(o.x, o.y, o.z));
    }
    // Scaling by the largest component first keeps huge directions from
    // overflowing the length (which would normalise them to zero).
    let scaled = d / d.abs().max_element();
    let unit = scaled / scaled.length();
    if !d.is_finite() || !unit.is_finite() {
        return Err(QueryError::BadRayDirection(d.x, d.y, d.z));
    }
    if !(max_distance.is_finite() && max_distance >= 0.0) {
        return Err(QueryError::BadMaxDistance(max_distance));
    }
    Ok(unit)
}

fn cast(view: &SideView, origin: DVec3, direction: DVec3, max_distance: f64) -> Option<RayHit> {
    let line = param_line(view, origin, direction);
    if !line.start.iter().all(|x| x.is_finite()) {
        return None; // an origin so far out that its frame coordinates overflow
    }
    let range = clip(&line, view.cells(), [0.0, max_distance])?;
    let lambda = if line.is_vertical() {
        vertical_hit(view, &line, range)
    } else {
        walk_hit(view, &line, range)
    }?;
    Some(hit_at(view, origin, direction, &line, lambda))
}

/// `(s, t, w)` along the ray: the locator's affine map applied to the origin
/// (bit for bit as for cloud points) and to the direction (its linear part).
fn param_line(view: &SideView, origin: DVec3, direction: DVec3) -> ParamLine {
    let (s, t, w) = view.locate(origin);
    let (frame, domain) = (view.frame(), view.domain());
    ParamLine {
        start: [s, t, w],
        slope: [
            direction.dot(frame.u) * (1.0 / domain.u_step),
            direction.dot(frame.v) * (1.0 / domain.v_step),
            direction.dot(frame.w),
        ],
    }
}

/// A ray along `w` projects to one point: a height test against `eval`, the
/// evaluation certification uses.
fn vertical_hit(view: &SideView, line: &ParamLine, [a, b]: [f64; 2]) -> Option<f64> {
    let [s, t, w0] = line.start;
    if !kept_closed(view.trim(), s, t) {
        return None;
    }
    let f = view.surface().eval(s, t);
    let gap = |lambda: f64| f - (w0 + lambda * line.slope[2]);
    let (ga, gb) = (gap(a), gap(b));
    let margin = margin_of(f.abs().max(line.at(a)[2].abs()).max(line.at(b)[2].abs()));
    if ga.abs() <= margin {
        return Some(a);
    }
    if gb.abs() > margin && (ga > 0.0) == (gb > 0.0) {
        return None;
    }
    Some(((f - w0) / line.slope[2]).clamp(a, b))
}

fn walk_hit(view: &SideView, line: &ParamLine, range: [f64; 2]) -> Option<f64> {
    let resolution = HIT_RESOLUTION * range[1].max(1.0);
    let mut cache = CellCache::new();
    let flow = walk(line, view.cells(), range, |piece| {
        match piece_root(view, line, piece, &mut cache, resolution) {
            Some(lambda) => ControlFlow::Break(lambda),
            None => ControlFlow::Continue(()),
        }
    });
    match flow {
        ControlFlow::Break(lambda) => Some(lambda),
        ControlFlow::Continue(()) => None,
    }
}

/// The Bézier patch of the cell the walk is in (pieces come cell by cell).
struct CellCache {
    cell: Option<(usize, usize)>,
    patch: BezierPatch,
    range: (f64, f64),
}

impl CellCache {
    fn new() -> Self {
        Self {
            cell: None,
            patch: BezierPatch([[0.0; 4]; 4]),
            range: (0.0, 0.0),
        }
    }

    fn get(&mut self, view: &SideView, cell: (usize, usize)) -> (&BezierPatch, (f64, f64)) {
        if self.cell != Some(cell) {
            self.patch = bezier_patch(view.surface(), cell.0, cell.1);
            self.range = (self.patch.min(), self.patch.max());
            self.cell = Some(cell);
        }
        (&self.patch, self.range)
    }
}

/// First root on one piece, skipping trimmed pieces and culling by the cell's
/// control-net range before building the degree-6 polynomial.
fn piece_root(
    view: &SideView,
    line: &ParamLine,
    piece: Piece,
    cache: &mut CellCache,
    resolution: f64,
) -> Option<f64> {
    let [a, b] = piece.lambda;
    let mid = line.at(0.5 * (a + b));
    if !kept_closed(view.trim(), mid[0], mid[1]) {
        return None;
    }
    let (patch, (lo, hi)) = cache.get(view, piece.cell);
    let (pa, pb) = (line.at(a), line.at(b));
    let (w_lo, w_hi) = (pa[2].min(pb[2]), pa[2].max(pb[2]));
    let margin = margin_of(lo.abs().max(hi.abs()).max(w_lo.abs()).max(w_hi.abs()));
    if lo - w_hi > margin || hi - w_lo < -margin {
        return None; // the whole cell is above (below) the piece
    }
    let (h, g) = (piece.cell.0 as f64, piece.cell.1 as f64);
    let poly = Bernstein6::along_segment(patch, [pa[0] - h, pb[0] - h], [pa[1] - g, pb[1] - g])
        .minus_linear(pa[2], pb[2]);
    let tau = first_root(&poly, depth_for(resolution / (b - a)), margin)?;
    Some(a + tau * (b - a))
}

#[inline]
fn margin_of(magnitude: f64) -> f64 {
    MARGIN_ULPS * f64::EPSILON * magnitude
}

fn hit_at(
    view: &SideView,
    origin: DVec3,
    direction: DVec3,
    line: &ParamLine,
    lambda: f64,
) -> RayHit {
    let [s, t, _] = line.at(lambda);
    let (fs, ft) = view.surface().gradient(s, t);
    let (frame, domain) = (view.frame(), view.domain());
    // Graph (u, v, f): normal ∝ (-∂f/∂u, -∂f/∂v, 1) in the frame.
    let n = frame.w - frame.u * (fs / domain.u_step) - frame.v * (ft / domain.v_step);
    let len = n.length();
    let normal = if len > 0.0 && len.is_finite() {
        n / len
    } else {
        frame.w
    };
    RayHit {
        distance: lambda,
        point: origin + direction * lambda,
        side: view.side(),
        s,
        t,
        normal,
    }
}
