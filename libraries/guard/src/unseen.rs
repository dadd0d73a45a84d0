//! Distance from a shape to the space a view did not see.
//!
//! A surrogate vouches only for the places where its cloud had points: the
//! kept triangles of its domain. Everywhere else (outside the domain's
//! rectangle, over trimmed triangles) the sensor may have seen nothing at all
//! (a dark object, a corner outside its cone, a region out of range), so the
//! guard treats that space as possibly occupied at every height: a prism along
//! the view's direction `w`. The distance from a shape to such a prism is the
//! distance, in the frame's `(u, v)` plane, from the shape's core (a point, or
//! a segment for a capsule) to the prism's cross-section, minus the radius.
//! When the cloud stated its sensor's field of view, the space outside it is
//! unseen too (`guard::field_of_view`): a kept triangle at the edge of the
//! view is partly interpolated over space the sensor never looked at. So are
//! the directions in which it got no return, when the cloud listed them
//! (`guard::no_return`): a black object between returns from the floor.
//!
//! Why this makes views of *different* clouds combine soundly: each view's
//! bound `min(occupied, unseen)` is a lower bound on the distance to anything
//! that view's cloud could have missed or measured, whatever the other views
//! say, so the largest bound over the views is a lower bound too.

use super::config::GuardConfig;
use super::envelope::index_f64;
use super::field_of_view::clearance_outside;
use super::shape::Shape;
use super::trimmed::{rect_gap, P2};
use super::Envelope;
use shroud_geometry::math::segment_distance;
use shroud_geometry::math::segment_distance_squared;

impl Envelope {
    /// Lower bound on the distance from `shape` to the space this view did
    /// not see (outside the domain, over a trimmed triangle, outside its
    /// sensor's field of view or along a ray that returned nothing when the
    /// cloud stated them), in `[0, max_report]`.
    pub(crate) fn unseen_clearance(&self, shape: &Shape, config: &GuardConfig) -> f64 {
        let (a, b) = self.core_uv(shape);
        let cap = config.max_report;
        let offset = shape.radius() + self.slack(shape, config);
        let mut best = self.distance_outside_domain(a, b) - offset;
        if best <= 0.0 {
            // Nothing below can lower it, and it clamps to 0.
            return 0.0;
        }
        if let Some(region) = self.view_region() {
            best = best.min(clearance_outside(region, shape, cap));
        }
        if let Some(dark) = self.dark() {
            best = best.min(dark.clearance(shape, cap.min(best.max(0.0))));
        }
        // Trimmed triangles no nearer than the capped bound cannot change
        // the clamped answer.
        let bound = best.min(cap);
        self.nearest_trimmed(a, b, offset, bound).clamp(0.0, cap)
    }

    /// The smaller of `bound` and the distance from segment `a`-`b` (inside
    /// the domain) to every trimmed triangle less `offset`, bit for bit the
    /// minimum over all of them: whole regions are skipped only when
    /// `guard::trimmed` proves them no nearer than the bound, cells only
    /// when their rectangle is (both with a rounding allowance).
    fn nearest_trimmed(&self, a: P2, b: P2, offset: f64, bound: f64) -> f64 {
        let (u, v) = (
            [a[0].min(b[0]), a[0].max(b[0])],
            [a[1].min(b[1]), a[1].max(b[1])],
        );
        if bound <= 0.0 {
            return bound;
        }
        let trimmed = self.trimmed();
        let core_cells = (self.cell_range(0, u), self.cell_range(1, v));
        if trimmed.lower_bound(core_cells.0, core_cells.1) - offset >= bound {
            return bound;
        }
        let reach = bound + offset;
        let (Some((h0, h1)), Some((g0, g1))) = (
            self.span(0, u[0] - reach, u[1] + reach),
            self.span(1, v[0] - reach, v[1] + reach),
        ) else {
            return bound;
        };
        let d = self.domain();
        // How far the core's extent along one axis lies from a cell's
        // interval.
        let gap = |x: [f64; 2], start: f64, step: f64, k: usize| {
            let (c0, c1) = (start + index_f64(k) * step, start + index_f64(k + 1) * step);
            (c0 - x[1]).max(x[0] - c1).max(0.0)
        };
        let mut best = bound;
        // Nearest rows and cells first, so that the bound drops early.
        for g in outward((g0, g1), core_cells.1[0]) {
            let gap_v = gap(v, d.v_min, d.v_step, g);
            if gap_v - trimmed.rounding - offset >= best {
                continue;
            }
            for (cell, triangles) in trimmed.row(g, [h0, h1], core_cells.0[0]) {
                if rect_gap(u, v, cell.lo, cell.hi) - trimmed.rounding - offset >= best {
                    continue;
                }
                for t in triangles {
                    if rect_gap(u, v, t.lo, t.hi) - trimmed.rounding - offset >= best {
                        continue;
                    }
                    best = best.min(distance_to_triangle(a, b, t.corners) - offset);
                }
                if best <= 0.0 {
                    return best;
                }
            }
        }
        best
    }

    /// The shape's core (a sphere's centre, a capsule's segment) as a frame
    /// segment in the `(u, v)` plane.
    fn core_uv(&self, shape: &Shape) -> (P2, P2) {
        let uv = |p| {
            let f = self.to_frame(p);
            P2::new(f[0], f[1])
        };
        match shape {
            Shape::Sphere(s) => (uv(s.centre), uv(s.centre)),
            Shape::Capsule(c) => (uv(c.a), uv(c.b)),
        }
    }

    /// Distance from segment `a`-`b` (a point when equal) to the outside of
    /// the domain's rectangle: 0 when an end lies outside, else the smaller
    /// end's distance to the border (the distance to the outside of a convex
    /// set is concave along a segment inside it, so its minimum is at an end).
    fn distance_outside_domain(&self, a: P2, b: P2) -> f64 {
        let (u, v) = self.uv_extent();
        let inside = |p: P2| {
            (p[0] - u[0])
                .min(u[1] - p[0])
                .min(p[1] - v[0])
                .min(v[1] - p[1])
        };
        let d = inside(a).min(inside(b));
        // NaN (never from a validated shape) counts as outside.
        if d > 0.0 {
            d
        } else {
            0.0
        }
    }
}

/// The indices `first..=last`, from `start` (clamped into them) outwards,
/// alternating sides (`start`, one below, one above, two below, ...), one
/// side alone once the other is used up.
fn outward((first, last): (usize, usize), start: usize) -> impl Iterator<Item = usize> {
    let start = start.clamp(first, last);
    // The next index above (from `start` itself), the last one below.
    let (mut above, mut below) = (start, start);
    let mut up_next = true;
    std::iter::from_fn(move || {
        let (up, down) = (above <= last, below > first);
        if up && (up_next || !down) {
            up_next = false;
            above += 1;
            Some(above - 1)
        } else if down {
            up_next = true;
            below -= 1;
            Some(below)
        } else {
            None
        }
    })
}

/// Whether `p` lies in the closed triangle `t`.
fn in_triangle(p: P2, t: [P2; 3]) -> bool {
    inside_by_sides(sides(p, t))
}

/// The cross products of the edges `t0 t1`, `t1 t2`, `t2 t0` with `p`'s
/// offset from each edge's start.
#[inline]
fn sides(p: P2, t: [P2; 3]) -> [f64; 3] {
    let side = |a: P2, b: P2| (b - a).perp_dot(p - a);
    [side(t[0], t[1]), side(t[1], t[2]), side(t[2], t[0])]
}

/// [`in_triangle`] from the [`sides`].
#[inline]
fn inside_by_sides(s: [f64; 3]) -> bool {
    (s[0] >= 0.0 && s[1] >= 0.0 && s[2] >= 0.0) || (s[0] <= 0.0 && s[1] <= 0.0 && s[2] <= 0.0)
}

/// Whether the closed segments `a`-`b` and `c`-`d` meet.
fn segments_meet(a: P2, b: P2, c: P2, d: P2) -> bool {
    let (d1, d2) = ((b - a).perp_dot(c - a), (b - a).perp_dot(d - a));
    let (d3, d4) = ((d - c).perp_dot(a - c), (d - c).perp_dot(b - c));
    (d1 * d2 <= 0.0) && (d3 * d4 <= 0.0) && {
        // Collinear segments meet only when their extents overlap.
        let overlap =
            |i: usize| a[i].min(b[i]) <= c[i].max(d[i]) && c[i].min(d[i]) <= a[i].max(b[i]);
        overlap(0) && overlap(1)
    }
}

/// Distance from segment `a`-`b` to the closed triangle `t`: 0 when they
/// meet, else the smallest of the ends' distances to the edges and the
/// corners' distances to the segment.
fn segment_triangle_distance(a: P2, b: P2, t: [P2; 3]) -> f64 {
    if in_triangle(a, t) || in_triangle(b, t) {
        return 0.0;
    }
    let edges = [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])];
    if edges.iter().any(|&(c, d)| segments_meet(a, b, c, d)) {
        return 0.0;
    }
    let ends = edges
        .iter()
        .flat_map(|&(c, d)| [segment_distance(a, c, d), segment_distance(b, c, d)]);
    let corners = t.iter().map(|&c| segment_distance(c, a, b));
    ends.chain(corners).fold(f64::INFINITY, f64::min)
}

/// [`segment_triangle_distance`], by the shorter way for a point.
fn distance_to_triangle(a: P2, b: P2, t: [P2; 3]) -> f64 {
    if a == b {
        point_triangle_distance(a, t)
    } else {
        segment_triangle_distance(a, b, t)
    }
}

/// [`segment_triangle_distance`] of the segment `p`-`p`, bit for bit, with
/// the work for the second end left out and the cross products computed
/// once: a point meets an edge when it is on its line (the cross products
/// vanish) within its extent, and a corner's distance to the point is the
/// distance of the degenerate segment.
fn point_triangle_distance(p: P2, t: [P2; 3]) -> f64 {
    let side = sides(p, t);
    if inside_by_sides(side) {
        return 0.0;
    }
    let edges = [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])];
    // `segments_meet(p, p, c, d)` with the cross products of the inside
    // test: of the degenerate segment's, two are products with a zero
    // vector (their product is a zero, always `<= 0`), and the other two
    // are both the side of edge `c`-`d`; its extents' overlap is `p`'s.
    let on_edge = |(&(c, d), s): (&(P2, P2), f64)| {
        let within = |i: usize| p[i] <= c[i].max(d[i]) && c[i].min(d[i]) <= p[i];
        s * s <= 0.0 && within(0) && within(1)
    };
    if edges.iter().zip(side).any(on_edge) {
        return 0.0;
    }
    // Squared, with one square root at the end: the rounded square root is
    // monotone, so the root of the smallest square is the smallest root
    // (and the smallest of squares, never NaN, is the same in any order).
    let end = |(c, d): (P2, P2)| segment_distance_squared(p, c, d);
    let corner = |c: P2| (c - p).length_squared();
    let ends = end(edges[0]).min(end(edges[1])).min(end(edges[2]));
    ends.min(corner(t[0]).min(corner(t[1])).min(corner(t[2])))
        .sqrt()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::field_of_view::tests::{random_fov, random_unit};
    use crate::tests::surrogate;
    use crate::trimmed::{triangle_corners, TRIANGLES};
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;
    use shroud_msg::{DarkCone, NoReturn};
    use shroud_surrogate::TrimMask;

    /// The unseen bound by exhaustion, as before `guard::trimmed_gaps`: the
    /// domain, the field of view and the dark cones as in
    /// [`Envelope::unseen_clearance`], then every trimmed triangle of the
    /// domain by the general segment distance, nothing skipped.
    fn unseen_by_exhaustion(env: &Envelope, shape: &Shape, config: &GuardConfig) -> f64 {
        let (a, b) = env.core_uv(shape);
        let cap = config.max_report;
        let offset = shape.radius() + env.slack(shape, config);
        let mut best = env.distance_outside_domain(a, b) - offset;
        if let Some(fov) = env.field_of_view() {
            let region = crate::field_of_view::ViewRegion::new(fov);
            best = best.min(clearance_outside(&region, shape, cap));
        }
        if let Some(dark) = env.dark() {
            best = best.min(dark.clearance(shape, cap.min(best.max(0.0))));
        }
        let (cells_s, cells_t) = env.cells();
        for (h, g) in (0..cells_t).flat_map(|g| (0..cells_s).map(move |h| (h, g))) {
            let kept = env.trim_bits(h, g);
            for (_, t) in TRIANGLES.iter().filter(|(bit, _)| kept & bit == 0) {
                let corners = triangle_corners(env.domain(), h, g, t);
                best = best.min(segment_triangle_distance(a, b, corners) - offset);
            }
        }
        best.clamp(0.0, cap)
    }

    /// A random surrogate (tilted frame, uneven steps, one side or both, a
    /// trim that keeps `kept` of the cells whole and trims the rest at
    /// random), maybe with a field of view and cones without a return.
    pub(crate) fn random_envelope(rng: &mut Pcg64, kept: f64) -> Envelope {
        let (cols, rows) = (rng.random_range(2..10), rng.random_range(2..10));
        let mut trim = TrimMask::full(cols - 1, rows - 1);
        for bits in trim.bits.iter_mut() {
            if !rng.random_bool(kept) {
                *bits = rng.random_range(0..15);
            }
        }
        let direction = random_unit(rng).to_array();
        let lower: Vec<f64> = (0..cols * rows)
            .map(|_| rng.random_range(-1.0..0.5))
            .collect();
        let upper: Vec<f64> = lower
            .iter()
            .map(|l| l + rng.random_range(0.0..0.5))
            .collect();
        let (upper, lower) = match rng.random_range(0..3) {
            0 => (Some(upper), None),
            1 => (None, Some(lower)),
            _ => (Some(upper), Some(lower)),
        };
        let mut sur = surrogate(direction, cols, rows, trim, upper, lower);
        sur.domain.u_min = rng.random_range(-3.0..3.0);
        sur.domain.v_min = rng.random_range(-3.0..3.0);
        sur.domain.u_step = rng.random_range(0.05..0.5);
        sur.domain.v_step = rng.random_range(0.05..0.5);
        let mut env = Envelope::new(&sur).expect("a valid surrogate");
        if rng.random_bool(0.3) {
            env = env.with_field_of_view(Some(random_fov(rng))).unwrap();
        }
        if rng.random_bool(0.3) {
            let cones = (0..rng.random_range(1..6))
                .map(|_| DarkCone {
                    axis: random_unit(rng).to_array(),
                    half_angle: rng.random_range(0.01..0.3),
                })
                .collect();
            let apex = [0; 3].map(|_| rng.random_range(-3.0..3.0));
            env = env.with_no_return(Some(&NoReturn { apex, cones })).unwrap();
        }
        env
    }

    /// A sphere or capsule near the domain of `env`, its core sometimes on
    /// cell borders and corners (where the gaps' bounds are tight).
    pub(crate) fn random_shape(rng: &mut Pcg64, env: &Envelope) -> Shape {
        let ([u0, u1], [v0, v1]) = env.uv_extent();
        let d = env.domain();
        let place = |rng: &mut Pcg64| {
            let (mut u, mut v) = (
                rng.random_range(u0 - 0.5..u1 + 0.5),
                rng.random_range(v0 - 0.5..v1 + 0.5),
            );
            if rng.random_bool(0.3) {
                u = d.u_min + ((u - d.u_min) / d.u_step * 2.0).round() * 0.5 * d.u_step;
                v = d.v_min + ((v - d.v_min) / d.v_step * 2.0).round() * 0.5 * d.v_step;
            }
            env.frame()
                .to_world(glam::DVec3::new(u, v, rng.random_range(-1.0..1.0)))
        };
        let radius = rng.random_range(0.001..0.4);
        let a = place(rng);
        if rng.random_bool(0.3) {
            let b = if rng.random_bool(0.5) {
                place(rng)
            } else {
                a + random_unit(rng) * 0.2
            };
            Shape::capsule(a, b, radius)
        } else {
            Shape::sphere(a, radius)
        }
    }

    #[test]
    fn outward_visits_every_index_once_nearest_first() {
        for (first, last) in [(0, 0), (0, 5), (3, 9)] {
            for start in 0..12 {
                let order: Vec<usize> = outward((first, last), start).collect();
                let mut sorted = order.clone();
                sorted.sort();
                assert_eq!(sorted, (first..=last).collect::<Vec<_>>());
                let from = start.clamp(first, last);
                let apart: Vec<usize> = order.iter().map(|i| i.abs_diff(from)).collect();
                assert!(apart.windows(2).all(|w| w[0] <= w[1]), "{order:?}");
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

        /// The unseen search with its skips is, bit for bit, the exhaustive
        /// minimum: never larger (that would be optimistic), never smaller.
        #[test]
        fn the_unseen_search_is_the_exhaustive_minimum(
            seed in any::<u64>(),
            kept in 0.0..1.0f64,
            cap in 0.01..3.0f64,
        ) {
            let mut rng = Pcg64::seed_from_u64(seed);
            let env = random_envelope(&mut rng, kept);
            let config = GuardConfig { stop_distance: 0.0, max_report: cap, ..GuardConfig::default() };
            for _ in 0..60 {
                let shape = random_shape(&mut rng, &env);
                let fast = env.unseen_clearance(&shape, &config);
                let exhaustive = unseen_by_exhaustion(&env, &shape, &config);
                prop_assert!(
                    fast == exhaustive,
                    "{shape:?}: {fast} vs exhaustive {exhaustive}"
                );
            }
        }

        /// A point's distance to a triangle is the degenerate segment's, bit
        /// for bit, on its edges and corners too.
        #[test]
        fn a_point_is_a_degenerate_segment(seed in any::<u64>()) {
            let mut rng = Pcg64::seed_from_u64(seed);
            // Coarse dyadic coordinates put points on edges and corners.
            let mut p = || P2::new(
                f64::from(rng.random_range(-8..8i32)) * 0.25,
                f64::from(rng.random_range(-8..8i32)) * 0.25,
            );
            for _ in 0..200 {
                let (q, t) = (p(), [p(), p(), p()]);
                let point = point_triangle_distance(q, t);
                let segment = segment_triangle_distance(q, q, t);
                prop_assert_eq!(point.to_bits(), segment.to_bits(), "{:?} {:?}", q, t);
            }
        }
    }

    /// The segment-to-triangle distance agrees with a dense sampling of both.
    #[test]
    fn segment_triangle_distance_agrees_with_sampling() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let mut p = || P2::new(rng.random_range(-2.0..2.0), rng.random_range(-2.0..2.0));
        for _ in 0..300 {
            let (a, b) = (p(), p());
            let t = [p(), p(), p()];
            let exact = segment_triangle_distance(a, b, t);
            let n = 60;
            let mut sampled = f64::INFINITY;
            for i in 0..=n {
                let x = i as f64 / n as f64;
                let q = a.lerp(b, x);
                let d = if in_triangle(q, t) {
                    0.0
                } else {
                    (0..3)
                        .map(|k| segment_distance(q, t[k], t[(k + 1) % 3]))
                        .fold(f64::INFINITY, f64::min)
                };
                sampled = sampled.min(d);
            }
            // Sampling only overestimates, by at most half a step.
            let step = a.distance(b) / n as f64;
            assert!(exact <= sampled + 1e-12, "{exact} > {sampled}");
            assert!(exact >= sampled - step, "{exact} < {sampled} - {step}");
        }
    }
}
