//! Points on the Catmull-Clark limit surface of a quad mesh, with their parameters
//! on the control mesh: the point clouds of paper 004, Section 6.2 (clouds sampled
//! from subdivision limit surfaces of closed quad meshes).
//!
//! Parametrisation: face `f` of the control mesh carries bilinear parameters
//! `(u, v)` in `[0, 1]^2`, corner 0 at (0, 0), 1 at (1, 0), 2 at (1, 1), 3 at
//! (0, 1). One Catmull-Clark step splits it into the faces `4f + k`, child `k`
//! covering the quadrant at corner `k` ([`child_parameters`],
//! [`parent_parameters`]); `r` steps compose this ([`refine_parameters`]).
//!
//! Evaluation after refining `depth` times: on a fine face whose four corners are
//! inner vertices of valence 4 the limit surface IS the uniform bicubic B-spline
//! patch over the face and its eight neighbours, evaluated exactly. The remaining
//! fine faces (those touching an extraordinary or boundary vertex) use the
//! bilinear interpolation of their corners' exact limit positions: exact at the
//! corners, only C0 across their sides, and off the true surface by about
//! `h^2 * curvature / 8` with `h ~ 2^-depth` control edge lengths. They cover an
//! area fraction of about `4^-depth` control faces per extraordinary-vertex
//! valence (about 0.1 % of a face per EV at depth 5), plus a strip of width
//! `2^-depth` along any boundary.

use rayon::prelude::*;

use super::catmull_clark::catmull_clark;
use super::error::MeshError;
use super::half_edge::HalfEdgeMesh;
use super::quad_mesh::QuadMesh;

type P = [f64; 3];

/// Below this many samples, threads cost more than they save.
const PARALLEL_THRESHOLD: usize = 4096;

/// A point of the limit surface with its control-mesh parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitSample {
    /// Face of the control mesh.
    pub face: usize,
    /// First parameter, from corner 0 towards corner 1 of `face`.
    pub u: f64,
    /// Second parameter, from corner 0 towards corner 3 of `face`.
    pub v: f64,
    /// The limit-surface point.
    pub point: [f64; 3],
}

/// Draws `count` parameters uniformly (face uniform among control faces, then
/// `u`, `v` uniform in [0, 1)) from a splitmix64 stream seeded by `seed`, and
/// evaluates the limit surface there after refining `control` `depth` times (see
/// the module doc for the accuracy near extraordinary vertices). Same inputs,
/// same samples. The only error is [`MeshError::TooManyVertices`] when the
/// refined mesh would be too large.
pub fn sample_limit_surface(
    control: &QuadMesh,
    count: usize,
    seed: u64,
    depth: usize,
) -> Result<Vec<LimitSample>, MeshError> {
    if count == 0 {
        return Ok(Vec::new());
    }
    let fine = refine_mesh(control, depth)?;
    let params = draw_parameters(control.face_count(), count, seed);
    let eval = |&(face, u, v): &(usize, f64, f64)| {
        let (fine_face, s, t) = refine_parameters(face, u, v, depth);
        let point = limit_point(&fine, fine_face, s, t);
        LimitSample { face, u, v, point }
    };
    Ok(if count >= PARALLEL_THRESHOLD {
        params.par_iter().map(eval).collect()
    } else {
        params.iter().map(eval).collect()
    })
}

/// `mesh` refined `levels` times by Catmull-Clark; face numbering composes
/// `4f + k` per level.
pub fn refine_mesh(mesh: &QuadMesh, levels: usize) -> Result<QuadMesh, MeshError> {
    let mut fine = mesh.clone();
    for _ in 0..levels {
        fine = catmull_clark(&fine)?;
    }
    Ok(fine)
}

/// The most Catmull-Clark steps, up to `max_levels`, after which `mesh` has
/// at most `max_faces` faces (each step multiplies them by four); 0 when
/// even the mesh itself has more.
pub fn levels_within(mesh: &QuadMesh, max_levels: usize, max_faces: usize) -> usize {
    (0..=max_levels)
        .take_while(|&k| mesh.face_count().saturating_mul(1 << (2 * k)) <= max_faces)
        .last()
        .unwrap_or(0)
}

/// The splitmix64 generator: tiny, deterministic and good enough for sampling.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 53 random bits.
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in 0..n by multiply-shift (bias below n / 2^64).
    fn below(&mut self, n: usize) -> usize {
        ((u128::from(self.next_u64()) * n as u128) >> 64) as usize
    }
}

fn draw_parameters(faces: usize, count: usize, seed: u64) -> Vec<(usize, f64, f64)> {
    let mut rng = SplitMix64(seed);
    (0..count)
        .map(|_| {
            let face = rng.below(faces);
            let u = rng.unit();
            (face, u, rng.unit())
        })
        .collect()
}

/// Splits parameters `(u, v)` of a face into the child `k` (0..4) containing
/// them and the child's own parameters `(s, t)`: child corner 0 is the parent's
/// corner `k`, its first side runs towards parent corner `k + 1`, its last side
/// towards parent corner `k - 1` (as [`catmull_clark`] numbers them). Halves go
/// to the higher quadrant (u = 0.5 lies in children 1 or 2).
pub fn child_parameters(u: f64, v: f64) -> (usize, f64, f64) {
    match (u >= 0.5, v >= 0.5) {
        (false, false) => (0, 2.0 * u, 2.0 * v),
        (true, false) => (1, 2.0 * v, 2.0 - 2.0 * u),
        (true, true) => (2, 2.0 - 2.0 * u, 2.0 - 2.0 * v),
        (false, true) => (3, 2.0 - 2.0 * v, 2.0 * u),
    }
}

/// The inverse of [`child_parameters`]: parameters `(s, t)` of child `k` (taken
/// mod 4) as parameters of its parent. The map is the affine one sending child
/// corner 0 to parent corner `P_k`, child (1, 0) to the midpoint towards
/// `P_{k+1}` and child (0, 1) to the midpoint towards `P_{k-1}`.
pub fn parent_parameters(k: usize, s: f64, t: f64) -> (f64, f64) {
    match k % 4 {
        0 => (0.5 * s, 0.5 * t),
        1 => (1.0 - 0.5 * t, 0.5 * s),
        2 => (1.0 - 0.5 * s, 1.0 - 0.5 * t),
        _ => (0.5 * t, 1.0 - 0.5 * s),
    }
}

/// Re-expresses parameters `(u, v)` (clamped to [0, 1]) of control face `face`
/// on the mesh refined `levels` times: the fine face `face * 4^levels + ...`
/// containing them and its parameters.
pub fn refine_parameters(face: usize, u: f64, v: f64, levels: usize) -> (usize, f64, f64) {
    let (mut face, mut u, mut v) = (face, u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
    for _ in 0..levels {
        let (k, s, t) = child_parameters(u, v);
        (face, u, v) = (4 * face + k, s, t);
    }
    (face, u, v)
}

/// The inverse of [`refine_parameters`]: parameters of face `fine_face` of the
/// mesh refined `levels` times as parameters of its control face.
pub fn coarsen_parameters(fine_face: usize, s: f64, t: f64, levels: usize) -> (usize, f64, f64) {
    let (mut face, mut u, mut v) = (fine_face, s, t);
    for _ in 0..levels {
        (u, v) = parent_parameters(face % 4, u, v);
        face /= 4;
    }
    (face, u, v)
}

/// The Catmull-Clark limit position of vertex `v`: inner vertex of valence n,
/// `(n^2 p + 4 sum(edge neighbours) + sum(diagonal neighbours)) / (n (n + 5))`;
/// boundary vertex, `(a + 4 p + b) / 6` with its boundary neighbours; a corner
/// (one face) stays put. Panics if `v` is not a vertex of `mesh`.
pub fn limit_position(mesh: &QuadMesh, v: usize) -> [f64; 3] {
    let he = mesh.half_edges();
    let p = mesh.vertices();
    let out = he.outgoing(v);
    if he.is_boundary_vertex(v) {
        return boundary_limit(mesh, v);
    }
    let mut edges = [0.0; 3];
    let mut diagonals = [0.0; 3];
    for &h in out {
        edges = add(edges, p[he.target(h) as usize]);
        diagonals = add(diagonals, p[he.target(he.next(h)) as usize]);
    }
    let n = out.len() as f64;
    let sum = add(scale(p[v], n * n), add(scale(edges, 4.0), diagonals));
    scale(sum, 1.0 / (n * (n + 5.0)))
}

fn boundary_limit(mesh: &QuadMesh, v: usize) -> P {
    let he = mesh.half_edges();
    let p = mesh.vertices();
    let out = he.outgoing(v);
    let (Some(&first), Some(&last)) = (out.first(), out.last()) else {
        return p[v];
    };
    if out.len() == 1 {
        return p[v];
    }
    let a = p[he.target(first) as usize];
    let b = p[he.origin(he.prev(last)) as usize];
    scale(add(add(a, b), scale(p[v], 4.0)), 1.0 / 6.0)
}

/// The limit surface over face `face` of `mesh` at its parameters `(s, t)`:
/// exact on regular faces, the bilinear interpolation of the corners' limit
/// positions elsewhere (see the module doc). Panics if `face` is not a face.
pub fn limit_point(mesh: &QuadMesh, face: usize, s: f64, t: f64) -> [f64; 3] {
    match control_grid(mesh, face) {
        Some(grid) => bicubic(&grid, s, t),
        None => {
            let c = mesh.faces()[face].map(|v| limit_position(mesh, v as usize));
            bilinear(c, s, t)
        }
    }
}

fn is_regular_inner(he: &HalfEdgeMesh, v: usize) -> bool {
    !he.is_boundary_vertex(v) && he.faces_at(v) == 4
}

/// Grid slots `(i, j)` of corner `k`, its neighbour away from corner `k + 1`,
/// its diagonal outside the face, and its neighbour away from corner `k - 1`;
/// `i` runs from corner 0 to corner 1, `j` from corner 0 to corner 3.
const GRID_SLOTS: [[(usize, usize); 4]; 4] = [
    [(1, 1), (0, 1), (0, 0), (1, 0)],
    [(2, 1), (2, 0), (3, 0), (3, 1)],
    [(2, 2), (3, 2), (3, 3), (2, 3)],
    [(1, 2), (1, 3), (0, 3), (0, 2)],
];

/// The 4 x 4 B-spline control points of a face whose corners are all inner
/// vertices of valence 4, `None` otherwise.
fn control_grid(mesh: &QuadMesh, face: usize) -> Option<[[P; 4]; 4]> {
    let he = mesh.half_edges();
    let corners = mesh.faces()[face];
    if !corners.iter().all(|&c| is_regular_inner(he, c as usize)) {
        return None;
    }
    let p = mesh.vertices();
    let mut grid = [[[0.0; 3]; 4]; 4];
    for (k, slots) in GRID_SLOTS.iter().enumerate() {
        let ring = corner_ring(he, 4 * face + k)?;
        let points = [corners[k], ring[0], ring[1], ring[2]];
        for (&(i, j), &v) in slots.iter().zip(&points) {
            grid[i][j] = p[v as usize];
        }
    }
    Some(grid)
}

/// For the half-edge `h` leaving corner `c` of its face towards the next
/// corner: the vertices around `c` outside the face, i.e. the neighbour
/// opposite the next corner, the diagonal, and the neighbour opposite the
/// previous corner. Walks the two faces beyond the edge to the previous corner.
fn corner_ring(he: &HalfEdgeMesh, h: usize) -> Option<[u32; 3]> {
    let beside = he.opposite(he.prev(h))?;
    let behind = he.origin(he.prev(beside));
    let across = he.opposite(he.prev(beside))?;
    let diagonal = he.origin(he.prev(he.prev(across)));
    let below = he.origin(he.prev(across));
    Some([behind, diagonal, below])
}

/// Uniform cubic B-spline basis on one segment.
fn cubic_weights(s: f64) -> [f64; 4] {
    let r = 1.0 - s;
    let (s2, s3) = (s * s, s * s * s);
    [
        r * r * r / 6.0,
        (3.0 * s3 - 6.0 * s2 + 4.0) / 6.0,
        (-3.0 * s3 + 3.0 * s2 + 3.0 * s + 1.0) / 6.0,
        s3 / 6.0,
    ]
}

fn bicubic(grid: &[[P; 4]; 4], s: f64, t: f64) -> P {
    let (ws, wt) = (cubic_weights(s), cubic_weights(t));
    let mut point = [0.0; 3];
    for (row, wi) in grid.iter().zip(ws) {
        for (q, wj) in row.iter().zip(wt) {
            point = add(point, scale(*q, wi * wj));
        }
    }
    point
}

fn bilinear(c: [P; 4], s: f64, t: f64) -> P {
    let bottom = add(scale(c[0], 1.0 - s), scale(c[1], s));
    let top = add(scale(c[3], 1.0 - s), scale(c[2], s));
    add(scale(bottom, 1.0 - t), scale(top, t))
}

fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: P, s: f64) -> P {
    [a[0] * s, a[1] * s, a[2] * s]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{cube_mesh, l_block};

    /// Corner parameters of a face, in corner order.
    const CORNERS: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];

    fn dist(a: P, b: P) -> f64 {
        let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    }

    /// The L-block with every vertex moved a little, so that no symmetry of a
    /// square can hide a wrongly oriented parametrisation.
    fn jittered_l() -> QuadMesh {
        let (vertices, faces) = l_block().into_parts();
        let mut rng = SplitMix64(7);
        let vertices = vertices
            .into_iter()
            .map(|p| p.map(|x| x + 0.3 * (rng.unit() - 0.5)))
            .collect();
        QuadMesh::new(vertices, faces).unwrap()
    }

    /// An open n x n grid on an affine image of the plane.
    fn affine_grid(n: u32) -> QuadMesh {
        let m = n + 1;
        let map = |i: f64, j: f64| [i + 0.3 * j, 0.1 * i + 0.8 * j, 0.2 * i - 0.4 * j];
        let vertices = (0..m * m)
            .map(|x| map((x % m) as f64, (x / m) as f64))
            .collect();
        let v = |i: u32, j: u32| j * m + i;
        let faces = (0..n * n)
            .map(|x| {
                let (i, j) = (x % n, x / n);
                [v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]
            })
            .collect();
        QuadMesh::new(vertices, faces).unwrap()
    }

    fn bilinear_on(mesh: &QuadMesh, face: usize, u: f64, v: f64) -> P {
        let c = mesh.faces()[face].map(|i| mesh.vertices()[i as usize]);
        bilinear(c, u, v)
    }

    fn regular_faces(mesh: &QuadMesh) -> Vec<usize> {
        (0..mesh.face_count())
            .filter(|&f| control_grid(mesh, f).is_some())
            .collect()
    }

    #[test]
    fn bicubic_corner_is_the_limit_position() {
        for mesh in [refine_mesh(&cube_mesh(), 3), refine_mesh(&jittered_l(), 2)] {
            let mesh = mesh.unwrap();
            let regular = regular_faces(&mesh);
            assert!(regular.len() > mesh.face_count() / 2);
            for &f in &regular {
                for (k, &(s, t)) in CORNERS.iter().enumerate() {
                    let corner = mesh.faces()[f][k] as usize;
                    let d = dist(limit_point(&mesh, f, s, t), limit_position(&mesh, corner));
                    assert!(d < 1e-12, "face {f} corner {k}: {d}");
                }
            }
        }
    }

    #[test]
    fn regular_faces_agree_along_shared_edges() {
        let mesh = refine_mesh(&jittered_l(), 2).unwrap();
        let he = mesh.half_edges();
        let mut checked = 0;
        for f in regular_faces(&mesh) {
            for k in 0..4 {
                let Some(o) = he.opposite(4 * f + k) else {
                    continue;
                };
                let (g, m) = (o / 4, o % 4);
                if control_grid(&mesh, g).is_none() {
                    continue;
                }
                for lambda in [0.0, 0.25, 0.5, 0.9] {
                    let along = |k: usize, l: f64| {
                        let (a, b) = (CORNERS[k], CORNERS[(k + 1) % 4]);
                        (a.0 + l * (b.0 - a.0), a.1 + l * (b.1 - a.1))
                    };
                    let (s, t) = along(k, lambda);
                    let (s2, t2) = along(m, 1.0 - lambda);
                    let d = dist(limit_point(&mesh, f, s, t), limit_point(&mesh, g, s2, t2));
                    assert!(d < 1e-9, "faces {f}/{g}: {d}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 100);
    }

    #[test]
    fn regular_patches_reproduce_an_affine_grid() {
        let mesh = affine_grid(6);
        let regular = regular_faces(&mesh);
        assert_eq!(regular.len(), 16);
        for f in regular {
            for (s, t) in [(0.2, 0.7), (0.9, 0.1), (0.5, 0.5)] {
                let d = dist(limit_point(&mesh, f, s, t), bilinear_on(&mesh, f, s, t));
                assert!(d < 1e-12, "face {f}: {d}");
            }
        }
    }

    #[test]
    fn open_grid_samples_stay_in_its_plane() {
        let mesh = affine_grid(3);
        // Normal of the plane spanned by the affine map's columns.
        let (a, b) = ([1.0, 0.1, 0.2], [0.3, 0.8, -0.4]);
        let n = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        assert_eq!(limit_position(&mesh, 0), mesh.vertices()[0]);
        for sample in sample_limit_surface(&mesh, 500, 3, 2).unwrap() {
            let p = sample.point;
            assert!((p[0] * n[0] + p[1] * n[1] + p[2] * n[2]).abs() < 1e-12);
        }
    }

    #[test]
    fn cube_limit_points_lie_between_sphere_and_box() {
        let samples = sample_limit_surface(&cube_mesh(), 3000, 11, 3).unwrap();
        for s in &samples {
            assert!(s.point.iter().all(|&x| (0.0..=1.0).contains(&x)));
            let r = dist(s.point, [0.5; 3]);
            assert!(r > 0.41 && r < 0.434, "radius {r}");
        }
    }

    #[test]
    fn depth_does_not_move_points_on_regular_faces() {
        let control = jittered_l();
        let coarse = sample_limit_surface(&control, 2000, 5, 2).unwrap();
        let fine = sample_limit_surface(&control, 2000, 5, 4).unwrap();
        let mesh = refine_mesh(&control, 2).unwrap();
        let mut checked = 0;
        for (a, b) in coarse.iter().zip(&fine) {
            assert_eq!((a.face, a.u, a.v), (b.face, b.u, b.v));
            let (f, _, _) = refine_parameters(a.face, a.u, a.v, 2);
            if control_grid(&mesh, f).is_some() {
                assert!(dist(a.point, b.point) < 1e-9);
                checked += 1;
            }
        }
        assert!(checked > 1000);
    }

    #[test]
    fn parameters_round_trip() {
        let mut rng = SplitMix64(1);
        let mut cases: Vec<(f64, f64)> = (0..500).map(|_| (rng.unit(), rng.unit())).collect();
        cases.extend([(0.0, 0.0), (0.5, 0.5), (1.0, 1.0), (0.5, 0.0), (1.0, 0.25)]);
        for (i, &(u, v)) in cases.iter().enumerate() {
            let (k, s, t) = child_parameters(u, v);
            assert!((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t));
            let (u2, v2) = parent_parameters(k, s, t);
            assert!((u2 - u).abs() < 1e-15 && (v2 - v).abs() < 1e-15);
            for levels in 0..7 {
                let face = i % 13;
                let (fine, s, t) = refine_parameters(face, u, v, levels);
                assert_eq!(fine >> (2 * levels), face);
                let (f2, u2, v2) = coarsen_parameters(fine, s, t, levels);
                assert_eq!(f2, face);
                assert!((u2 - u).abs() < 1e-12 && (v2 - v).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn quadrants_match_catmull_clark_numbering() {
        let control = jittered_l();
        let fine = catmull_clark(&control).unwrap();
        let he = control.half_edges();
        let (nv, ne) = (control.vertex_count(), he.edge_count());
        // Position of a refined vertex before smoothing: the old vertex, the
        // edge midpoint, or the face centroid.
        let linear = |x: usize| -> P {
            if x < nv {
                return control.vertices()[x];
            }
            if x < nv + ne {
                let [a, b] = he.edge_vertices(x - nv);
                let (a, b) = (
                    control.vertices()[a as usize],
                    control.vertices()[b as usize],
                );
                return scale(add(a, b), 0.5);
            }
            bilinear_on(&control, x - nv - ne, 0.5, 0.5)
        };
        for f in 0..control.face_count() {
            for k in 0..4 {
                let child = fine.faces()[4 * f + k];
                assert_eq!(child[0], control.faces()[f][k]);
                assert_eq!(child[2] as usize, nv + ne + f);
                for (j, &(s, t)) in CORNERS.iter().enumerate() {
                    let (u, v) = parent_parameters(k, s, t);
                    let d = dist(bilinear_on(&control, f, u, v), linear(child[j] as usize));
                    assert!(d < 1e-12, "face {f} child {k} corner {j}");
                }
                let (u, v) = parent_parameters(k, 0.3, 0.6);
                assert_eq!(refine_parameters(f, u, v, 1).0, 4 * f + k);
            }
        }
    }

    #[test]
    fn sampling_is_deterministic() {
        let mesh = l_block();
        assert!(sample_limit_surface(&mesh, 0, 1, 3).unwrap().is_empty());
        let a = sample_limit_surface(&mesh, 5000, 42, 2).unwrap();
        let b = sample_limit_surface(&mesh, 5000, 42, 2).unwrap();
        let c = sample_limit_surface(&mesh, 5000, 43, 2).unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_eq!(a.len(), 5000);
        assert!(a.iter().all(|s| s.face < mesh.face_count()));
        assert!(a
            .iter()
            .all(|s| (0.0..1.0).contains(&s.u) && (0.0..1.0).contains(&s.v)));
        // Every control face gets samples.
        let mut hit = vec![false; mesh.face_count()];
        a.iter().for_each(|s| hit[s.face] = true);
        assert!(hit.iter().all(|&h| h));
    }
}
