//! Boundary candidates ordered into closed loops. Candidates form a band a few
//! points wide along each rim, with holes where random sampling left a rim
//! point unmarked; walking it point by point breaks at the first hole. So the
//! band is treated as a graph instead: two candidates are linked when they lie
//! within the larger of their neighbourhood radii (about `sqrt(k)` spacings,
//! so the graph bridges holes of several spacings whatever the local density),
//! its connected components are the rim pieces, and a piece is a loop when it
//! holds two separate paths between two far-apart points: the shortest path
//! (Dijkstra), then the shortest one that keeps away from it except near its
//! ends. Their union, in order, is the loop. Spurs of noise hanging off the
//! band do not matter: shortest paths ignore them.

use super::super::neighbours::NeighbourIndex;
use glam::DVec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A closed chain of boundary points.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryLoop {
    /// Indices into the cloud, in walking order (the loop closes back to the first).
    pub indices: Vec<usize>,
    /// Length of the closed polyline.
    pub length: f64,
}

/// The candidate graph: positions and weighted adjacency, by candidate number.
struct Band {
    points: Vec<DVec3>,
    edges: Vec<Vec<(usize, f64)>>,
}

/// Connected pieces of the band through `candidates` (indices into `points`,
/// each with its neighbourhood radius), as sublists of `candidates`.
pub fn rim_pieces(
    points: &[DVec3],
    candidates: &[(usize, f64)],
    link: f64,
) -> Vec<Vec<(usize, f64)>> {
    let band = Band::new(points, candidates, link);
    let mut piece_of = vec![usize::MAX; candidates.len()];
    let mut pieces = Vec::new();
    for seed in 0..candidates.len() {
        if piece_of[seed] != usize::MAX {
            continue;
        }
        let id = pieces.len();
        piece_of[seed] = id;
        let mut members = vec![seed];
        let mut at = 0;
        while let Some(&a) = members.get(at) {
            at += 1;
            for &(b, _) in &band.edges[a] {
                if piece_of[b] == usize::MAX {
                    piece_of[b] = id;
                    members.push(b);
                }
            }
        }
        pieces.push(members.iter().map(|&m| candidates[m]).collect());
    }
    pieces
}

/// The closed loop through the piece `members` (indices into `points`, each
/// with its neighbourhood radius), or `None` when the piece is an open arc or
/// a blob without a hole.
pub fn close_loop(points: &[DVec3], members: &[(usize, f64)], link: f64) -> Option<BoundaryLoop> {
    let band = Band::new(points, members, link);
    let n = band.points.len();
    if n < 4 {
        return None;
    }
    let centroid = band.points.iter().copied().sum::<DVec3>() / n as f64;
    let start = farthest(n, |i| band.points[i].distance(centroid));
    let (dist, previous) = band.shortest_paths(start, &vec![true; n]);
    // The farthest point along the band (unreachable ones cannot end a path).
    let end = farthest(n, |i| if dist[i].is_finite() { dist[i] } else { -1.0 });
    let first = path_to(&previous, end);
    // Keep away from the first path by the band's width (its typical link
    // length times a margin), except around the two ends, which both share.
    let mut radii: Vec<f64> = members.iter().map(|&(_, r)| r).collect();
    let width = 2.0 * median(&mut radii);
    let (s, e) = (band.points[start], band.points[end]);
    if s.distance(e) <= 2.0 * width {
        return None;
    }
    let open: Vec<bool> = band
        .points
        .iter()
        .map(|&p| {
            p.distance(s) <= width
                || p.distance(e) <= width
                || first.iter().all(|&j| band.points[j].distance(p) > width)
        })
        .collect();
    let (_, previous) = band.shortest_paths(start, &open);
    // No second path: the chain does not close.
    previous[end]?;
    let second = path_to(&previous, end);
    let mut order = first;
    order.extend(
        second
            .iter()
            .rev()
            .skip(1)
            .take(second.len().saturating_sub(2)),
    );
    let indices: Vec<usize> = order.iter().map(|&j| members[j].0).collect();
    let length: f64 = (0..indices.len())
        .map(|a| points[indices[a]].distance(points[indices[(a + 1) % indices.len()]]))
        .sum();
    // A loop hardly longer than the band is wide is a clump of noise, not a rim.
    (length > 8.0 * width).then_some(BoundaryLoop { indices, length })
}

impl Band {
    /// Links every pair of `members` closer than `link` times the larger of
    /// their radii.
    fn new(points: &[DVec3], members: &[(usize, f64)], link: f64) -> Self {
        let positions: Vec<DVec3> = members.iter().map(|&(i, _)| points[i]).collect();
        let index = NeighbourIndex::new(positions.clone());
        let widest = link * members.iter().map(|&(_, r)| r).fold(0.0, f64::max);
        let edges = members
            .iter()
            .enumerate()
            .map(|(a, &(_, ra))| {
                index
                    .within(positions[a], widest)
                    .into_iter()
                    .filter(|&(b, d)| b != a && d <= link * ra.max(members[b].1))
                    .collect()
            })
            .collect();
        Self {
            points: positions,
            edges,
        }
    }

    /// Dijkstra from `start` over the nodes marked `open`: distances and
    /// predecessors.
    fn shortest_paths(&self, start: usize, open: &[bool]) -> (Vec<f64>, Vec<Option<usize>>) {
        let n = self.points.len();
        let mut dist = vec![f64::INFINITY; n];
        let mut previous = vec![None; n];
        let mut heap = BinaryHeap::new();
        dist[start] = 0.0;
        heap.push(Reverse((Ordered(0.0), start)));
        while let Some(Reverse((Ordered(d), a))) = heap.pop() {
            if d > dist[a] {
                continue;
            }
            for &(b, w) in &self.edges[a] {
                if open[b] && d + w < dist[b] {
                    dist[b] = d + w;
                    previous[b] = Some(a);
                    heap.push(Reverse((Ordered(d + w), b)));
                }
            }
        }
        (dist, previous)
    }
}

/// The index below `count` maximising `key`.
fn farthest(count: usize, key: impl Fn(usize) -> f64) -> usize {
    (0..count)
        .max_by(|&a, &b| key(a).total_cmp(&key(b)))
        .unwrap_or(0)
}

/// The path from the Dijkstra root to `end`, root first.
fn path_to(previous: &[Option<usize>], end: usize) -> Vec<usize> {
    let mut path = vec![end];
    let mut at = end;
    while let Some(p) = previous[at] {
        path.push(p);
        at = p;
    }
    path.reverse();
    path
}

/// Median of `values` (reordered); 0 when empty.
fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mid = values.len() / 2;
    values.select_nth_unstable_by(mid, f64::total_cmp);
    values[mid]
}

/// `f64` ordered by `total_cmp`, for the heap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Ordered(f64);

impl Eq for Ordered {}

impl PartialOrd for Ordered {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Ordered {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    /// A band three points wide along `turn` radians of the unit circle,
    /// every point with link radius 0.06 (about three spacings).
    fn band(turn: f64) -> (Vec<DVec3>, Vec<(usize, f64)>) {
        let points: Vec<DVec3> = (0..300)
            .flat_map(|i| {
                (0..3).map(move |w| {
                    let (a, r) = (turn * f64::from(i) / 300.0, 1.0 + 0.02 * f64::from(w));
                    DVec3::new(r * a.cos(), r * a.sin(), 0.0)
                })
            })
            .collect();
        let members = (0..points.len()).map(|i| (i, 0.06)).collect();
        (points, members)
    }

    #[test]
    fn a_ring_closes_and_an_arc_does_not() {
        let (ring, members) = band(TAU);
        assert_eq!(rim_pieces(&ring, &members, 1.0).len(), 1);
        let rim = close_loop(&ring, &members, 1.0).expect("a closed ring");
        assert!((rim.length / TAU - 1.0).abs() < 0.1, "{}", rim.length);
        let (arc, members) = band(0.75 * TAU);
        assert_eq!(rim_pieces(&arc, &members, 1.0).len(), 1);
        assert_eq!(close_loop(&arc, &members, 1.0), None);
    }

    #[test]
    fn far_apart_pieces_stay_apart() {
        let (mut points, _) = band(TAU);
        points.extend(band(TAU).0.iter().map(|&p| p + DVec3::new(5.0, 0.0, 0.0)));
        let members: Vec<(usize, f64)> = (0..points.len()).map(|i| (i, 0.06)).collect();
        let pieces = rim_pieces(&points, &members, 1.0);
        assert_eq!(pieces.iter().map(Vec::len).collect::<Vec<_>>(), [900, 900]);
    }
}
