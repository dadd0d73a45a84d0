//! Closed quad meshes bounding unions of unit voxels (polycubes), and the named
//! polycube control meshes of the closed-surface fitting experiments (paper 004,
//! Section 6.2): an L-block, a ring (genus 1) and a staircase.

use std::collections::{BTreeSet, HashMap};

use super::error::MeshError;
use super::quad_mesh::QuadMesh;

/// Integer lattice point; `i64` so that `i32::MAX + 1` cannot overflow.
type Lattice = [i64; 3];

/// The closed quad mesh bounding the union of the unit voxels `cells` (voxel
/// `[i, j, k]` spans `[i, i+1] x [j, j+1] x [k, k+1]`).
///
/// Every voxel face not shared with another voxel of the set becomes one quad,
/// counter-clockwise seen from outside (as [`super::cube_mesh`]); vertices are
/// shared by integer position. Repeated cells count once. Faces come in the order
/// of the sorted cells, then -x, +x, -y, +y, -z, +z, so the result is
/// deterministic.
///
/// Errors: [`MeshError::NoFaces`] for an empty set; voxels touching only along
/// an edge or at a corner make the surface non-manifold, which
/// [`QuadMesh::new`] reports as [`MeshError::NonManifoldEdge`] or
/// [`MeshError::NonManifoldVertex`].
pub fn polycube(cells: &[[i32; 3]]) -> Result<QuadMesh, MeshError> {
    // A sorted set both deduplicates and fixes the face order.
    let set: BTreeSet<Lattice> = cells
        .iter()
        .map(|c| [i64::from(c[0]), i64::from(c[1]), i64::from(c[2])])
        .collect();
    let mut vertices = Vec::new();
    let mut index: HashMap<Lattice, u32> = HashMap::new();
    let mut faces = Vec::new();
    for cell in &set {
        for axis in 0..3 {
            for positive in [false, true] {
                let mut neighbour = *cell;
                neighbour[axis] += if positive { 1 } else { -1 };
                if set.contains(&neighbour) {
                    continue;
                }
                let quad = boundary_quad(*cell, axis, positive);
                faces.push(quad.map(|p| vertex_index(p, &mut vertices, &mut index)));
            }
        }
    }
    QuadMesh::new(vertices, faces)
}

/// The lattice corners of the face of `cell` normal to `axis` on its positive or
/// negative side, counter-clockwise seen from outside. With the cyclic axes
/// `b = axis + 1`, `c = axis + 2` we have `e_b x e_c = e_axis`, so the order
/// origin, +b, +b+c, +c faces the positive side; the negative side reverses it.
fn boundary_quad(cell: Lattice, axis: usize, positive: bool) -> [Lattice; 4] {
    let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut origin = cell;
    if positive {
        origin[axis] += 1;
    }
    let offset = |db: i64, dc: i64| {
        let mut p = origin;
        p[b] += db;
        p[c] += dc;
        p
    };
    if positive {
        [offset(0, 0), offset(1, 0), offset(1, 1), offset(0, 1)]
    } else {
        [offset(0, 0), offset(0, 1), offset(1, 1), offset(1, 0)]
    }
}

/// The index of lattice point `p`, appending it on first use.
fn vertex_index(
    p: Lattice,
    vertices: &mut Vec<[f64; 3]>,
    index: &mut HashMap<Lattice, u32>,
) -> u32 {
    *index.entry(p).or_insert_with(|| {
        vertices.push(p.map(|x| x as f64));
        // Saturating is harmless: with more than u32::MAX vertices
        // QuadMesh::new rejects the mesh before it looks at any face.
        u32::try_from(vertices.len() - 1).unwrap_or(u32::MAX)
    })
}

/// An L-shaped block one voxel thick: three voxels along x plus one on top of the
/// first along y (4 voxels, 3 x 2 footprint). 18 faces, 20 vertices, 36 edges;
/// the re-entrant corner gives two valence-5 vertices, the convex corners
/// valence-3 vertices.
pub fn l_block() -> QuadMesh {
    polycube(&[[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]])
        .unwrap_or_else(|_| unreachable!("the L-block is a manifold polycube"))
}

/// A 3 x 3 x 1 ring of 8 voxels around a missing centre: a genus-1 closed mesh,
/// 32 faces, 32 vertices, 64 edges (Euler characteristic 0). Outer corners give
/// valence-3 vertices, inner corners valence-5 vertices.
pub fn ring_block() -> QuadMesh {
    let cells: Vec<[i32; 3]> = (0..3)
        .flat_map(|i| (0..3).map(move |j| [i, j, 0]))
        .filter(|&c| c != [1, 1, 0])
        .collect();
    polycube(&cells).unwrap_or_else(|_| unreachable!("the ring is a manifold polycube"))
}

/// A three-step staircase one voxel deep: columns of heights 3, 2, 1 along x
/// (6 voxels). 24 faces, 26 vertices, 48 edges; the inner step edges give
/// valence-5 vertices, the outer corners valence-3 vertices.
pub fn step_block() -> QuadMesh {
    let cells: Vec<[i32; 3]> = (0..3)
        .flat_map(|i| (0..3 - i).map(move |k| [i, 0, k]))
        .collect();
    polycube(&cells).unwrap_or_else(|_| unreachable!("the staircase is a manifold polycube"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{classify, cube_mesh, VertexKind};
    use glam::DVec3;

    fn sub(a: [f64; 3], b: [f64; 3]) -> DVec3 {
        DVec3::from_array(a) - DVec3::from_array(b)
    }

    /// Signed volume by the divergence theorem over the quads split into two
    /// triangles; positive exactly when the faces point outward.
    fn volume(mesh: &QuadMesh) -> f64 {
        let p = mesh.vertices();
        let tri = |a: u32, b: u32, c: u32| {
            let [a, b, c] = [a, b, c].map(|i| DVec3::from_array(p[i as usize]));
            a.dot(b.cross(c)) / 6.0
        };
        mesh.faces()
            .iter()
            .map(|f| tri(f[0], f[1], f[2]) + tri(f[0], f[2], f[3]))
            .sum()
    }

    fn check_shape(mesh: &QuadMesh, faces: usize, euler: i64, voxels: f64) {
        assert!(mesh.is_closed());
        assert_eq!(mesh.face_count(), faces);
        assert_eq!(mesh.euler_characteristic(), euler);
        assert!((volume(mesh) - voxels).abs() < 1e-12);
        let c = classify(mesh);
        assert!(c.n_ev() > 0);
        assert_eq!(c.n_bev + c.n_brv + c.n_c, 0);
        for (v, &kind) in c.vertices.iter().enumerate() {
            let n = c.valences[v];
            assert_eq!(kind == VertexKind::InnerExtraordinary, n != 4);
            assert!((3..=6).contains(&n), "valence {n}");
        }
    }

    #[test]
    fn single_voxel_is_the_cube() {
        let mesh = polycube(&[[0, 0, 0]]).unwrap();
        assert_eq!(mesh.vertex_count(), 8);
        assert!(mesh.is_closed());
        assert!((volume(&mesh) - 1.0).abs() < 1e-12);
        assert!((volume(&cube_mesh()) - 1.0).abs() < 1e-12);
        // Every face normal points away from the centre, as the cube's do.
        let p = mesh.vertices();
        for f in mesh.faces() {
            let [a, b, _, d] = f.map(|i| p[i as usize]);
            let n = sub(b, a).cross(sub(d, a));
            let out = sub(a, [0.5; 3]);
            assert!(n.dot(out) > 0.0);
        }
    }

    #[test]
    fn shared_faces_disappear_and_duplicates_count_once() {
        let mesh = polycube(&[[0, 0, 0], [1, 0, 0], [0, 0, 0]]).unwrap();
        assert_eq!(mesh.face_count(), 10);
        assert_eq!(mesh.vertex_count(), 12);
        assert_eq!(mesh.euler_characteristic(), 2);
        assert!((volume(&mesh) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn negative_and_extreme_coordinates() {
        let mesh = polycube(&[[-5, i32::MAX, i32::MIN]]).unwrap();
        assert!(mesh.is_closed());
        assert!(mesh
            .vertices()
            .iter()
            .any(|p| p[1] == i32::MAX as f64 + 1.0));
    }

    #[test]
    fn empty_set_has_no_faces() {
        assert_eq!(polycube(&[]), Err(MeshError::NoFaces));
    }

    #[test]
    fn edge_contact_is_rejected() {
        let err = polycube(&[[0, 0, 0], [1, 1, 0]]).unwrap_err();
        assert!(matches!(err, MeshError::NonManifoldEdge { .. }), "{err:?}");
    }

    #[test]
    fn corner_contact_is_rejected() {
        let err = polycube(&[[0, 0, 0], [1, 1, 1]]).unwrap_err();
        assert!(
            matches!(err, MeshError::NonManifoldVertex { .. }),
            "{err:?}"
        );
    }

    #[test]
    fn named_shapes() {
        let l = l_block();
        check_shape(&l, 18, 2, 4.0);
        assert_eq!((l.vertex_count(), l.edge_count()), (20, 36));
        let ring = ring_block();
        check_shape(&ring, 32, 0, 8.0);
        assert_eq!((ring.vertex_count(), ring.edge_count()), (32, 64));
        let steps = step_block();
        check_shape(&steps, 24, 2, 6.0);
        assert_eq!((steps.vertex_count(), steps.edge_count()), (26, 48));
    }

    #[test]
    fn l_block_has_valence_three_and_five() {
        let c = classify(&l_block());
        assert!(c.valences.contains(&3));
        assert_eq!(c.valences.iter().filter(|&&n| n == 5).count(), 2);
    }
}
