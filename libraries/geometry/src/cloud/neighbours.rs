//! Neighbour search over a point cloud: a kd-tree (kiddo's immutable tree) over f64
//! positions, k-nearest and radius queries, and the typical sample spacing.

use glam::DVec3;
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use std::num::NonZeroUsize;

/// A kd-tree over a fixed set of points; query results are indices into them.
pub struct NeighbourIndex {
    points: Vec<DVec3>,
    /// `None` for an empty cloud (the tree cannot be built over no points).
    tree: Option<ImmutableKdTree<f64, 3>>,
}

impl std::fmt::Debug for NeighbourIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NeighbourIndex")
            .field("points", &self.points.len())
            .finish()
    }
}

impl NeighbourIndex {
    /// Builds the tree. Callers validate the points (finite) beforehand.
    pub fn new(points: Vec<DVec3>) -> Self {
        let coords: Vec<[f64; 3]> = points.iter().map(|p| p.to_array()).collect();
        let tree = (!coords.is_empty()).then(|| ImmutableKdTree::new_from_slice(&coords));
        Self { points, tree }
    }

    /// From raw f32 triples.
    pub fn from_f32(points: &[[f32; 3]]) -> Self {
        Self::new(points.iter().map(|p| to_dvec3(*p)).collect())
    }

    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The `k` nearest points to `query` (including a point at `query` itself),
    /// nearest first, as `(index, distance)`.
    pub fn nearest(&self, query: DVec3, k: usize) -> Vec<(usize, f64)> {
        let (Some(k), Some(tree)) = (NonZeroUsize::new(k.min(self.points.len())), &self.tree)
        else {
            return Vec::new();
        };
        tree.nearest_n::<SquaredEuclidean>(&query.to_array(), k)
            .into_iter()
            .map(|n| (n.item as usize, n.distance.sqrt()))
            .collect()
    }

    /// The nearest point to `query` as `(index, distance)`, `None` when empty.
    pub fn nearest_one(&self, query: DVec3) -> Option<(usize, f64)> {
        let n = self
            .tree
            .as_ref()?
            .nearest_one::<SquaredEuclidean>(&query.to_array());
        Some((n.item as usize, n.distance.sqrt()))
    }

    /// Every point within `radius` of `query` (unsorted) as `(index, distance)`.
    pub fn within(&self, query: DVec3, radius: f64) -> Vec<(usize, f64)> {
        let Some(tree) = self.tree.as_ref().filter(|_| radius >= 0.0) else {
            return Vec::new();
        };
        tree.within_unsorted::<SquaredEuclidean>(&query.to_array(), radius * radius)
            .into_iter()
            .map(|n| (n.item as usize, n.distance.sqrt()))
            .collect()
    }

    /// Median distance from a point to its nearest other point, over an evenly
    /// strided sample of at most `samples` points: the cloud's sampling spacing.
    /// Zero for fewer than two distinct points.
    pub fn spacing(&self, samples: usize) -> f64 {
        let n = self.points.len();
        if n < 2 {
            return 0.0;
        }
        let stride = (n / samples.max(1)).max(1);
        let mut d: Vec<f64> = (0..n)
            .step_by(stride)
            .filter_map(|i| {
                self.nearest(self.points[i], 2)
                    .into_iter()
                    .find(|&(j, _)| j != i)
                    .map(|(_, d)| d)
            })
            .collect();
        if d.is_empty() {
            return 0.0;
        }
        let mid = d.len() / 2;
        d.select_nth_unstable_by(mid, f64::total_cmp);
        d[mid]
    }
}

/// f32 triple to f64 vector.
pub fn to_dvec3(p: [f32; 3]) -> DVec3 {
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

/// f64 vector to f32 triple.
pub fn to_f32(p: DVec3) -> [f32; 3] {
    [p.x as f32, p.y as f32, p.z as f32]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_neighbours_and_spacing() {
        let pts: Vec<DVec3> = (0..100)
            .map(|i| DVec3::new(f64::from(i % 10), f64::from(i / 10), 0.0) * 0.5)
            .collect();
        let index = NeighbourIndex::new(pts);
        let near = index.nearest(DVec3::new(1.0, 1.0, 0.1), 5);
        assert_eq!(near.len(), 5);
        assert_eq!(near[0].0, 22);
        assert!((index.spacing(50) - 0.5).abs() < 1e-12);
        assert_eq!(index.within(DVec3::new(1.0, 1.0, 0.0), 0.51).len(), 5);
        assert!(NeighbourIndex::new(Vec::new())
            .nearest(DVec3::ZERO, 3)
            .is_empty());
    }
}
