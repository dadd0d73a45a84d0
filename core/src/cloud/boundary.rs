//! Open-boundary detection on point clouds (the role of Qian et al. 2005 in Zou et
//! al., Section 3.1): a point is on the boundary when its neighbours, seen in its
//! tangent plane, leave a wide angular gap. Boundary points are then chained into
//! closed loops, the candidates for the polygon of interest P_inter.

use super::neighbours::NeighbourIndex;
use super::plane::fit_plane;
use glam::DVec3;
use rayon::prelude::*;

/// Tuning of [`boundary_points`] and [`boundary_loops`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryParams {
    /// Neighbours looked at around each point.
    pub k: usize,
    /// Smallest angular gap (radians) between consecutive neighbours, around the
    /// point in its tangent plane, that makes it a boundary point.
    pub min_gap: f64,
    /// Largest step between consecutive loop points, in units of the cloud's
    /// sampling spacing.
    pub link: f64,
    /// Loops with fewer points are dropped (noise, small holes from sampling).
    pub min_loop_points: usize,
}

impl Default for BoundaryParams {
    fn default() -> Self {
        Self {
            k: 20,
            min_gap: 2.0,
            link: 3.0,
            min_loop_points: 12,
        }
    }
}

/// A closed chain of boundary points.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryLoop {
    /// Indices into the cloud, in walking order (the loop closes back to the first).
    pub indices: Vec<usize>,
    /// Length of the closed polyline.
    pub length: f64,
}

/// Marks the points of `index` whose largest angular gap between neighbours
/// (projected on the local least-squares plane) is at least `params.min_gap`.
pub fn boundary_points(index: &NeighbourIndex, params: &BoundaryParams) -> Vec<bool> {
    let pts = index.points();
    (0..pts.len())
        .into_par_iter()
        .map(|i| largest_gap(index, i, params.k) >= params.min_gap)
        .collect()
}

/// Largest angle between consecutive neighbours of point `i` around it in its
/// tangent plane; `2 pi` when it has too few neighbours to tell.
pub fn largest_gap(index: &NeighbourIndex, i: usize, k: usize) -> f64 {
    let pts = index.points();
    let p = pts[i];
    let near = index.nearest(p, k.max(4) + 1);
    let Some(fit) = fit_plane(near.iter().map(|&(j, _)| pts[j])) else {
        return std::f64::consts::TAU;
    };
    let (u, v) = (fit.axes[2], fit.axes[1]);
    let mut angles: Vec<f64> = near
        .iter()
        .filter(|&&(j, d)| j != i && d > 0.0)
        .map(|&(j, _)| {
            let d = pts[j] - p;
            d.dot(v).atan2(d.dot(u))
        })
        .collect();
    if angles.len() < 3 {
        return std::f64::consts::TAU;
    }
    angles.sort_by(f64::total_cmp);
    let wrap = std::f64::consts::TAU - (angles[angles.len() - 1] - angles[0]);
    angles.windows(2).map(|w| w[1] - w[0]).fold(wrap, f64::max)
}

/// Closed loops of boundary points, longest first. Each walk steps to the nearest
/// unused boundary point ahead (within `link` spacings), absorbing the boundary
/// band it passes, and is kept if it comes back to its start.
pub fn boundary_loops(index: &NeighbourIndex, params: &BoundaryParams) -> Vec<BoundaryLoop> {
    let pts = index.points();
    let on_boundary = boundary_points(index, params);
    let members: Vec<usize> = (0..pts.len()).filter(|&i| on_boundary[i]).collect();
    if members.len() < params.min_loop_points.max(3) {
        return Vec::new();
    }
    let spacing = index.spacing(512);
    if spacing <= 0.0 {
        return Vec::new();
    }
    let reach = params.link * spacing;
    let band = NeighbourIndex::new(members.iter().map(|&i| pts[i]).collect());
    let pos = band.points();
    let mut used = vec![false; members.len()];
    let mut loops = Vec::new();
    for start in 0..members.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut path = vec![start];
        let mut current = start;
        let mut heading: Option<DVec3> = None;
        let mut farthest: f64 = 0.0;
        let closed = loop {
            let back = pos[current].distance(pos[start]);
            farthest = farthest.max(back);
            let can_close = path.len() >= params.min_loop_points && farthest > 2.0 * reach;
            if can_close && back <= reach && path.len() > 2 {
                break true;
            }
            let near = band.within(pos[current], 3.0 * reach);
            for &(j, d) in &near {
                if d <= spacing && j != start {
                    used[j] = true;
                }
            }
            // The nearest unused point ahead, looking further across sampling gaps.
            let ahead = |&&(j, d): &&(usize, f64)| {
                !used[j]
                    && d > 0.0
                    && heading.is_none_or(|h| (pos[j] - pos[current]).dot(h) > -0.2 * d)
            };
            let next = [1.0, 2.0, 3.0].iter().find_map(|&scale| {
                near.iter()
                    .filter(ahead)
                    .filter(|&&(_, d)| d <= scale * reach)
                    .min_by(|a, b| a.1.total_cmp(&b.1))
            });
            match next {
                Some(&(j, _)) => {
                    heading = Some((pos[j] - pos[current]).normalize_or_zero());
                    used[j] = true;
                    path.push(j);
                    current = j;
                }
                None => break can_close && back <= 3.0 * reach,
            }
        };
        if closed {
            let indices: Vec<usize> = path.iter().map(|&j| members[j]).collect();
            let length = (0..indices.len())
                .map(|a| pts[indices[a]].distance(pts[indices[(a + 1) % indices.len()]]))
                .sum();
            loops.push(BoundaryLoop { indices, length });
        }
    }
    loops.sort_by(|a, b| b.length.total_cmp(&a.length));
    loops
}
