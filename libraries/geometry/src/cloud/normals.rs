//! Point normals by local least-squares plane fitting over the k nearest neighbours,
//! and a consistent orientation by propagation along the neighbour graph (Hoppe et
//! al. 1992: most-parallel neighbours first). Zou et al. estimate normals from local
//! triangulations (Section 5); local fitting gives the same normals without meshing.

use super::neighbours::NeighbourIndex;
use super::plane::fit_plane;
use glam::DVec3;
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Which way "outside" is, to fix the sign of normals where it is unambiguous.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Orientation {
    /// Outward is this direction everywhere (e.g. up for a terrain scan).
    Toward(DVec3),
    /// Outward points away from this point (e.g. the centroid of a closed-ish shape).
    AwayFrom(DVec3),
    /// Outward points away from the line through `origin` along `axis` (e.g. the
    /// walls of a child model standing on its polygon of interest).
    AwayFromAxis { origin: DVec3, axis: DVec3 },
}

impl Orientation {
    /// The outward reference direction at `p` (not normalised; may be zero).
    pub fn reference(&self, p: DVec3) -> DVec3 {
        match *self {
            Self::Toward(d) => d,
            Self::AwayFrom(c) => p - c,
            Self::AwayFromAxis { origin, axis } => {
                let axis = axis.normalize_or_zero();
                let d = p - origin;
                d - d.dot(axis) * axis
            }
        }
    }

    /// |cos| of the angle between `n` and the reference at `p`: how much the
    /// reference can be trusted to orient `n` there.
    fn confidence(&self, p: DVec3, n: DVec3) -> f64 {
        let r = self.reference(p);
        let len = r.length();
        if len > 0.0 && len.is_finite() {
            (n.dot(r) / len).abs()
        } else {
            0.0
        }
    }
}

/// Unoriented unit normals of `queries`, each from the least-squares plane of its
/// `k` nearest points in `index` (k is raised to at least 3). Points whose
/// neighbourhood is degenerate get the zero vector.
pub fn estimate_normals(index: &NeighbourIndex, queries: &[DVec3], k: usize) -> Vec<DVec3> {
    let k = k.max(3);
    queries
        .par_iter()
        .map(|&q| {
            let near = index.nearest(q, k);
            let pts = index.points();
            fit_plane(near.iter().map(|&(i, _)| pts[i]))
                .filter(|fit| fit.spread[1] > 0.0)
                .map(|fit| fit.plane.normal)
                .unwrap_or(DVec3::ZERO)
        })
        .collect()
}

#[derive(PartialEq)]
struct Edge {
    weight: f64,
    to: usize,
    from: usize,
}

impl Eq for Edge {}

impl PartialOrd for Edge {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Edge {
    fn cmp(&self, other: &Self) -> Ordering {
        self.weight.total_cmp(&other.weight)
    }
}

/// Flips `normals` (of `points`, in place) to a consistent orientation.
///
/// Each connected part of the `k`-nearest-neighbour graph is seeded at its point
/// whose normal is most parallel to `orientation`'s reference, and the sign then
/// propagates to the most parallel neighbour first. Where the reference is clear
/// (|cos| >= `trust`) it wins over propagation, so one bad crease cannot flip a
/// whole region; `trust > 1` means pure propagation after the seed.
pub fn orient_normals(
    points: &[DVec3],
    normals: &mut [DVec3],
    k: usize,
    orientation: Orientation,
    trust: f64,
) {
    let n = points.len().min(normals.len());
    if n == 0 {
        return;
    }
    let index = NeighbourIndex::new(points[..n].to_vec());
    let graph: Vec<Vec<usize>> = points[..n]
        .par_iter()
        .map(|&p| {
            index
                .nearest(p, k.max(2) + 1)
                .into_iter()
                .map(|(j, _)| j)
                .collect()
        })
        .collect();
    let confidence: Vec<f64> = (0..n)
        .map(|i| orientation.confidence(points[i], normals[i]))
        .collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| confidence[b].total_cmp(&confidence[a]));
    let mut done = vec![false; n];
    let mut heap = BinaryHeap::new();
    let align = |normal: &mut DVec3, p: DVec3| {
        if normal.dot(orientation.reference(p)) < 0.0 {
            *normal = -*normal;
        }
    };
    for seed in order {
        if done[seed] {
            continue;
        }
        align(&mut normals[seed], points[seed]);
        done[seed] = true;
        push_neighbours(&graph, normals, seed, &done, &mut heap);
        while let Some(Edge { to, from, .. }) = heap.pop() {
            if done[to] {
                continue;
            }
            if confidence[to] >= trust {
                align(&mut normals[to], points[to]);
            } else if normals[to].dot(normals[from]) < 0.0 {
                normals[to] = -normals[to];
            }
            done[to] = true;
            push_neighbours(&graph, normals, to, &done, &mut heap);
        }
    }
}

fn push_neighbours(
    graph: &[Vec<usize>],
    normals: &[DVec3],
    from: usize,
    done: &[bool],
    heap: &mut BinaryHeap<Edge>,
) {
    for &to in &graph[from] {
        if !done[to] {
            heap.push(Edge {
                weight: normals[from].dot(normals[to]).abs(),
                to,
                from,
            });
        }
    }
}

/// Estimated and oriented normals of every point of `index` (see
/// [`estimate_normals`] and [`orient_normals`]). Finally the whole set is flipped
/// if the reference, weighted by |cos|, disagrees with it overall (guards
/// against an unlucky seed on open surfaces).
pub fn oriented_normals(index: &NeighbourIndex, k: usize, orientation: Orientation) -> Vec<DVec3> {
    let mut normals = estimate_normals(index, index.points(), k);
    orient_normals(index.points(), &mut normals, k, orientation, 0.7);
    let vote: f64 = index
        .points()
        .iter()
        .zip(&normals)
        .map(|(&p, &n)| {
            let r = orientation.reference(p);
            let len = r.length();
            if len > 0.0 && len.is_finite() {
                n.dot(r) / len
            } else {
                0.0
            }
        })
        .sum();
    if vote < 0.0 {
        normals.iter_mut().for_each(|n| *n = -*n);
    }
    normals
}

/// A default idea of "outside" for a cloud: for a flat-ish cloud (smallest spread
/// under a tenth of the middle one: terrains, table tops, scans seen from one
/// side) the side of its least-squares plane facing +z (+x, +y if vertical);
/// otherwise away from its centroid.
pub fn default_orientation(points: &[DVec3]) -> Orientation {
    let Some(fit) = super::plane::fit_plane(points.iter().copied()) else {
        return Orientation::Toward(DVec3::Z);
    };
    if fit.spread[0] < 0.1 * fit.spread[1] {
        let n = fit.plane.normal;
        let key = if n.z.abs() > 1e-3 {
            n.z
        } else if n.x.abs() > 1e-3 {
            n.x
        } else {
            n.y
        };
        Orientation::Toward(if key < 0.0 { -n } else { n })
    } else {
        Orientation::AwayFrom(fit.plane.origin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere(n: usize) -> Vec<DVec3> {
        // Radius 2 around (1, 0, 0), the lattice's first point at the +y pole.
        crate::math::fibonacci_sphere(n)
            .into_iter()
            .map(|d| DVec3::new(1.0, 0.0, 0.0) + 2.0 * DVec3::new(d.x, d.z, d.y))
            .collect()
    }

    #[test]
    fn sphere_normals_point_outward() {
        let pts = sphere(2000);
        let index = NeighbourIndex::new(pts.clone());
        let centre = DVec3::new(1.0, 0.0, 0.0);
        let normals = oriented_normals(&index, 10, Orientation::AwayFrom(centre));
        for (p, n) in pts.iter().zip(&normals) {
            assert!(n.dot((*p - centre).normalize()) > 0.99, "{p} {n}");
        }
    }

    #[test]
    fn propagation_alone_is_consistent() {
        let pts = sphere(1500);
        let index = NeighbourIndex::new(pts.clone());
        let mut normals = estimate_normals(&index, &pts, 10);
        // Pure propagation from one seed oriented toward +y.
        orient_normals(&pts, &mut normals, 10, Orientation::Toward(DVec3::Y), 2.0);
        let centre = DVec3::new(1.0, 0.0, 0.0);
        let outward = pts
            .iter()
            .zip(&normals)
            .filter(|(p, n)| n.dot(**p - centre) > 0.0)
            .count();
        assert_eq!(outward, pts.len());
    }
}
