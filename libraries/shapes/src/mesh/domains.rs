//! The domain meshes of paper 004's experiments, built in code: M_T (a
//! triangle split into three quads around a valence-3 EV), M_E (a regular
//! hexagon split into six quads around a valence-6 EV; refined twice it is the
//! paper's 96-patch mesh) and the cube (refined twice, the 96-face sphere mesh
//! before projection).

use super::error::MeshError;
use super::quad_mesh::QuadMesh;

/// M_T: the triangle (0,0), (2,0), (1, sqrt 3) split at its centroid into
/// three quads through the midpoints of its sides.
pub fn triangle_mesh() -> QuadMesh {
    let (a, b, c) = ([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 3f64.sqrt(), 0.0]);
    let mid = |p: [f64; 3], q: [f64; 3]| [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, 0.0];
    let o = [1.0, 3f64.sqrt() / 3.0, 0.0];
    // 0 A, 1 B, 2 C, 3 mAB, 4 mBC, 5 mCA, 6 O
    let vertices = vec![a, b, c, mid(a, b), mid(b, c), mid(c, a), o];
    let faces = vec![[0, 3, 6, 5], [1, 4, 6, 3], [2, 5, 6, 4]];
    QuadMesh::new(vertices, faces).unwrap_or_else(|_| unreachable!("M_T is a valid quad mesh"))
}

/// M_E before refinement: a regular hexagon of circumradius 1 split into six
/// quads (centre, side midpoints, corners).
pub fn hexagon_mesh() -> QuadMesh {
    let corner = |k: usize| {
        let a = std::f64::consts::PI / 3.0 * k as f64;
        [a.cos(), a.sin(), 0.0]
    };
    let mid = |k: usize| {
        let (p, q) = (corner(k), corner((k + 1) % 6));
        [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, 0.0]
    };
    // 0..6 corners, 6..12 midpoints (6 + k between corners k and k+1), 12 centre.
    let mut vertices: Vec<[f64; 3]> = (0..6).map(corner).collect();
    vertices.extend((0..6).map(mid));
    vertices.push([0.0; 3]);
    let faces = (0..6u32).map(|k| [12, 6 + (k + 5) % 6, k, 6 + k]).collect();
    QuadMesh::new(vertices, faces)
        .unwrap_or_else(|_| unreachable!("the hexagon is a valid quad mesh"))
}

/// The rectangle `lo`..`hi` in z = 0 split into `n` x `n` equal quads (a
/// regular grid: no extraordinary vertex, the G1 space is the C1 one).
pub fn rectangle_mesh(lo: [f64; 2], hi: [f64; 2], n: u32) -> Result<QuadMesh, MeshError> {
    let n = n.max(1);
    let count = (n as usize + 1).pow(2);
    if count > u32::MAX as usize {
        return Err(MeshError::TooManyVertices { count });
    }
    let m = n + 1;
    let at = |i: u32, j: u32| {
        let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
        [
            lo[0] + s * (hi[0] - lo[0]),
            lo[1] + t * (hi[1] - lo[1]),
            0.0,
        ]
    };
    let vertices = (0..m * m).map(|k| at(k % m, k / m)).collect();
    let index = |i: u32, j: u32| j * m + i;
    let faces = (0..n * n)
        .map(|k| {
            let (i, j) = (k % n, k / n);
            [
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            ]
        })
        .collect();
    QuadMesh::new(vertices, faces)
}

/// The unit cube as six outward-facing quads.
pub fn cube_mesh() -> QuadMesh {
    let vertices = (0..8)
        .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
        .collect();
    let faces = vec![
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    QuadMesh::new(vertices, faces).unwrap_or_else(|_| unreachable!("the cube is a valid quad mesh"))
}
