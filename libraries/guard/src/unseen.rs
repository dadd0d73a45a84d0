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
use super::field_of_view::clearance_outside;
use super::shape::Shape;
use super::Envelope;
use glam::DVec2;
use shroud_geometry::math::segment_distance;
use shroud_surrogate::trim::{BOTTOM, LEFT, RIGHT, TOP};

/// A point of the `(u, v)` plane.
type P2 = DVec2;

/// The four triangles of a cell in local coordinates: the edge, then the
/// centre (see `surrogate::trim`).
const TRIANGLES: [(u8, [P2; 3]); 4] = [
    (
        BOTTOM,
        [P2::new(0.0, 0.0), P2::new(1.0, 0.0), P2::new(0.5, 0.5)],
    ),
    (
        RIGHT,
        [P2::new(1.0, 0.0), P2::new(1.0, 1.0), P2::new(0.5, 0.5)],
    ),
    (
        TOP,
        [P2::new(1.0, 1.0), P2::new(0.0, 1.0), P2::new(0.5, 0.5)],
    ),
    (
        LEFT,
        [P2::new(0.0, 1.0), P2::new(0.0, 0.0), P2::new(0.5, 0.5)],
    ),
];

impl Envelope {
    /// Lower bound on the distance from `shape` to the space this view did
    /// not see (outside the domain, over a trimmed triangle, outside its
    /// sensor's field of view or along a ray that returned nothing when the
    /// cloud stated them), in `[0, max_report]`.
    pub(crate) fn unseen_clearance(&self, shape: &Shape, config: &GuardConfig) -> f64 {
        let (a, b) = match shape {
            Shape::Sphere(s) => {
                let c = self.to_frame(s.centre);
                (P2::new(c[0], c[1]), P2::new(c[0], c[1]))
            }
            Shape::Capsule(c) => {
                let (a, b) = (self.to_frame(c.a), self.to_frame(c.b));
                (P2::new(a[0], a[1]), P2::new(b[0], b[1]))
            }
        };
        let cap = config.max_report;
        let offset = shape.radius() + self.slack(shape, config);
        let mut best = self.distance_outside_domain(a, b) - offset;
        if let Some(fov) = self.field_of_view() {
            best = best.min(clearance_outside(fov, shape, cap));
        }
        if let Some(dark) = self.dark() {
            best = best.min(dark.clearance(shape, cap.min(best.max(0.0))));
        }
        let reach = cap + offset;
        let (lo_u, hi_u) = (a[0].min(b[0]) - reach, a[0].max(b[0]) + reach);
        let (lo_v, hi_v) = (a[1].min(b[1]) - reach, a[1].max(b[1]) + reach);
        if let (Some((h0, h1)), Some((g0, g1))) =
            (self.span(0, lo_u, hi_u), self.span(1, lo_v, hi_v))
        {
            let d = self.domain();
            // How far the core's extent along one axis lies from a cell's
            // interval: a lower bound on the distance to anything in the cell,
            // so cells no nearer than the current best are skipped.
            let gap = |lo: f64, hi: f64, start: f64, step: f64, k: usize| {
                let (c0, c1) = (start + k as f64 * step, start + (k + 1) as f64 * step);
                (c0 - hi).max(lo - c1).max(0.0)
            };
            let (u, v) = (
                [a[0].min(b[0]), a[0].max(b[0])],
                [a[1].min(b[1]), a[1].max(b[1])],
            );
            for g in g0..=g1 {
                if gap(v[0], v[1], d.v_min, d.v_step, g) - offset >= best {
                    continue;
                }
                for h in h0..=h1 {
                    if best <= 0.0 {
                        return 0.0;
                    }
                    if gap(u[0], u[1], d.u_min, d.u_step, h) - offset >= best {
                        continue;
                    }
                    let dist = self.distance_to_trimmed(h, g, a, b) - offset;
                    best = best.min(dist);
                }
            }
        }
        best.clamp(0.0, cap)
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

    /// Distance from segment `a`-`b` to the trimmed triangles of cell
    /// `(h, g)` (infinite when the cell is whole).
    fn distance_to_trimmed(&self, h: usize, g: usize, a: P2, b: P2) -> f64 {
        let kept = self.trim_bits(h, g);
        let d = self.domain();
        let to_uv = |p: P2| {
            P2::new(
                d.u_min + (h as f64 + p[0]) * d.u_step,
                d.v_min + (g as f64 + p[1]) * d.v_step,
            )
        };
        TRIANGLES
            .iter()
            .filter(|(bit, _)| kept & bit == 0)
            .map(|(_, t)| segment_triangle_distance(a, b, [to_uv(t[0]), to_uv(t[1]), to_uv(t[2])]))
            .fold(f64::INFINITY, f64::min)
    }
}

/// Whether `p` lies in the closed triangle `t`.
fn in_triangle(p: P2, t: [P2; 3]) -> bool {
    let s = [0, 1, 2].map(|i| (t[(i + 1) % 3] - t[i]).perp_dot(p - t[i]));
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

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

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
