//! Quality measures of a blend: the gap between the transition surface and the
//! blending regions at the seams, and the overlap rate of a combined model
//! (the figure of merit of Zou et al., Sections 5-6).

use super::merge::{Merged, Source};
use super::pipeline::Blend;
use super::rbf::Rbf;
use glam::DVec3;
use shroud_geometry::cloud::NeighbourIndex;

/// Gap statistics over a set of seam points.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Gap {
    /// Seam points measured.
    pub count: usize,
    /// Distance to the zero set, |s| / |grad s|: the surface gap.
    pub surface_mean: f64,
    pub surface_max: f64,
    /// Distance to the nearest kept transition sample: the sampled gap.
    pub sampled_mean: f64,
    pub sampled_max: f64,
}

/// The gap at `seam` points (region points next to where T_R takes over).
pub fn seam_gap(rbf: &Rbf, seam: &[DVec3], transition: &NeighbourIndex) -> Gap {
    if seam.is_empty() {
        return Gap::default();
    }
    let surface: Vec<f64> = seam.iter().map(|&p| rbf.distance_estimate(p)).collect();
    let sampled: Vec<f64> = seam
        .iter()
        .map(|&p| transition.nearest_one(p).map_or(f64::INFINITY, |(_, d)| d))
        .collect();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    Gap {
        count: seam.len(),
        surface_mean: mean(&surface),
        surface_max: max(&surface),
        sampled_mean: mean(&sampled),
        sampled_max: max(&sampled),
    }
}

/// The seam points of a blend: the F_p points within `width` inside P_out (where
/// the kept parent meets T_R) and the F_c points within `width` below P_front
/// (where the kept child meets T_R).
pub fn seam_points(blend: &Blend, parent: &[DVec3], width: f64) -> (Vec<DVec3>, Vec<DVec3>) {
    let r = &blend.regions;
    let parent_seam = r
        .parent_region
        .iter()
        .map(|&i| parent[i])
        .filter(|&p| r.outline_distance(p, r.d_out) >= r.d_out - width)
        .collect();
    let child_seam = r
        .child_region
        .iter()
        .map(|&i| blend.child_points[i])
        .filter(|&p| r.plane.height(p) >= r.front - width)
        .collect();
    (parent_seam, child_seam)
}

/// Fraction of the points of `cloud` that have a point from a *different* source
/// within `radius`: double layers where parts overlap. A clean merge only has
/// such pairs along the seams (curves), a plain union over whole areas.
pub fn overlap_rate(cloud: &Merged, radius: f64) -> f64 {
    if cloud.is_empty() {
        return 0.0;
    }
    let by_source = |s: Source| -> NeighbourIndex {
        NeighbourIndex::new(
            cloud
                .points
                .iter()
                .zip(&cloud.sources)
                .filter(|(_, &t)| t == s)
                .map(|(p, _)| *p)
                .collect(),
        )
    };
    let indexes = [
        (Source::Parent, by_source(Source::Parent)),
        (Source::Child, by_source(Source::Child)),
        (Source::Transition, by_source(Source::Transition)),
    ];
    let overlapping = cloud
        .points
        .iter()
        .zip(&cloud.sources)
        .filter(|(p, s)| {
            indexes
                .iter()
                .filter(|(t, _)| t != *s)
                .any(|(_, index)| index.nearest_one(**p).is_some_and(|(_, d)| d < radius))
        })
        .count();
    overlapping as f64 / cloud.len() as f64
}
