//! A bounding volume hierarchy over a triangle mesh, built once with a binned
//! surface-area heuristic, and ray queries by Möller–Trumbore intersection.
//! Geometry is stored in f32 (as the emitted points are); nodes are 32 bytes and
//! triangles are stored pre-shifted (`v0`, `e1`, `e2`) in leaf order.

use crate::error::SceneError;
use glam::Vec3A;
use shroud_shapes::format::TriangleMesh;

/// Bins of the surface-area heuristic along the split axis.
const BINS: usize = 16;
/// Most triangles in a leaf that the heuristic may keep unsplit.
const MAX_LEAF: usize = 8;
/// Deepest node; deeper ranges become leaves so the traversal stack never overflows.
const MAX_DEPTH: usize = 60;
/// Slack on the barycentric tests so that a ray through an edge shared by two
/// triangles hits at least one of them despite rounding (no cracks in a mesh).
const EDGE_SLACK: f32 = 1e-6;

/// A node: its box and either two children (`count == 0`, children at `start`
/// and `start + 1`) or a leaf of `count` triangles from `start`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    min: [f32; 3],
    start: u32,
    max: [f32; 3],
    count: u32,
}

/// A triangle as its first vertex and two edge vectors.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Triangle {
    v0: Vec3A,
    e1: Vec3A,
    e2: Vec3A,
}

/// The nearest intersection of a ray with the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// Ray parameter `t` of the hit: the point is `origin + t * direction` (the
    /// distance when the direction is a unit vector).
    pub distance: f32,
    /// Index of the hit triangle in the mesh the BVH was built from.
    pub triangle: u32,
    /// Unit geometric normal of the hit triangle, on the side its vertices are
    /// counter-clockwise (not flipped towards the ray).
    pub normal: [f32; 3],
}

/// A BVH over the triangles of one mesh. Triangles of zero area are left out
/// (no ray can hit them). Immutable once built; share it behind an `Arc`.
#[derive(Debug, Clone, PartialEq)]
pub struct Bvh {
    nodes: Vec<Node>,
    triangles: Vec<Triangle>,
    /// Mesh index of each stored triangle.
    ids: Vec<u32>,
}

impl Bvh {
    /// Builds the hierarchy. Fails on a mesh without vertices or triangles, a
    /// vertex that is not finite (also once narrowed to f32), an index past the
    /// vertices, or a mesh whose triangles all have zero area.
    pub fn build(mesh: &TriangleMesh) -> Result<Self, SceneError> {
        let prims = primitives(mesh)?;
        let mut builder = Builder {
            bounds: prims.iter().map(|p| bounds_of(&p.0)).collect(),
            centroids: prims
                .iter()
                .map(|p| (p.0[0] + p.0[1] + p.0[2]) / 3.0)
                .collect(),
            order: (0..prims.len() as u32).collect(),
            nodes: Vec::with_capacity(2 * prims.len()),
        };
        builder.build();
        let triangles = builder
            .order
            .iter()
            .map(|&i| {
                let [a, b, c] = prims[i as usize].0;
                Triangle {
                    v0: a,
                    e1: b - a,
                    e2: c - a,
                }
            })
            .collect();
        let ids = builder.order.iter().map(|&i| prims[i as usize].1).collect();
        Ok(Self {
            nodes: builder.nodes,
            triangles,
            ids,
        })
    }

    /// Number of triangles stored (those of positive area).
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of nodes of the hierarchy.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The box around every stored triangle, as `(min, max)` (padded by about
    /// 1e-5 of its largest coordinate).
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        (self.nodes[0].min, self.nodes[0].max)
    }

    /// The nearest hit of the ray `origin + t * direction` with `0 < t <
    /// max_distance`, or `None`. Both faces of every triangle are hit. The
    /// direction need not be unit length but must be finite and non-zero.
    pub fn intersect(
        &self,
        origin: [f32; 3],
        direction: [f32; 3],
        max_distance: f32,
    ) -> Option<RayHit> {
        let o = Vec3A::from(origin);
        let d = Vec3A::from(direction);
        // Zero components become tiny ones so that the slab test never computes
        // 0 * inf (NaN) for a ray in a box's face plane.
        let safe = d.to_array().map(|c| {
            if c.abs() < 1e-30 {
                1e-30f32.copysign(c)
            } else {
                c
            }
        });
        let inv = Vec3A::from(safe).recip();
        let mut best_t = max_distance;
        let mut best: Option<usize> = None;
        let mut stack = [0u32; MAX_DEPTH + 4];
        let mut depth = 0;
        let mut node = 0usize;
        self.slab(node, o, inv, best_t)?;
        loop {
            let n = &self.nodes[node];
            if n.count > 0 {
                let start = n.start as usize;
                for i in start..start + n.count as usize {
                    if let Some(t) = intersect_triangle(&self.triangles[i], o, d, best_t) {
                        best_t = t;
                        best = Some(i);
                    }
                }
            } else {
                let left = n.start as usize;
                let near = self.slab(left, o, inv, best_t);
                let far = self.slab(left + 1, o, inv, best_t);
                match (near, far) {
                    (Some(a), Some(b)) => {
                        let (first, second) = if a <= b {
                            (left, left + 1)
                        } else {
                            (left + 1, left)
                        };
                        stack[depth] = second as u32;
                        depth += 1;
                        node = first;
                        continue;
                    }
                    (Some(_), None) => {
                        node = left;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = left + 1;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next node whose box the ray still reaches before the best hit.
            loop {
                if depth == 0 {
                    return best.map(|i| self.hit(i, best_t));
                }
                depth -= 1;
                node = stack[depth] as usize;
                if self.slab(node, o, inv, best_t).is_some() {
                    break;
                }
            }
        }
    }

    fn hit(&self, index: usize, distance: f32) -> RayHit {
        let t = &self.triangles[index];
        RayHit {
            distance,
            triangle: self.ids[index],
            normal: t.e1.cross(t.e2).normalize_or_zero().to_array(),
        }
    }

    /// Entry parameter of the ray into node `index`'s box if it enters it
    /// before `t_max`.
    #[inline]
    fn slab(&self, index: usize, o: Vec3A, inv: Vec3A, t_max: f32) -> Option<f32> {
        let n = &self.nodes[index];
        let t0 = (Vec3A::from(n.min) - o) * inv;
        let t1 = (Vec3A::from(n.max) - o) * inv;
        let enter = t0.min(t1).max_element().max(0.0);
        let exit = t0.max(t1).min_element().min(t_max);
        (enter <= exit).then_some(enter)
    }
}

/// Möller–Trumbore: the ray parameter of the hit in `(0, t_max)`, if any.
#[inline]
fn intersect_triangle(tri: &Triangle, o: Vec3A, d: Vec3A, t_max: f32) -> Option<f32> {
    let p = d.cross(tri.e2);
    let det = tri.e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - tri.v0;
    let u = s.dot(p) * inv;
    // Written so that NaN fails every test.
    if !(-EDGE_SLACK..=1.0 + EDGE_SLACK).contains(&u) {
        return None;
    }
    let q = s.cross(tri.e1);
    let v = d.dot(q) * inv;
    if !(v >= -EDGE_SLACK && u + v <= 1.0 + EDGE_SLACK) {
        return None;
    }
    let t = tri.e2.dot(q) * inv;
    (t > 0.0 && t < t_max).then_some(t)
}

/// The mesh's triangles of positive area as f32 corners with their mesh indices,
/// after checking the mesh.
fn primitives(mesh: &TriangleMesh) -> Result<Vec<([Vec3A; 3], u32)>, SceneError> {
    if mesh.vertices.is_empty() {
        return Err(SceneError::EmptyMesh {
            reason: "it has no vertices",
        });
    }
    if mesh.triangles.is_empty() {
        return Err(SceneError::EmptyMesh {
            reason: "it has no triangles",
        });
    }
    if mesh.triangles.len() > u32::MAX as usize {
        return Err(SceneError::TooManyPoints {
            parameter: "mesh.triangles".into(),
            value: mesh.triangles.len(),
            max: u32::MAX as usize,
        });
    }
    let mut vertices = Vec::with_capacity(mesh.vertices.len());
    for (vertex, v) in mesh.vertices.iter().enumerate() {
        let narrow = v.map(|c| c as f32);
        if let Some(k) = (0..3).find(|&k| !narrow[k].is_finite()) {
            return Err(SceneError::MeshVertexNotFinite {
                vertex,
                axis: k,
                value: v[k],
            });
        }
        vertices.push(Vec3A::from(narrow));
    }
    let mut prims = Vec::with_capacity(mesh.triangles.len());
    for (triangle, t) in mesh.triangles.iter().enumerate() {
        if let Some(&index) = t.iter().find(|&&i| i as usize >= vertices.len()) {
            return Err(SceneError::MeshIndexOutOfRange {
                triangle,
                index,
                vertices: vertices.len(),
            });
        }
        let corners = t.map(|i| vertices[i as usize]);
        let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        if normal != Vec3A::ZERO && normal.is_finite() {
            prims.push((corners, triangle as u32));
        }
    }
    if prims.is_empty() {
        return Err(SceneError::EmptyMesh {
            reason: "every triangle has zero area",
        });
    }
    Ok(prims)
}

fn bounds_of(corners: &[Vec3A; 3]) -> (Vec3A, Vec3A) {
    (
        corners[0].min(corners[1]).min(corners[2]),
        corners[0].max(corners[1]).max(corners[2]),
    )
}

/// Half the surface area of a box (the constant factor does not matter).
fn half_area(min: Vec3A, max: Vec3A) -> f32 {
    let e = (max - min).max(Vec3A::ZERO);
    e.x * e.y + e.y * e.z + e.z * e.x
}

struct Builder {
    bounds: Vec<(Vec3A, Vec3A)>,
    centroids: Vec<Vec3A>,
    /// Primitive indices, permuted so that every node covers a contiguous range.
    order: Vec<u32>,
    nodes: Vec<Node>,
}

/// One heuristic bin: its primitive count and box.
#[derive(Clone, Copy)]
struct Bin {
    count: usize,
    min: Vec3A,
    max: Vec3A,
}

impl Bin {
    const EMPTY: Self = Self {
        count: 0,
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    fn add(&mut self, min: Vec3A, max: Vec3A, count: usize) {
        self.count += count;
        self.min = self.min.min(min);
        self.max = self.max.max(max);
    }
}

impl Builder {
    fn build(&mut self) {
        self.nodes.push(self.leaf(0, self.order.len()));
        // (node, first primitive, end, depth)
        let mut pending = vec![(0usize, 0usize, self.order.len(), 0usize)];
        while let Some((node, start, end, depth)) = pending.pop() {
            let Some(mid) = self.split(start, end, depth) else {
                continue;
            };
            let left = self.nodes.len();
            self.nodes.push(self.leaf(start, mid));
            self.nodes.push(self.leaf(mid, end));
            self.nodes[node].start = left as u32;
            self.nodes[node].count = 0;
            pending.push((left, start, mid, depth + 1));
            pending.push((left + 1, mid, end, depth + 1));
        }
    }

    /// A leaf node over `order[start..end]`. Its box is padded by a few f32 ulps
    /// of its coordinates, so that a ray running exactly in a face plane of the
    /// box (an axis-parallel ray along a mesh's border) still enters it, and so
    /// does a ray that meets a triangle within the edge slack.
    fn leaf(&self, start: usize, end: usize) -> Node {
        let mut bin = Bin::EMPTY;
        for &i in &self.order[start..end] {
            let (min, max) = self.bounds[i as usize];
            bin.add(min, max, 1);
        }
        let pad = 1e-5 * bin.min.abs().max(bin.max.abs()).max_element() + 1e-30;
        Node {
            min: (bin.min - Vec3A::splat(pad)).to_array(),
            start: start as u32,
            max: (bin.max + Vec3A::splat(pad)).to_array(),
            count: (end - start) as u32,
        }
    }

    /// Where to split `order[start..end]` (after partitioning it), or `None` to
    /// keep it a leaf.
    fn split(&mut self, start: usize, end: usize, depth: usize) -> Option<usize> {
        let count = end - start;
        if count <= 2 || depth >= MAX_DEPTH {
            return None;
        }
        let mut centre_min = Vec3A::splat(f32::INFINITY);
        let mut centre_max = Vec3A::splat(f32::NEG_INFINITY);
        let mut node = Bin::EMPTY;
        for &i in &self.order[start..end] {
            let c = self.centroids[i as usize];
            centre_min = centre_min.min(c);
            centre_max = centre_max.max(c);
            let (min, max) = self.bounds[i as usize];
            node.add(min, max, 1);
        }
        let extent = centre_max - centre_min;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        if extent[axis] <= 0.0 {
            // All centroids coincide: no plane separates them.
            return (count > MAX_LEAF).then(|| start + count / 2);
        }
        let scale = BINS as f32 / extent[axis];
        let bin_of = |c: Vec3A| (((c[axis] - centre_min[axis]) * scale) as usize).min(BINS - 1);
        let mut bins = [Bin::EMPTY; BINS];
        for &i in &self.order[start..end] {
            let (min, max) = self.bounds[i as usize];
            bins[bin_of(self.centroids[i as usize])].add(min, max, 1);
        }
        // Cost of splitting after bin k: area-weighted counts on both sides.
        let mut right_costs = [0.0f32; BINS];
        let mut right = Bin::EMPTY;
        for k in (1..BINS).rev() {
            right.add(bins[k].min, bins[k].max, bins[k].count);
            right_costs[k - 1] = half_area(right.min, right.max) * right.count as f32;
        }
        let mut left = Bin::EMPTY;
        let mut best = (f32::INFINITY, 0);
        for k in 0..BINS - 1 {
            left.add(bins[k].min, bins[k].max, bins[k].count);
            if left.count == 0 || left.count == count {
                continue;
            }
            let cost = half_area(left.min, left.max) * left.count as f32 + right_costs[k];
            if cost < best.0 {
                best = (cost, k);
            }
        }
        // Traversal costs about as much as one triangle test.
        let node_area = half_area(node.min, node.max);
        let leaf_cost = node_area * count as f32;
        let split_cost = node_area + best.0;
        if split_cost >= leaf_cost && count <= MAX_LEAF {
            return None;
        }
        if !best.0.is_finite() {
            return Some(start + count / 2);
        }
        let split_bin = best.1;
        let (centroids, range) = (&self.centroids, &mut self.order[start..end]);
        let mut mid = 0;
        for i in 0..range.len() {
            if bin_of(centroids[range[i] as usize]) <= split_bin {
                range.swap(i, mid);
                mid += 1;
            }
        }
        if mid == 0 || mid == count {
            return Some(start + count / 2);
        }
        Some(start + mid)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grid of `n x n` unit-square cells in the plane z = `z`.
    fn plane(n: u32, z: f64) -> TriangleMesh {
        let mut mesh = TriangleMesh::default();
        for j in 0..=n {
            for i in 0..=n {
                mesh.vertices.push([f64::from(i), f64::from(j), z]);
            }
        }
        let at = |i: u32, j: u32| j * (n + 1) + i;
        for j in 0..n {
            for i in 0..n {
                mesh.triangles
                    .push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                mesh.triangles
                    .push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        mesh
    }

    /// Brute force over every triangle, for comparison.
    fn brute(bvh: &Bvh, o: [f32; 3], d: [f32; 3], t_max: f32) -> Option<f32> {
        bvh.triangles
            .iter()
            .filter_map(|t| intersect_triangle(t, o.into(), d.into(), t_max))
            .reduce(f32::min)
    }

    #[test]
    fn agrees_with_brute_force_on_a_soup() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(9);
        let mut mesh = TriangleMesh::default();
        for k in 0..600u32 {
            let c: [f64; 3] = std::array::from_fn(|_| rng.random_range(-5.0..5.0));
            for _ in 0..3 {
                mesh.vertices
                    .push(std::array::from_fn(|a| c[a] + rng.random_range(-0.6..0.6)));
            }
            mesh.triangles.push([3 * k, 3 * k + 1, 3 * k + 2]);
        }
        let bvh = Bvh::build(&mesh).unwrap();
        assert_eq!(bvh.triangle_count(), 600);
        assert!(bvh.node_count() > 100);
        for _ in 0..3000 {
            let o: [f32; 3] = std::array::from_fn(|_| rng.random_range(-8.0..8.0));
            let d: [f32; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
            let hit = bvh.intersect(o, d, 100.0).map(|h| h.distance);
            assert_eq!(hit, brute(&bvh, o, d, 100.0));
        }
    }

    #[test]
    fn rays_through_shared_edges_and_vertices_never_fall_through() {
        let bvh = Bvh::build(&plane(8, 2.0)).unwrap();
        for i in 0..=32 {
            for j in 0..=32 {
                let o = [i as f32 * 0.25, j as f32 * 0.25, 5.0];
                let hit = bvh.intersect(o, [0.0, 0.0, -1.0], 10.0);
                assert_eq!(hit.map(|h| h.distance), Some(3.0), "{o:?}");
            }
        }
        let hit = bvh
            .intersect([4.0, 4.0, 0.0], [0.0, 0.0, 1.0], 10.0)
            .unwrap();
        assert_eq!(hit.distance, 2.0);
        assert_eq!(hit.normal, [0.0, 0.0, 1.0]);
        assert!(bvh
            .intersect([4.0, 4.0, 0.0], [0.0, 0.0, 1.0], 2.0)
            .is_none());
        assert!(bvh
            .intersect([4.0, 4.0, 0.0], [0.0, 0.0, -1.0], 10.0)
            .is_none());
        assert!(bvh
            .intersect([4.0, 4.0, 2.0], [1.0, 0.0, 0.0], 10.0)
            .is_none());
        assert!(bvh
            .intersect([9.0, 4.0, 5.0], [0.0, 0.0, -1.0], 10.0)
            .is_none());
    }

    #[test]
    fn reports_the_mesh_triangle_index() {
        let mut mesh = plane(2, 0.0);
        mesh.triangles.insert(0, [0, 0, 1]); // zero area: left out
        let bvh = Bvh::build(&mesh).unwrap();
        assert_eq!(bvh.triangle_count(), 8);
        // Cell (1, 0), lower-right triangle: mesh triangle 1 + 2 = 3.
        let hit = bvh
            .intersect([1.8, 0.2, 1.0], [0.0, 0.0, -1.0], 5.0)
            .unwrap();
        assert_eq!(hit.triangle, 3);
        let (min, max) = bvh.bounds();
        assert!(min.iter().all(|&c| (-1e-4..0.0).contains(&c)), "{min:?}");
        assert!(max[0] > 2.0 && max[0] < 2.0001 && max[2] > 0.0, "{max:?}");
    }

    #[test]
    fn bad_meshes_are_errors() {
        let good = plane(1, 0.0);
        let mut nan = good.clone();
        nan.vertices[2][1] = f64::NAN;
        let mut huge = good.clone();
        huge.vertices[1][2] = 1e300;
        let mut index = good.clone();
        index.triangles[1][2] = 4;
        let flat = TriangleMesh {
            vertices: vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]],
            triangles: vec![[0, 1, 2]],
        };
        let cases = [
            (TriangleMesh::default(), "no vertices"),
            (
                TriangleMesh {
                    triangles: vec![],
                    ..good.clone()
                },
                "no triangles",
            ),
            (nan, "vertex 2"),
            (huge, "vertex 1"),
            (index, "triangle 1"),
            (flat, "zero area"),
        ];
        for (mesh, expected) in cases {
            let err = Bvh::build(&mesh).unwrap_err();
            assert!(err.to_string().contains(expected), "{expected}: {err}");
        }
    }
}
