//! Which points lie on an open boundary: the angle and half-disc criteria of
//! Bendels, Schnabel and Klein, "Detecting holes in point set surfaces" (WSCG
//! 2006, Section 3), on each point's k nearest neighbours projected into its
//! least-squares tangent plane.
//!
//! * Angle: the largest angular gap g between consecutive neighbours around the
//!   point; `P_angle = (g - 2π/k) / (π - 2π/k)` clamped to [0, 1] (1 for a
//!   half disc or less, 0 for perfectly even neighbours).
//! * Half disc: the neighbours' centroid shifts toward the interior at the
//!   boundary; for a half disc of radius R its distance from the point is
//!   `4R / 3π`, so `P_halfdisc = |centroid - p| / (4R / 3π)` clamped to [0, 1],
//!   with R the distance to the k-th neighbour. The shift is normalised by the
//!   local spacing, so it does not care how dense the scan is there.
//!
//! A point is a candidate when the mean of both reaches `min_score`. Random
//! (irregular) sampling leaves wide gaps inside the surface now and then; they
//! pass the angle criterion alone but rarely move the centroid, which is why
//! both are averaged (Bendels et al. weigh them likewise).

use super::super::neighbours::NeighbourIndex;
use super::super::plane::fit_plane;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::f64::consts::{PI, TAU};

/// One point's neighbourhood as the criteria see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbourhood {
    /// Mean of the angle and half-disc probabilities, in [0, 1].
    pub score: f64,
    /// Distance to the k-th neighbour: the local scale (links between rim
    /// points are measured in it).
    pub radius: f64,
}

/// [`Neighbourhood`] of every point of `index` over its `k` nearest neighbours
/// (k is raised to at least 4). A point without a tangent plane (too few
/// distinct neighbours) scores 1: nothing surrounds it.
pub fn neighbourhoods(index: &NeighbourIndex, k: usize) -> Vec<Neighbourhood> {
    (0..index.len())
        .into_par_iter()
        .map(|i| neighbourhood(index, i, k.max(4)))
        .collect()
}

fn neighbourhood(index: &NeighbourIndex, i: usize, k: usize) -> Neighbourhood {
    let pts = index.points();
    let p = pts[i];
    let near = index.nearest(p, k + 1);
    let radius = near.last().map_or(0.0, |&(_, d)| d);
    let lonely = Neighbourhood { score: 1.0, radius };
    let Some(fit) = fit_plane(near.iter().map(|&(j, _)| pts[j])) else {
        return lonely;
    };
    let offsets: Vec<DVec2> = near
        .iter()
        .filter(|&&(j, d)| j != i && d > 0.0)
        .map(|&(j, _)| in_plane(pts[j] - p, fit.axes))
        .collect();
    if offsets.len() < 3 || !(radius > 0.0) {
        return lonely;
    }
    let score = 0.5 * (angle_probability(&offsets) + half_disc_probability(&offsets, radius));
    Neighbourhood { score, radius }
}

/// `d` in the tangent plane of the fit with principal `axes` (normal first).
fn in_plane(d: DVec3, axes: [DVec3; 3]) -> DVec2 {
    DVec2::new(d.dot(axes[2]), d.dot(axes[1]))
}

/// Largest angle between consecutive `offsets` around the origin; `2π` for
/// fewer than two.
pub fn largest_gap(offsets: &[DVec2]) -> f64 {
    let mut angles: Vec<f64> = offsets.iter().map(|d| d.y.atan2(d.x)).collect();
    if angles.len() < 2 {
        return TAU;
    }
    angles.sort_by(f64::total_cmp);
    let wrap = TAU - (angles[angles.len() - 1] - angles[0]);
    angles.windows(2).map(|w| w[1] - w[0]).fold(wrap, f64::max)
}

/// Bendels et al.'s angle criterion for the neighbours at `offsets`.
fn angle_probability(offsets: &[DVec2]) -> f64 {
    let even = TAU / offsets.len() as f64;
    ((largest_gap(offsets) - even) / (PI - even)).clamp(0.0, 1.0)
}

/// Bendels et al.'s half-disc criterion for the neighbours at `offsets`
/// within `radius`.
fn half_disc_probability(offsets: &[DVec2], radius: f64) -> f64 {
    let centroid = offsets.iter().copied().sum::<DVec2>() / offsets.len() as f64;
    (centroid.length() / (4.0 * radius / (3.0 * PI))).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ring(count: usize, from: f64, to: f64) -> Vec<DVec2> {
        (0..count)
            .map(|i| {
                let a = from + (to - from) * (i as f64 + 0.5) / count as f64;
                DVec2::new(a.cos(), a.sin())
            })
            .collect()
    }

    #[test]
    fn a_full_ring_scores_zero_and_a_half_disc_one() {
        let full = ring(16, 0.0, TAU);
        assert!(angle_probability(&full) < 1e-9);
        assert!(half_disc_probability(&full, 1.0) < 1e-9);
        // A half disc filled evenly: gap π, centroid at 4R / 3π.
        let half: Vec<DVec2> = (1..=8)
            .flat_map(|r| {
                ring(4 * r, 0.0, PI)
                    .into_iter()
                    .map(move |d| d * r as f64 / 8.0)
            })
            .collect();
        assert!(angle_probability(&half) > 0.99);
        assert!(half_disc_probability(&half, 1.0) > 0.9);
        assert!((largest_gap(&ring(4, 0.0, PI)) - 1.25 * PI).abs() < 1e-9);
    }

    #[test]
    fn interior_points_of_a_grid_are_not_candidates_and_edges_are() {
        let pts: Vec<DVec3> = (0..400)
            .map(|i| DVec3::new(f64::from(i % 20), f64::from(i / 20), 0.0))
            .collect();
        let index = NeighbourIndex::new(pts);
        let n = neighbourhoods(&index, 20);
        assert!(n[10 * 20 + 10].score < 0.2, "{:?}", n[210]);
        assert!(n[10].score > 0.7, "edge {:?}", n[10]);
        assert!(n[0].score > 0.9, "corner {:?}", n[0]);
    }
}
