//! The envelope of a surrogate: once per surrogate, every kept cell gets a box in
//! frame coordinates `(u, v, h)` that holds every certified cloud point of the
//! cell, and the Bézier patches the clearance refines.
//!
//! Why the box holds the points. A certified point `p` has parameters
//! `(s, t) = locate(p)` in a closed kept triangle of the cell `(h, g)` that
//! `knot_interval` assigns (trim keeps every triangle holding a point; parameters
//! in the domain slack clamp to the edge cells), and its height satisfies
//! `lower(s, t) <= w <= upper(s, t)` as evaluated in f64 (a one-sided surrogate
//! bounds one side only: the other is `-inf` or `+inf`). So:
//!
//! - `(s - h, t - g)` lies in the bounding rectangle of the cell's kept
//!   triangles, and `(u, v)` of `p` in that rectangle mapped to frame
//!   coordinates, up to the domain slack and the rounding of the locator (both
//!   covered by padding the rectangle with `margin`, and its sides on the
//!   domain's border by `DOMAIN_SLACK * step` more);
//! - over that rectangle the surface is a bicubic Bézier patch whose restricted
//!   control net bounds it (convex hull property: the Bernstein weights are
//!   non-negative and sum to one), so `upper <= max(net)`, `lower >= min(net)`;
//!   f64 evaluation and the net's own rounding differ from the exact values by
//!   a few ulps of the largest control point, which the height padding covers.
//!   The Bézier net of a cell lies in the convex hull of its 16 B-spline
//!   coefficients, so this is never looser than the coefficients' min and max.
//!
//! Everything outside the domain, and over trimmed triangles, holds no
//! certified point: the sensor did not see it, and the guard counts it as
//! possibly occupied at every height (`unseen`).
// Small fixed-size matrices and nets are clearer with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::error::GuardError;
use super::field_of_view::ViewRegion;
use super::no_return::DarkCones;
use super::trimmed::Trimmed;
use glam::DVec3;
use shroud_geometry::math::Frame;
use shroud_geometry::spline::{bezier_patch, BezierPatch, UniformCubicSurface};
use shroud_msg::{FieldOfView, NoReturn};
use shroud_surrogate::query::{kept_closed, patch_on_rect, SideView, SurrogateView};
use shroud_surrogate::trim::{ALL, BOTTOM, LEFT, RIGHT, TOP};
use shroud_surrogate::DomainLocate;
use shroud_surrogate::{Domain, Locator, Surrogate, TrimMask, DOMAIN_SLACK};
use std::sync::OnceLock;

/// Geometric margin, relative to the largest coordinate magnitude involved:
/// covers the locator's and the frame's rounding (a few ulps) many times over.
pub(crate) const MARGIN_REL: f64 = 1e-12;

/// Height padding of a control net, in ulps of its largest control point (plus
/// one unit): B-spline to Bézier conversion, restriction and f64 evaluation.
/// Each refinement level adds [`PAD_ULPS_PER_LEVEL`] for its subdivision.
pub(crate) const PAD_ULPS: f64 = 256.0;
pub(crate) const PAD_ULPS_PER_LEVEL: f64 = 64.0;

/// Frames further from orthonormal than this are refused (a fitted frame is
/// within a few ulps).
pub(crate) const MAX_FRAME_ERROR: f64 = 1e-9;

/// Largest deviation of the frame's Gram matrix from the identity.
fn orthonormality_error(f: &Frame) -> f64 {
    let (u, v, w) = (f.u, f.v, f.w);
    [
        u.dot(u) - 1.0,
        v.dot(v) - 1.0,
        w.dot(w) - 1.0,
        u.dot(v),
        u.dot(w),
        v.dot(w),
    ]
    .iter()
    .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// A padded axis-aligned box in frame coordinates `(u, v, h)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellBox {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

/// What the refinement of one kept cell starts from.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CellPatches {
    /// Kept triangle bits of the cell.
    pub kept: u8,
    /// Local parameters of the kept triangles' bounding rectangle, in `[0, 1]`.
    pub s: [f64; 2],
    pub t: [f64; 2],
    /// The surfaces' patches restricted to that rectangle (a side that is
    /// absent holds zeros and is never read).
    pub upper: BezierPatch,
    pub lower: BezierPatch,
    /// Largest control point magnitude of the cell (sets the height padding).
    pub magnitude: f64,
}

/// A quarter of a piece of a kept cell, the same for every shape: its local
/// rectangle `s` x `t`, its frame box with its parent's height range (a
/// cheap first bound), its own padded height range (never looser than the
/// parent's) and its restricted patches (`guard::clearance` refines by them),
/// and its own split once a shape needed it (near the top of the tree only).
#[derive(Debug, Clone)]
pub(crate) struct Piece {
    pub s: [f64; 2],
    pub t: [f64; 2],
    pub near: CellBox,
    pub h: [f64; 2],
    pub upper: BezierPatch,
    pub lower: BezierPatch,
    pub split: OnceLock<Box<Split>>,
}

/// The four quarters of a piece, `None` where no kept triangle is met.
pub(crate) type Split = [Option<Piece>; 4];

/// Per-surrogate precomputation for clearance queries.
#[derive(Debug, Clone)]
pub struct Envelope {
    frame: Frame,
    domain: Domain,
    cells_s: usize,
    cells_t: usize,
    has_upper: bool,
    has_lower: bool,
    /// Every cell, row-major `g * cells_s + h`; trimmed cells hold
    /// [`CellBox::EMPTY`].
    boxes: Vec<CellBox>,
    /// Per row of cells, the bounding box of its kept boxes (empty rows:
    /// [`CellBox::EMPTY`]).
    row_boxes: Vec<CellBox>,
    /// The surfaces and trim, for the exact test of a sphere centre.
    upper_surface: Option<UniformCubicSurface>,
    lower_surface: Option<UniformCubicSurface>,
    trim: TrimMask,
    /// The trimmed triangles, for the unseen search (`guard::trimmed`).
    trimmed: Trimmed,
    locator: Locator,
    patches: Vec<CellPatches>,
    /// Per cell, its split, computed when a shape first needs it and kept
    /// with the envelope (it depends on the surrogate alone); the pieces
    /// keep theirs below it (`guard::clearance`).
    first_splits: Vec<OnceLock<Box<Split>>>,
    /// Absolute geometric margin of this surrogate.
    margin: f64,
    /// Extra padding in `u` and `v` of rectangles on the domain's border.
    slack_pad: [f64; 2],
    /// `1 / u_step`, `1 / v_step`.
    inv_step: [f64; 2],
    /// Per axis: the cell count as a float, and how far boxes reach past
    /// their cells (`span` asks for both on every row it looks at).
    cells_f: [f64; 2],
    span_pad: [f64; 2],
    /// [`Self::uv_extent`], computed once.
    extent: ([f64; 2], [f64; 2]),
    /// How far the frame is from orthonormal (distances in frame coordinates
    /// are world distances up to a factor `1 +- 3 frame_error`).
    frame_error: f64,
    kept_cells: usize,
    /// The region the source cloud's sensor covered, when the cloud said:
    /// space outside it is unseen (`guard::field_of_view`).
    field_of_view: Option<FieldOfView>,
    /// The same, ready for depth queries.
    view_region: Option<ViewRegion>,
    /// The directions in which the source cloud's sensor got no return,
    /// when the cloud said: unseen too (`guard::no_return`).
    dark: Option<DarkCones>,
}

impl CellBox {
    /// The box of a trimmed cell: no point is in it.
    pub const EMPTY: CellBox = CellBox {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    pub fn is_empty(&self) -> bool {
        self.lo[0] > self.hi[0]
    }

    /// The bounding box of both.
    pub(crate) fn union(&self, other: &CellBox) -> CellBox {
        CellBox {
            lo: std::array::from_fn(|k| self.lo[k].min(other.lo[k])),
            hi: std::array::from_fn(|k| self.hi[k].max(other.hi[k])),
        }
    }
}

impl Envelope {
    /// Validates the surrogate (frame, domain, trim and surfaces agree, finite
    /// coefficients) and precomputes the cell boxes.
    pub fn new(surrogate: &Surrogate) -> Result<Self, GuardError> {
        let view = SurrogateView::new(surrogate)?;
        let (upper, lower) = (view.upper(), view.lower());
        let any = upper.or(lower).ok_or(GuardError::Surrogate(
            shroud_surrogate::query::QueryError::NoSurface,
        ))?;
        let domain = *any.domain();
        let trim = any.trim();
        let (cells_s, cells_t) = any.cells();
        let u_max = domain.u_min + cells_s as f64 * domain.u_step;
        let v_max = domain.v_min + cells_t as f64 * domain.v_step;
        let coefficient_scale = view
            .sides()
            .flat_map(|side| side.surface().coefficients.iter())
            .fold(0.0f64, |m, c| m.max(c.abs()));
        let scale = [domain.u_min, domain.v_min, u_max, v_max]
            .iter()
            .fold(coefficient_scale, |m, x| m.max(x.abs()));
        let margin = MARGIN_REL * (1.0 + scale);
        let frame_error = orthonormality_error(&surrogate.frame);
        if !(frame_error <= MAX_FRAME_ERROR) {
            return Err(GuardError::Surrogate(
                shroud_surrogate::query::QueryError::BadFrame,
            ));
        }
        let slack_pad = [DOMAIN_SLACK * domain.u_step, DOMAIN_SLACK * domain.v_step];
        let mut envelope = Self {
            frame: surrogate.frame,
            domain,
            cells_s,
            cells_t,
            has_upper: upper.is_some(),
            has_lower: lower.is_some(),
            boxes: Vec::with_capacity(cells_s * cells_t),
            row_boxes: Vec::with_capacity(cells_t),
            upper_surface: upper.map(|v| v.surface().clone()),
            lower_surface: lower.map(|v| v.surface().clone()),
            trim: trim.clone(),
            trimmed: Trimmed::new(trim, &domain, (cells_s, cells_t)),
            locator: domain.locator(&surrogate.frame),
            patches: Vec::with_capacity(cells_s * cells_t),
            first_splits: (0..cells_s * cells_t).map(|_| OnceLock::new()).collect(),
            margin,
            slack_pad,
            frame_error,
            inv_step: [1.0 / domain.u_step, 1.0 / domain.v_step],
            cells_f: [cells_s as f64, cells_t as f64],
            span_pad: slack_pad.map(|slack| 2.0 * margin + 2.0 * slack),
            extent: ([domain.u_min, u_max], [domain.v_min, v_max]),
            kept_cells: 0,
            field_of_view: None,
            view_region: None,
            dark: None,
        };
        for g in 0..cells_t {
            let mut row_box = CellBox::EMPTY;
            for h in 0..cells_s {
                let kept = trim.cell_bits(h, g);
                let patches = cell_patches(upper, lower, h, g, kept);
                let cell_box = if kept != 0 {
                    envelope.box_of(h, g, &patches, 0)
                } else {
                    CellBox::EMPTY
                };
                if kept != 0 {
                    row_box = row_box.union(&cell_box);
                    envelope.kept_cells += 1;
                }
                envelope.boxes.push(cell_box);
                envelope.patches.push(patches);
            }
            envelope.row_boxes.push(row_box);
        }
        Ok(envelope)
    }

    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    pub fn domain(&self) -> &Domain {
        &self.domain
    }

    /// Cells along `s` and `t`.
    pub fn cells(&self) -> (usize, usize) {
        (self.cells_s, self.cells_t)
    }

    /// Cells with at least one kept triangle.
    pub fn kept_cells(&self) -> usize {
        self.kept_cells
    }

    pub fn has_upper(&self) -> bool {
        self.has_upper
    }

    pub fn has_lower(&self) -> bool {
        self.has_lower
    }

    /// The padded box of cell `(h, g)` (`None` when trimmed away or out of range).
    pub fn cell_box(&self, h: usize, g: usize) -> Option<CellBox> {
        (h < self.cells_s && g < self.cells_t)
            .then(|| self.boxes[g * self.cells_s + h])
            .filter(|b| !b.is_empty())
    }

    /// Frame coordinates `(u, v, h)` of a world point.
    #[inline]
    pub fn to_frame(&self, p: DVec3) -> [f64; 3] {
        [
            p.dot(self.frame.u),
            p.dot(self.frame.v),
            p.dot(self.frame.w),
        ]
    }

    /// The domain as a frame rectangle `([u_min, u_max], [v_min, v_max])`.
    pub fn uv_extent(&self) -> ([f64; 2], [f64; 2]) {
        self.extent
    }

    /// Absolute margin subtracted from every distance of this surrogate.
    pub(crate) fn margin(&self) -> f64 {
        self.margin
    }

    /// The same envelope, knowing the region its cloud's sensor covered (or
    /// not): space outside it counts as unseen. Refused unless it is convex.
    pub fn with_field_of_view(mut self, fov: Option<FieldOfView>) -> Result<Self, GuardError> {
        if let Some(f) = &fov {
            f.validate()
                .map_err(|e| GuardError::FieldOfView(e.to_string()))?;
        }
        self.view_region = fov.as_ref().map(ViewRegion::new);
        self.field_of_view = fov;
        Ok(self)
    }

    /// The same envelope, knowing the directions in which its cloud's sensor
    /// got no return (or not): they count as unseen. Refused unless valid.
    pub fn with_no_return(mut self, no_return: Option<&NoReturn>) -> Result<Self, GuardError> {
        if let Some(n) = no_return {
            n.validate()
                .map_err(|e| GuardError::NoReturn(e.to_string()))?;
        }
        self.dark = no_return.map(DarkCones::new);
        Ok(self)
    }

    /// The directions without return, ready for queries, if the cloud said.
    pub(crate) fn dark(&self) -> Option<&DarkCones> {
        self.dark.as_ref()
    }

    /// The region the source cloud's sensor covered, if the cloud said.
    pub fn field_of_view(&self) -> Option<&FieldOfView> {
        self.field_of_view.as_ref()
    }

    /// [`Self::field_of_view`], ready for depth queries.
    pub(crate) fn view_region(&self) -> Option<&ViewRegion> {
        self.view_region.as_ref()
    }

    /// Deviation of the frame from orthonormal (see the field).
    pub(crate) fn frame_error(&self) -> f64 {
        self.frame_error
    }

    /// Kept triangle bits of cell `(h, g)` (the tests' exhaustive searches
    /// read them; the guard reads `guard::trimmed`).
    #[cfg(test)]
    pub(crate) fn trim_bits(&self, h: usize, g: usize) -> u8 {
        self.trim.cell_bits(h, g)
    }

    pub(crate) fn trimmed(&self) -> &Trimmed {
        &self.trimmed
    }

    /// Where the first split of cell `index` is kept.
    pub(crate) fn first_split(&self, index: usize) -> &OnceLock<Box<Split>> {
        &self.first_splits[index]
    }

    pub(crate) fn patches(&self, index: usize) -> &CellPatches {
        &self.patches[index]
    }

    pub(crate) fn boxes(&self) -> &[CellBox] {
        &self.boxes
    }

    pub(crate) fn row_boxes(&self) -> &[CellBox] {
        &self.row_boxes
    }

    /// Whether the ball of radius `r` around the world point `p` certainly
    /// meets the occupied region: `p` is over a kept place of the domain and
    /// within `r` of the occupied height interval there (a surface point then
    /// lies within `r`). Answering 0 is always conservative; on a surrogate
    /// whose surfaces do not cross, the search would find 0 too (the box of
    /// every piece around `p` holds that surface point).
    pub(crate) fn certainly_touches(&self, p: DVec3, r: f64) -> bool {
        let (s, t, w) = self.locator.locate(p);
        if !(self.domain.contains_param(s, t) && kept_closed(&self.trim, s, t)) {
            return false;
        }
        let above_lower = self
            .lower_surface
            .as_ref()
            .is_none_or(|f| w >= f.eval(s, t) - r);
        above_lower
            && self
                .upper_surface
                .as_ref()
                .is_none_or(|f| w <= f.eval(s, t) + r)
    }

    /// The padded box of the local rectangle `s x t` of cell `(h, g)`, with the
    /// height range of the given (restricted) patches at refinement `level`.
    #[inline]
    pub(crate) fn box_of(&self, h: usize, g: usize, p: &CellPatches, level: u32) -> CellBox {
        let mut b = self.sub_box_uv(h, g, p.s, p.t);
        [b.lo[2], b.hi[2]] = self.height_range(&p.upper, &p.lower, p.magnitude, level);
        b
    }

    /// Padded `[min, max]` of the occupied heights over a piece whose patches
    /// (restricted to it) are given: `-inf` / `+inf` for an absent side.
    #[inline]
    pub(crate) fn height_range(
        &self,
        upper: &BezierPatch,
        lower: &BezierPatch,
        magnitude: f64,
        level: u32,
    ) -> [f64; 2] {
        let pad = (PAD_ULPS + PAD_ULPS_PER_LEVEL * level as f64) * f64::EPSILON * (1.0 + magnitude);
        let hi = if self.has_upper {
            net_max(upper) + pad
        } else {
            f64::INFINITY
        };
        let lo = if self.has_lower {
            net_min(lower) - pad
        } else {
            f64::NEG_INFINITY
        };
        [lo, hi]
    }

    /// The padded frame rectangle of the local rectangle `s x t` of cell
    /// `(h, g)`, with an unbounded height range.
    #[inline]
    pub(crate) fn sub_box_uv(&self, h: usize, g: usize, s: [f64; 2], t: [f64; 2]) -> CellBox {
        let d = &self.domain;
        let u = |x: f64| d.u_min + (index_f64(h) + x) * d.u_step;
        let v = |x: f64| d.v_min + (index_f64(g) + x) * d.v_step;
        // Points in the domain slack sit just outside the domain's border.
        let (m, [su, sv]) = (self.margin, self.slack_pad);
        let at_start = |cell: usize, x: f64| cell == 0 && x == 0.0;
        let at_end = |cell: usize, n: usize, x: f64| cell + 1 == n && x == 1.0;
        CellBox {
            lo: [
                u(s[0]) - m - if at_start(h, s[0]) { su } else { 0.0 },
                v(t[0]) - m - if at_start(g, t[0]) { sv } else { 0.0 },
                f64::NEG_INFINITY,
            ],
            hi: [
                u(s[1])
                    + m
                    + if at_end(h, self.cells_s, s[1]) {
                        su
                    } else {
                        0.0
                    },
                v(t[1])
                    + m
                    + if at_end(g, self.cells_t, t[1]) {
                        sv
                    } else {
                        0.0
                    },
                f64::INFINITY,
            ],
        }
    }

    /// The first and last cell along `u` (`axis` 0) or `v` (1) that the
    /// frame interval `x` (inside the domain) lies in, up to rounding.
    pub(crate) fn cell_range(&self, axis: usize, x: [f64; 2]) -> [usize; 2] {
        let (origin, n) = if axis == 0 {
            (self.domain.u_min, self.cells_s)
        } else {
            (self.domain.v_min, self.cells_t)
        };
        let index = |x: f64| cell_index((x - origin) * self.inv_step[axis], n);
        [index(x[0]), index(x[1])]
    }

    /// The cells along `u` (`axis` 0) or `v` (1) whose padded boxes may meet
    /// the frame interval `[lo, hi]` (widened by more than the boxes' padding,
    /// and a little against rounding); `None` when it misses the domain.
    #[inline]
    pub(crate) fn span(&self, axis: usize, lo: f64, hi: f64) -> Option<(usize, usize)> {
        const FUDGE: f64 = 1e-6;
        let (origin, n) = if axis == 0 {
            (self.domain.u_min, self.cells_s)
        } else {
            (self.domain.v_min, self.cells_t)
        };
        let inv = self.inv_step[axis];
        // Boxes reach past their cells by the margin and the slack padding.
        let pad = self.span_pad[axis];
        let (a, b) = (
            (lo - pad - origin) * inv - FUDGE,
            (hi + pad - origin) * inv + FUDGE,
        );
        if !(b >= 0.0 && a <= self.cells_f[axis]) {
            return None;
        }
        Some((cell_index(a, n), cell_index(b, n)))
    }
}

/// `floor(x)` clamped into `0..cells` (`cells >= 1`), NaN to 0, as an
/// index: the saturating cast truncates towards zero, which is the floor
/// from 0 up, instead of a call of `floor` the baseline x86-64 has no
/// instruction for.
#[inline]
fn cell_index(x: f64, cells: usize) -> usize {
    // Below 1 (NaN too) the index is 0; from 1 up, truncation is the floor,
    // and a cast to `i64` is one instruction there where a cast to `usize`
    // is a sequence (it saturates at `i64::MAX`, far above any cell count).
    if x >= 1.0 {
        // Clamped while still an `i64`, so that no target's `usize` can wrap.
        (x as i64).min(cells as i64 - 1) as usize
    } else {
        0
    }
}

/// A cell index as a float, exactly as `k as f64` gives it: through `i64`,
/// one instruction where the conversion of a `usize` is a sequence on
/// baseline x86-64 (indices are below `isize::MAX`, so the value is the
/// same).
#[inline]
pub(crate) fn index_f64(k: usize) -> f64 {
    k as i64 as f64
}

/// Smallest and largest control point of a net.
#[inline]
pub(crate) fn net_range(p: &BezierPatch) -> [f64; 2] {
    [net_min(p), net_max(p)]
}

/// Smallest control point of a net: per column, then across (the order
/// fixes which zero a tie of `-0` and `0` gives).
#[inline]
fn net_min(p: &BezierPatch) -> f64 {
    let mut lo = p.0[0];
    for row in &p.0[1..] {
        for k in 0..4 {
            lo[k] = lo[k].min(row[k]);
        }
    }
    lo[0].min(lo[1]).min(lo[2].min(lo[3]))
}

/// Largest control point of a net, as [`net_min`].
#[inline]
fn net_max(p: &BezierPatch) -> f64 {
    let mut hi = p.0[0];
    for row in &p.0[1..] {
        for k in 0..4 {
            hi[k] = hi[k].max(row[k]);
        }
    }
    hi[0].max(hi[1]).max(hi[2].max(hi[3]))
}

/// The patches of cell `(h, g)` restricted to its kept rectangle.
fn cell_patches(
    upper: Option<SideView>,
    lower: Option<SideView>,
    h: usize,
    g: usize,
    kept: u8,
) -> CellPatches {
    let (s, t) = kept_rect(kept);
    let zero = BezierPatch([[0.0; 4]; 4]);
    let mut magnitude = 0.0f64;
    let mut restricted = |side: Option<SideView>| match side {
        Some(view) if kept != 0 => {
            let full = bezier_patch(view.surface(), h, g);
            let [lo, hi] = net_range(&full);
            magnitude = magnitude.max(lo.abs()).max(hi.abs());
            if s == [0.0, 1.0] && t == [0.0, 1.0] {
                full
            } else {
                BezierPatch(patch_on_rect(&full, s, t))
            }
        }
        _ => zero,
    };
    let (upper, lower) = (restricted(upper), restricted(lower));
    CellPatches {
        kept,
        s,
        t,
        upper,
        lower,
        magnitude,
    }
}

/// Bounding rectangle (local, in `[0, 1]^2`) of the closed kept triangles.
pub(crate) fn kept_rect(bits: u8) -> ([f64; 2], [f64; 2]) {
    let mut s = [1.0f64, 0.0];
    let mut t = [1.0f64, 0.0];
    for (bit, bs, bt) in [
        (BOTTOM, [0.0, 1.0], [0.0, 0.5]),
        (RIGHT, [0.5, 1.0], [0.0, 1.0]),
        (TOP, [0.0, 1.0], [0.5, 1.0]),
        (LEFT, [0.0, 0.5], [0.0, 1.0]),
    ] {
        if bits & bit != 0 {
            s = [s[0].min(bs[0]), s[1].max(bs[1])];
            t = [t[0].min(bt[0]), t[1].max(bt[1])];
        }
    }
    if bits & ALL == 0 {
        return ([0.0, 1.0], [0.0, 1.0]);
    }
    (s, t)
}

/// Whether the closed local rectangle `s x t` meets a closed kept triangle:
/// separating axes `u`, `v`, `u - v`, `u + v` (the edge normals of the rectangle
/// and the triangles) are exact for convex polygons. Dyadic corners make every
/// sum here exact.
#[inline]
pub(crate) fn rect_meets_kept(bits: u8, s: [f64; 2], t: [f64; 2]) -> bool {
    if bits & ALL == ALL {
        return true;
    }
    // Projections of each triangle on u, v, u - v, u + v.
    const TRIANGLES: [(u8, [[f64; 2]; 4]); 4] = [
        (BOTTOM, [[0.0, 1.0], [0.0, 0.5], [0.0, 1.0], [0.0, 1.0]]),
        (RIGHT, [[0.5, 1.0], [0.0, 1.0], [0.0, 1.0], [1.0, 2.0]]),
        (TOP, [[0.0, 1.0], [0.5, 1.0], [-1.0, 0.0], [1.0, 2.0]]),
        (LEFT, [[0.0, 0.5], [0.0, 1.0], [-1.0, 0.0], [0.0, 1.0]]),
    ];
    let rect = [s, t, [s[0] - t[1], s[1] - t[0]], [s[0] + t[0], s[1] + t[1]]];
    TRIANGLES.iter().any(|(bit, tri)| {
        bits & bit != 0
            && rect
                .iter()
                .zip(tri)
                .all(|(r, q)| r[0] <= q[1] && q[0] <= r[1])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use shroud_surrogate::query::kept_closed;
    use shroud_surrogate::trim::triangle_of;
    use shroud_surrogate::TrimMask;

    /// The cast is the clamped floor it replaced, NaN and infinities
    /// included.
    #[test]
    fn cell_index_is_the_clamped_floor() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(13);
        let special = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.0,
            0.0,
            -1.0,
            -0.5,
            1e300,
        ];
        for cells in 1..6usize {
            let mut xs: Vec<f64> = special.to_vec();
            xs.extend((0..200).map(|_| rng.random_range(-3.0..9.0)));
            xs.extend((0..=9).map(|k| k as f64));
            for x in xs {
                let floor = x.floor().clamp(0.0, cells as f64 - 1.0) as usize;
                assert_eq!(cell_index(x, cells), floor, "{x} in {cells}");
            }
        }
    }

    /// Through `i64` an index converts to the same float as directly, up to
    /// the largest a slice can have.
    #[test]
    fn index_f64_is_the_direct_conversion() {
        let big = isize::MAX as usize;
        let ks = (0..5000).chain([1 << 53, (1 << 53) + 1, big - 1, big]);
        for k in ks {
            assert_eq!(index_f64(k).to_bits(), (k as f64).to_bits(), "{k}");
        }
    }

    #[test]
    fn kept_rect_bounds_the_kept_triangles() {
        assert_eq!(kept_rect(BOTTOM), ([0.0, 1.0], [0.0, 0.5]));
        assert_eq!(kept_rect(LEFT | BOTTOM), ([0.0, 1.0], [0.0, 1.0]));
        assert_eq!(kept_rect(RIGHT), ([0.5, 1.0], [0.0, 1.0]));
        assert_eq!(kept_rect(TOP | BOTTOM), ([0.0, 1.0], [0.0, 1.0]));
    }

    /// A rectangle meets a kept triangle exactly when a fine sample of it does
    /// (samples include the corners and edges, where closed triangles touch).
    #[test]
    fn rect_test_agrees_with_sampling_the_closed_triangles() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        for _ in 0..4000 {
            let bits: u8 = rng.random_range(1..16);
            let mut trim = TrimMask::empty(1, 1);
            trim.bits[0] = bits;
            let level = rng.random_range(0..4u32);
            let n = 1u32 << level;
            let (i, j) = (rng.random_range(0..n), rng.random_range(0..n));
            let w = 1.0 / n as f64;
            let (s, t) = (
                [i as f64 * w, (i + 1) as f64 * w],
                [j as f64 * w, (j + 1) as f64 * w],
            );
            let k = 16;
            let sampled = (0..=k).any(|a| {
                (0..=k).any(|b| {
                    let (x, y) = (
                        s[0] + (s[1] - s[0]) * a as f64 / k as f64,
                        t[0] + (t[1] - t[0]) * b as f64 / k as f64,
                    );
                    kept_closed(&trim, x, y)
                })
            });
            assert_eq!(
                rect_meets_kept(bits, s, t),
                sampled,
                "bits {bits:04b} rect {s:?} x {t:?}"
            );
        }
    }

    #[test]
    fn marked_points_lie_in_a_rect_that_meets_the_kept_triangles() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        for _ in 0..2000 {
            let (x, y): (f64, f64) = (rng.random_range(0.0..=1.0), rng.random_range(0.0..=1.0));
            let bits = triangle_of(x, y);
            let (s, t) = kept_rect(bits);
            assert!((s[0]..=s[1]).contains(&x) && (t[0]..=t[1]).contains(&y));
            let n = 8.0;
            let (i, j) = ((x * n).floor().min(n - 1.0), (y * n).floor().min(n - 1.0));
            assert!(rect_meets_kept(
                bits,
                [i / n, (i + 1.0) / n],
                [j / n, (j + 1.0) / n]
            ));
        }
    }
}
