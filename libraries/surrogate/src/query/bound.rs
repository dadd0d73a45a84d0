//! Conservative height bounds of a surface over an axis-aligned rectangle of the
//! domain. Over each cell the rectangle covers, the cell's bicubic Bézier patch is
//! restricted to the covered part; by the convex hull property the surface there
//! lies between the smallest and largest control point of the restricted net,
//! which is tighter than the raw B-spline coefficients and tightens further as
//! the part is subdivided (`refine`). Results are padded outward by the rounding
//! bound of the restriction, so they are never inside the true range.

use super::bernstein::patch_on_rect;
use super::error::QueryError;
use super::view::SideView;
use shroud_geometry::spline::{bezier_patch, BezierPatch};

/// Deepest refinement: `4^MAX_REFINE` sub-rectangles per cell.
pub const MAX_REFINE: u32 = 6;

/// Outward padding, in ulps of the largest control point involved: the rounding
/// of two nested cubic restrictions (six lerps) with room to spare.
const PAD_ULPS: f64 = 64.0;

/// A rectangle in spline parameters; corners in any order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamRect {
    pub s: [f64; 2],
    pub t: [f64; 2],
}

/// A rectangle in frame coordinates `(u, v)`; corners in any order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvRect {
    pub u: [f64; 2],
    pub v: [f64; 2],
}

/// Which cells count.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CellFilter {
    /// Cells with at least one kept triangle (the surrogate's actual extent),
    /// including cells that touch the rectangle only along an edge.
    #[default]
    Kept,
    /// Every cell, trimmed or not.
    All,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BoundOptions {
    pub cells: CellFilter,
    /// Subdivide each covered part `refine` times in both directions (`4^refine`
    /// pieces) and bound each piece: tighter, still conservative.
    pub refine: u32,
}

/// `min <= f <= max` wherever the query looked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeightRange {
    pub min: f64,
    pub max: f64,
}

/// Height bounds over rectangles.
pub trait BoundQuery {
    /// Bounds over the part of `rect` inside the domain; `None` when that part is
    /// empty or (with [`CellFilter::Kept`]) meets no kept cell.
    fn range_over_params(
        &self,
        rect: ParamRect,
        options: BoundOptions,
    ) -> Result<Option<HeightRange>, QueryError>;

    /// [`Self::range_over_params`] for a rectangle in frame coordinates; its
    /// parameter image is widened by a few ulps so rounding cannot shrink it.
    fn range_over_uv(
        &self,
        rect: UvRect,
        options: BoundOptions,
    ) -> Result<Option<HeightRange>, QueryError>;

    fn upper_bound(
        &self,
        rect: ParamRect,
        options: BoundOptions,
    ) -> Result<Option<f64>, QueryError> {
        Ok(self.range_over_params(rect, options)?.map(|r| r.max))
    }

    fn lower_bound(
        &self,
        rect: ParamRect,
        options: BoundOptions,
    ) -> Result<Option<f64>, QueryError> {
        Ok(self.range_over_params(rect, options)?.map(|r| r.min))
    }
}

impl BoundQuery for SideView<'_> {
    fn range_over_params(
        &self,
        rect: ParamRect,
        options: BoundOptions,
    ) -> Result<Option<HeightRange>, QueryError> {
        if !(rect.s.iter().chain(&rect.t).all(|x| x.is_finite())) {
            return Err(QueryError::NonFiniteRect(rect.s, rect.t));
        }
        if options.refine > MAX_REFINE {
            return Err(QueryError::RefineTooDeep {
                depth: options.refine,
                max: MAX_REFINE,
            });
        }
        let (cs, ct) = self.cells();
        let (Some(s), Some(t)) = (clip_interval(rect.s, cs), clip_interval(rect.t, ct)) else {
            return Ok(None);
        };
        let closed = options.cells == CellFilter::Kept;
        let (h_span, g_span) = (cell_span(s, cs, closed), cell_span(t, ct, closed));
        let mut acc = Accumulator::new();
        for g in g_span.0..=g_span.1 {
            for h in h_span.0..=h_span.1 {
                if closed && !self.trim().cell_kept(h, g) {
                    continue;
                }
                let patch = bezier_patch(self.surface(), h, g);
                let local = |x: [f64; 2], cell: usize| x.map(|x| (x - cell as f64).clamp(0.0, 1.0));
                acc.add(&patch, local(s, h), local(t, g), options.refine);
            }
        }
        Ok(acc.finish())
    }

    fn range_over_uv(
        &self,
        rect: UvRect,
        options: BoundOptions,
    ) -> Result<Option<HeightRange>, QueryError> {
        if !(rect.u.iter().chain(&rect.v).all(|x| x.is_finite())) {
            return Err(QueryError::NonFiniteRect(rect.u, rect.v));
        }
        let (s0, t0) = self.params_of_uv(rect.u[0].min(rect.u[1]), rect.v[0].min(rect.v[1]));
        let (s1, t1) = self.params_of_uv(rect.u[0].max(rect.u[1]), rect.v[0].max(rect.v[1]));
        let widen = |x: f64| 8.0 * f64::EPSILON * (1.0 + x.abs());
        let rect = ParamRect {
            s: [s0 - widen(s0), s1 + widen(s1)],
            t: [t0 - widen(t0), t1 + widen(t1)],
        };
        self.range_over_params(rect, options)
    }
}

/// The sorted interval clipped to `[0, cells]`, or `None` when it misses it.
fn clip_interval(x: [f64; 2], cells: usize) -> Option<[f64; 2]> {
    let lo = x[0].min(x[1]).max(0.0);
    let hi = x[0].max(x[1]).min(cells as f64);
    (lo <= hi).then_some([lo, hi])
}

/// First and last cell meeting `[x0, x1]` (inside `[0, cells]`): half-open cells
/// `[h, h+1)`, or with `closed` every cell whose closed interval meets it.
fn cell_span([x0, x1]: [f64; 2], cells: usize, closed: bool) -> (usize, usize) {
    let last = (cells - 1) as f64;
    let (lo, hi) = if closed {
        (x0.ceil() - 1.0, x1.floor())
    } else {
        (x0.floor(), x1.ceil() - 1.0)
    };
    let lo = lo.clamp(0.0, last);
    (lo as usize, hi.clamp(lo, last) as usize)
}

/// Running min and max of control nets, and the magnitude that sets the padding.
struct Accumulator {
    min: f64,
    max: f64,
    magnitude: f64,
}

impl Accumulator {
    fn new() -> Self {
        Self {
            min: f64::INFINITY,
            max: f64::NEG_INFINITY,
            magnitude: 0.0,
        }
    }

    /// Bounds the patch over local `[s0, s1] x [t0, t1]`, split into `2^refine`
    /// equal parts per direction (dyadic, so the split points are exact).
    fn add(&mut self, patch: &BezierPatch, s: [f64; 2], t: [f64; 2], refine: u32) {
        self.magnitude = self.magnitude.max(patch.min().abs()).max(patch.max().abs());
        let n = 1u32 << refine;
        let at = |x: [f64; 2], k: u32| x[0] + (x[1] - x[0]) * (k as f64 / n as f64);
        for j in 0..n {
            let tj = [at(t, j), at(t, j + 1)];
            for i in 0..n {
                let net = patch_on_rect(patch, [at(s, i), at(s, i + 1)], tj);
                for &c in net.iter().flatten() {
                    self.min = self.min.min(c);
                    self.max = self.max.max(c);
                }
            }
        }
    }

    fn finish(&self) -> Option<HeightRange> {
        let pad = PAD_ULPS * f64::EPSILON * self.magnitude;
        (self.min <= self.max).then_some(HeightRange {
            min: self.min - pad,
            max: self.max + pad,
        })
    }
}
