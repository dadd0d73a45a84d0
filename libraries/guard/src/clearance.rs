//! Conservative clearance of a sphere or capsule to the occupied region of an
//! envelope: a lower bound on the Euclidean distance from the shape to every
//! certified cloud point in the surrogate's domain, `0` when they may meet,
//! capped at `max_report`.
//!
//! The bound. For a point `p` and a sphere `(c, r)`, `dist(p, sphere) =
//! max(0, |p - c| - r)`. Each certified point lies in the box `B` of its cell
//! (see `envelope`), so `|p - c| >= dist(c, B)` and `dist(p, sphere) >= dist(c,
//! B) - r`. Frame coordinates are an orthonormal change of basis, so distances
//! computed there are world distances (up to rounding, which the margin
//! covers). For a capsule, replace `c` by its axis segment and `dist(c, B)` by
//! the exact segment-to-box distance. The minimum over the cells under the
//! shape's footprint bounds every point there; cells whose rectangle is farther
//! than `r + max_report` cannot lower a capped answer and are not visited.
//!
//! Refinement. A cell whose box says the shape is closer than `stop_distance`
//! is split into 2x2 sub-rectangles, each bounded by its restricted Bézier net
//! (tighter by the convex hull property), recursively up to `refine_depth`
//! levels; sub-rectangles that meet no kept triangle hold no point and are
//! dropped. The search is branch and bound: cells and sub-rectangles are visited
//! closest first and skipped once they cannot lower the current minimum.
//!
//! Refinement serves one decision, whether the shape is clear of
//! `stop_distance`. Once a fully refined piece is below it, the search stops:
//! the answer is that piece's bound folded with the coarser bounds of the
//! pieces not yet refined, still a lower bound on the distance, but not the
//! tightest one available. Clearances at or above `stop_distance` are the full
//! branch-and-bound minimum.
//!
//! Shortcut. When a sphere's centre (a capsule's end) lies over a kept place
//! within `r` of the occupied height interval there, a surface point is within
//! `r` and the answer is 0 without a search.
// Small fixed-size matrices and nets are clearer with explicit indices.
#![allow(clippy::needless_range_loop)]

use super::config::GuardConfig;
use super::envelope::{rect_meets_kept, CellBox, CellPatches, Envelope, Piece, Split};
use super::error::GuardError;
use super::probe::{PointProbe, Probe, SegmentProbe};
use super::shape::Shape;
use glam::DVec3;
use shroud_geometry::spline::BezierPatch;
use std::sync::OnceLock;

/// Cells waiting for refinement, kept on the stack; beyond this many a cell is
/// refined at once (same answer, less pruning).
const PENDING: usize = 32;

impl Envelope {
    /// Clearance of a sphere (see the module docs), in `[0, max_report]`.
    pub fn sphere_clearance(
        &self,
        centre: DVec3,
        radius: f64,
        config: &GuardConfig,
    ) -> Result<f64, GuardError> {
        self.shape_clearance(&Shape::sphere(centre, radius), config)
    }

    /// Clearance of a capsule (segment `a`-`b` swept by `radius`).
    pub fn capsule_clearance(
        &self,
        a: DVec3,
        b: DVec3,
        radius: f64,
        config: &GuardConfig,
    ) -> Result<f64, GuardError> {
        self.shape_clearance(&Shape::capsule(a, b, radius), config)
    }

    /// Clearance of any shape; refuses non-finite shapes and bad configs.
    pub fn shape_clearance(&self, shape: &Shape, config: &GuardConfig) -> Result<f64, GuardError> {
        config.validate()?;
        if !shape.is_valid() {
            return Err(GuardError::BadShape { index: 0, link: 0 });
        }
        Ok(self.clearance_unchecked(shape, config))
    }

    /// What every distance of `shape` to this surrogate is reduced by: the
    /// surrogate's margin, the frame's distance from orthonormal (frame
    /// distances below `max_report + r` scale by at most `1 +- 3
    /// frame_error`), and the rounding of the shape's own coordinates.
    pub(crate) fn slack(&self, shape: &Shape, config: &GuardConfig) -> f64 {
        let r = shape.radius();
        let skew = 4.0 * self.frame_error() * (config.max_report + r);
        let size = match shape {
            Shape::Sphere(s) => s.centre.abs().max_element(),
            Shape::Capsule(c) => c.a.abs().max_element().max(c.b.abs().max_element()),
        };
        self.margin() + skew + 16.0 * f64::EPSILON * (size + r)
    }

    /// [`Self::shape_clearance`] for a shape and config already validated.
    pub(crate) fn clearance_unchecked(&self, shape: &Shape, config: &GuardConfig) -> f64 {
        self.clearance_up_to(shape, config, config.max_report)
    }

    /// [`Self::clearance_unchecked`] searched only up to `cap` (at most
    /// `config.max_report`), a lower bound in `[0, cap]`: with `cap` at or
    /// above the stop distance, the full search's bound where that is below
    /// `cap`, else `cap`; below it, possibly lower, as cells are then not
    /// refined (the answer is below the stop distance anyway). Fewer cells
    /// are looked at the smaller the cap.
    pub(crate) fn clearance_up_to(&self, shape: &Shape, config: &GuardConfig, cap: f64) -> f64 {
        let cap = cap.clamp(0.0, config.max_report);
        let r = shape.radius();
        let slack = self.slack(shape, config);
        match shape {
            Shape::Sphere(s) => {
                let touches = || self.certainly_touches(s.centre, r);
                let probe = PointProbe(self.to_frame(s.centre));
                self.search(&probe, r, slack, (config, cap), touches)
            }
            Shape::Capsule(c) => {
                let touches = || self.certainly_touches(c.a, r) || self.certainly_touches(c.b, r);
                let probe = SegmentProbe {
                    a: self.to_frame(c.a),
                    b: self.to_frame(c.b),
                };
                self.search(&probe, r, slack, (config, cap), touches)
            }
        }
    }

    /// Branch-and-bound minimum of `dist(core, box) - radius - slack` over the
    /// cells (and sub-rectangles) near the core, clamped to `[0, max_report]`.
    /// Rows farther than the current minimum are skipped, and within a row only
    /// the cells whose `u` range can still be close enough are looked at.
    /// `touches` is the shortcut test, asked only when some cell needs refining.
    fn search<P: Probe>(
        &self,
        probe: &P,
        radius: f64,
        slack: f64,
        (config, cap): (&GuardConfig, f64),
        touches: impl Fn() -> bool,
    ) -> f64 {
        let offset = radius + slack;
        let (u, v) = probe.uv_bounds();
        let reach = cap + offset;
        let (Some((g0, g1)), Some(_)) = (
            self.span(1, v[0] - reach, v[1] + reach),
            self.span(0, u[0] - reach, u[1] + reach),
        ) else {
            return cap;
        };
        let (cells_s, _) = self.cells();
        let mut best = cap;
        let mut pending = [(0.0f64, 0usize); PENDING];
        let mut waiting = 0;
        let mut touching: Option<bool> = None;
        let refine = config.refine_depth > 0;
        let (boxes, row_boxes) = (self.boxes(), self.row_boxes());
        // Half-open ranges (the indices are cells, far below `usize::MAX`):
        // an inclusive range's loop checks more on every step.
        for g in g0..g1 + 1 {
            // Cells nearer than `best` lie within `limit` of the core.
            let limit = best + offset;
            let row = &row_boxes[g];
            let dv = (row.lo[1] - v[1]).max(v[0] - row.hi[1]).max(0.0);
            // A row whose box is no nearer holds no cell that is (a point
            // high above the surface, say).
            if dv >= limit || probe.beyond(row, limit) {
                continue;
            }
            let du = (limit * limit - dv * dv).sqrt();
            let Some((a, b)) = self.span(0, u[0] - du, u[1] + du) else {
                continue;
            };
            // `span` orders its ends; an empty span is skipped, not an underflow.
            if a > b {
                continue;
            }
            let first = g * cells_s + a;
            for (index, cell) in (first..).zip(&boxes[first..first + (b - a) + 1]) {
                if cell.is_empty() {
                    continue;
                }
                let limit = best + offset;
                let d2 = probe.dist2_to_box(&cell.lo, &cell.hi);
                if d2 >= limit * limit {
                    continue;
                }
                let c = d2.sqrt() - offset;
                if c >= best {
                    continue;
                }
                if refine && c < config.stop_distance {
                    if waiting < PENDING {
                        pending[waiting] = (c, index);
                        waiting += 1;
                    } else {
                        if *touching.get_or_insert_with(&touches) {
                            return 0.0;
                        }
                        best = self.refine_cell(probe, offset, index, best, config);
                    }
                } else {
                    best = c;
                }
            }
        }
        if waiting > 0 && *touching.get_or_insert_with(&touches) {
            return 0.0;
        }
        let pending = &mut pending[..waiting];
        pending.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        for &(c, index) in pending.iter() {
            if c >= best {
                break;
            }
            if best < config.stop_distance {
                // Known to be below the threshold: the coarse bound of the
                // closest cell not yet refined keeps the answer conservative.
                best = c;
                break;
            }
            best = self.refine_cell(probe, offset, index, best, config);
        }
        best.clamp(0.0, cap)
    }

    /// The smaller of `best` and the refined bound of one cell.
    fn refine_cell<P: Probe>(
        &self,
        probe: &P,
        offset: f64,
        index: usize,
        best: f64,
        config: &GuardConfig,
    ) -> f64 {
        let (cells_s, _) = self.cells();
        let p = self.patches(index);
        let coarse = self.boxes()[index];
        let node = Node {
            s: p.s,
            t: p.t,
            h: [coarse.lo[2], coarse.hi[2]],
            upper: &p.upper,
            lower: &p.lower,
        };
        let mut search = Refinement {
            envelope: self,
            probe,
            offset,
            index,
            cell: (index % cells_s, index / cells_s),
            patches: p,
            config,
            best,
        };
        search.descend(&node, 1, Some(Kept::CELL));
        search.best
    }
}

/// A sub-rectangle of a cell (local parameters) with its restricted
/// patches, borrowed from the cell or from the piece it is.
#[derive(Clone, Copy)]
struct Node<'p> {
    s: [f64; 2],
    t: [f64; 2],
    /// Padded height range of the points over the node.
    h: [f64; 2],
    upper: &'p BezierPatch,
    lower: &'p BezierPatch,
}

impl<'p> Node<'p> {
    fn of(piece: &'p Piece) -> Self {
        Node {
            s: piece.s,
            t: piece.t,
            h: piece.h,
            upper: &piece.upper,
            lower: &piece.lower,
        }
    }
}

struct Refinement<'a, P> {
    envelope: &'a Envelope,
    probe: &'a P,
    offset: f64,
    /// The cell, as an index and as `(h, g)`.
    index: usize,
    cell: (usize, usize),
    patches: &'a CellPatches,
    config: &'a GuardConfig,
    best: f64,
}

/// How many levels below a cell splits are kept with the envelope: the
/// cell's, its quarters' and theirs (at most 21 a cell, some 34 KB, for the
/// cells shapes came near); deeper splits are made anew.
const KEPT_LEVELS: usize = 2;

/// Where a node's split is kept with the envelope once made (it depends on
/// the surrogate alone): the quarters taken from the cell down to the node.
#[derive(Debug, Clone, Copy)]
struct Kept {
    path: [usize; KEPT_LEVELS],
    len: usize,
}

impl Kept {
    /// The cell's own split.
    const CELL: Kept = Kept {
        path: [0; KEPT_LEVELS],
        len: 0,
    };

    /// Where quarter `k`'s split is kept, if it is.
    fn then(self, k: usize) -> Option<Kept> {
        (self.len < KEPT_LEVELS).then(|| {
            let mut next = self;
            next.path[self.len] = k;
            next.len += 1;
            next
        })
    }
}

impl<'a, P: Probe> Refinement<'a, P> {
    /// The place of a kept split (`None` when a split above it is not
    /// made yet, which it comes after).
    fn kept(&self, at: Kept) -> Option<&'a OnceLock<Box<Split>>> {
        let mut place = self.envelope.first_split(self.index);
        for &k in &at.path[..at.len] {
            place = &place.get()?[k].as_ref()?.split;
        }
        Some(place)
    }

    /// Splits `node` 2x2 (children at `level`) and folds their bounds into
    /// `best`, recursing into children still closer than `stop_distance`.
    /// The split is made once and kept in `kept` when given (near the top
    /// of a cell's tree: it depends on the surrogate alone).
    fn descend(&mut self, node: &Node, level: u32, kept: Option<Kept>) {
        // Made only when not kept: a split is large, and so is dropping it.
        let fresh: Split;
        let split: &Split = match kept.and_then(|at| self.kept(at)) {
            Some(lock) => lock.get_or_init(|| {
                let mut split = Box::default();
                self.split(node, level, &mut split, false);
                split
            }),
            None => {
                let mut made = Split::default();
                self.split(node, level, &mut made, true);
                fresh = made;
                &fresh
            }
        };
        let mut children: [(f64, Option<&Piece>); 4] = [(f64::INFINITY, None); 4];
        for (child, piece) in children.iter_mut().zip(split) {
            let Some(piece) = piece else {
                continue;
            };
            if self.bound(&piece.near) >= self.best {
                continue;
            }
            let mut b = piece.near;
            (b.lo[2], b.hi[2]) = (piece.h[0], piece.h[1]);
            let c = self.bound(&b);
            *child = (c, Some(piece));
        }
        for k in closest_first(std::array::from_fn(|k| children[k].0)) {
            let (c, Some(piece)) = children[k] else {
                break;
            };
            if c >= self.best {
                break;
            }
            if self.best < self.config.stop_distance {
                // Decided: fold in the bound of the closest unexplored sibling.
                self.best = c;
                break;
            }
            if level < self.config.refine_depth && c < self.config.stop_distance {
                let kept = kept.and_then(|at| at.then(k));
                self.descend(&Node::of(piece), level + 1, kept);
            } else {
                self.best = c;
            }
        }
    }

    /// The quarters of `node` (children at `level`) into `out`, as far as
    /// they are the same for every shape. A child's points lie in the
    /// parent's height range too (its net is made of convex combinations of
    /// the parent's), hence the cheap first bound `near`; with `near_only`,
    /// a quarter that is no nearer by it than `best` is left out at once
    /// (as `descend` would leave it out).
    fn split(&self, node: &Node, level: u32, out: &mut Split, near_only: bool) {
        let e = self.envelope;
        let upper_quarters = e.has_upper().then(|| quarters(node.upper));
        let lower_quarters = e.has_lower().then(|| quarters(node.lower));
        let halves = [[0.0, 0.5], [0.5, 1.0]];
        let local = |x: [f64; 2], h: [f64; 2]| {
            let mid = 0.5 * (x[0] + x[1]);
            if h[0] == 0.0 {
                [x[0], mid]
            } else {
                [mid, x[1]]
            }
        };
        for (k, piece) in out.iter_mut().enumerate() {
            let (s, t) = (local(node.s, halves[k % 2]), local(node.t, halves[k / 2]));
            if !rect_meets_kept(self.patches.kept, s, t) {
                continue;
            }
            let (h, g) = self.cell;
            let mut near: CellBox = e.sub_box_uv(h, g, s, t);
            (near.lo[2], near.hi[2]) = (node.h[0], node.h[1]);
            if near_only && self.bound(&near) >= self.best {
                continue;
            }
            let (upper, lower) = (
                upper_quarters.as_ref().map_or(*node.upper, |q| q[k]),
                lower_quarters.as_ref().map_or(*node.lower, |q| q[k]),
            );
            let heights = e.height_range(&upper, &lower, self.patches.magnitude, level);
            // Never looser than the parent's range.
            let h = [heights[0].max(node.h[0]), heights[1].min(node.h[1])];
            *piece = Some(Piece {
                s,
                t,
                near,
                h,
                upper,
                lower,
                split: OnceLock::new(),
            });
        }
    }

    /// The shape's bound from a box: its distance less the offset.
    fn bound(&self, b: &CellBox) -> f64 {
        self.probe.dist2_to_box(&b.lo, &b.hi).sqrt() - self.offset
    }
}

/// The order of four children by their bounds, nearest first, ties in
/// their order (a stable insertion sort, as the standard library's sort of
/// so few is): the children are visited by index instead of being moved.
fn closest_first(bounds: [f64; 4]) -> [usize; 4] {
    let mut order = [0, 1, 2, 3];
    for i in 1..4 {
        let mut j = i;
        while j > 0 && bounds[order[j]].total_cmp(&bounds[order[j - 1]]).is_lt() {
            order.swap(j, j - 1);
            j -= 1;
        }
    }
    order
}

/// The four quarters of a patch over `[0, 1/2]^2`, `[1/2, 1] x [0, 1/2]`,
/// `[0, 1/2] x [1/2, 1]`, `[1/2, 1]^2` (index `k`: `s` half `k % 2`, `t` half
/// `k / 2`), by de Casteljau at the midpoint: rows first, then columns. This is
/// `BezierPatch::restrict` specialised to the 2x2 split: one subdivision of
/// each row and column instead of two per quarter, and exact halving.
fn quarters(p: &BezierPatch) -> [BezierPatch; 4] {
    let halves = |c: [f64; 4]| {
        let mid = |a: f64, b: f64| 0.5 * (a + b);
        let (a1, b1, c1) = (mid(c[0], c[1]), mid(c[1], c[2]), mid(c[2], c[3]));
        let (a2, b2) = (mid(a1, b1), mid(b1, c1));
        let a3 = mid(a2, b2);
        ([c[0], a1, a2, a3], [a3, b2, c1, c[3]])
    };
    // Split every row (t fixed) along s.
    let mut rows = [[[0.0; 4]; 4]; 2];
    for (r, row) in p.0.iter().enumerate() {
        let (left, right) = halves(*row);
        rows[0][r] = left;
        rows[1][r] = right;
    }
    let mut out = [BezierPatch([[0.0; 4]; 4]); 4];
    for (side, net) in rows.iter().enumerate() {
        for q in 0..4 {
            let (low, high) = halves([net[0][q], net[1][q], net[2][q], net[3][q]]);
            for r in 0..4 {
                out[side].0[r][q] = low[r];
                out[2 + side].0[r][q] = high[r];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::unseen::tests::{random_envelope, random_shape};
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};

    /// A probe that never skips a row: the search as it was before the rows'
    /// boxes.
    struct EveryRow<P>(P);

    impl<P: Probe> Probe for EveryRow<P> {
        fn uv_bounds(&self) -> ([f64; 2], [f64; 2]) {
            self.0.uv_bounds()
        }

        fn dist2_to_box(&self, lo: &[f64; 3], hi: &[f64; 3]) -> f64 {
            self.0.dist2_to_box(lo, hi)
        }

        fn beyond(&self, _outer: &CellBox, _limit: f64) -> bool {
            false
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

        /// Skipping the rows whose box is no nearer than the bound so far
        /// changes no clearance, bit for bit, whatever the stop distance,
        /// refinement depth and cap: never larger (that would be
        /// optimistic), never smaller; nor do the splits the envelope
        /// keeps from earlier shapes.
        #[test]
        fn skipping_rows_by_their_boxes_changes_no_clearance(
            seed in any::<u64>(),
            kept in 0.3..1.0f64,
            stop in 0.0..0.4f64,
            depth in 0u32..=4,
        ) {
            let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
            let env = random_envelope(&mut rng, kept);
            let cold = env.clone();
            let config = GuardConfig {
                stop_distance: stop,
                max_report: stop + rng.random_range(0.01..1.0),
                refine_depth: depth,
                ..GuardConfig::default()
            };
            for _ in 0..40 {
                let Shape::Sphere(sphere) = random_shape(&mut rng, &env) else {
                    continue;
                };
                let shape = Shape::Sphere(sphere);
                let cap = rng.random_range(0.0..=config.max_report);
                let (r, slack) = (sphere.radius, env.slack(&shape, &config));
                let probe = PointProbe(env.to_frame(sphere.centre));
                let touches = || env.certainly_touches(sphere.centre, r);
                let fast = env.clearance_up_to(&shape, &config, cap);
                let every_row = env.search(&EveryRow(probe), r, slack, (&config, cap), touches);
                prop_assert!(fast == every_row, "{shape:?} cap {cap}: {fast} vs {every_row}");
                // The splits kept from earlier shapes change nothing either.
                let cold = cold.clone().clearance_up_to(&shape, &config, cap);
                prop_assert!(fast == cold, "{shape:?} cap {cap}: {fast} vs {cold} afresh");
            }
        }
    }

    /// Visiting by index keeps the order of sorting the children
    /// themselves by their bounds (stably), ties, infinities and NaN included.
    #[test]
    fn closest_first_is_the_stable_sort_of_the_bounds() {
        let values = [0.0, -0.0, 1.0, 0.5, f64::INFINITY, f64::NAN, 0.5];
        for code in 0..values.len().pow(4) {
            let bounds: [f64; 4] =
                std::array::from_fn(|k| values[code / values.len().pow(k as u32) % values.len()]);
            let mut sorted: Vec<(f64, usize)> = bounds.iter().copied().zip(0..).collect();
            sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
            let want: Vec<usize> = sorted.iter().map(|&(_, k)| k).collect();
            assert_eq!(closest_first(bounds).to_vec(), want, "{bounds:?}");
        }
    }

    #[test]
    fn quarters_agree_with_restrict() {
        let mut net = [[0.0; 4]; 4];
        for (i, v) in net.iter_mut().flatten().enumerate() {
            *v = ((i * 7919) % 23) as f64 * 0.37 - 3.0;
        }
        let p = BezierPatch(net);
        let q = quarters(&p);
        for (k, quarter) in q.iter().enumerate() {
            let (s0, t0) = (0.5 * (k % 2) as f64, 0.5 * (k / 2) as f64);
            let r = p.restrict(s0, s0 + 0.5, t0, t0 + 0.5);
            for (a, b) in quarter.0.iter().flatten().zip(r.0.iter().flatten()) {
                assert!((a - b).abs() < 1e-12, "quarter {k}: {a} vs {b}");
            }
            for (x, y) in [(0.0, 0.0), (0.3, 0.8), (1.0, 1.0)] {
                let direct = p.eval(s0 + 0.5 * x, t0 + 0.5 * y);
                assert!((quarter.eval(x, y) - direct).abs() < 1e-12);
            }
        }
    }
}
