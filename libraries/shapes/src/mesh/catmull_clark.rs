//! One Catmull-Clark refinement step of a quad mesh, with the usual boundary rules
//! (boundary edges at their midpoint, boundary vertices on the cubic B-spline
//! boundary curve, corners fixed).

use super::error::MeshError;
use super::quad_mesh::QuadMesh;

type P = [f64; 3];

fn add(a: P, b: P) -> P {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: P, s: f64) -> P {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Refines `mesh` once. The new vertices are the old vertices (moved), then one
/// point per edge (in edge order), then one point per face; each face `[a, b, c, d]`
/// becomes four faces `[a, e_ab, f, e_da]`, `[b, e_bc, f, e_ab]`, ... keeping the
/// orientation. The result has 4F faces and V + E + F vertices.
///
/// The only error is [`MeshError::TooManyVertices`] when V + E + F exceeds `u32`
/// indices; the refined topology of a valid mesh is always valid.
pub fn catmull_clark(mesh: &QuadMesh) -> Result<QuadMesh, MeshError> {
    let he = mesh.half_edges();
    let verts = mesh.vertices();
    let faces = mesh.faces();
    let (nv, ne, nf) = (verts.len(), he.edge_count(), faces.len());
    let total = nv + ne + nf;
    if total > u32::MAX as usize {
        return Err(MeshError::TooManyVertices { count: total });
    }

    let face_points: Vec<P> = faces
        .iter()
        .map(|f| {
            let s = f
                .iter()
                .fold([0.0; 3], |acc, &v| add(acc, verts[v as usize]));
            scale(s, 0.25)
        })
        .collect();

    let edge_points: Vec<P> = (0..ne)
        .map(|e| {
            let h = he.edge_half_edge(e);
            let [a, b] = he.edge_vertices(e);
            let mid = add(verts[a as usize], verts[b as usize]);
            match he.opposite(h) {
                None => scale(mid, 0.5),
                Some(o) => scale(
                    add(mid, add(face_points[he.face(h)], face_points[he.face(o)])),
                    0.25,
                ),
            }
        })
        .collect();

    let vertex_points: Vec<P> = (0..nv)
        .map(|v| {
            let p = verts[v];
            let out = he.outgoing(v);
            if he.is_boundary_vertex(v) {
                if out.len() == 1 {
                    return p;
                }
                // Both boundary neighbours: target of the first outgoing half-edge
                // and origin of the incoming boundary half-edge.
                let (Some(&first), Some(&last)) = (out.first(), out.last()) else {
                    return p;
                };
                let a = verts[he.target(first) as usize];
                let b = verts[he.origin(he.prev(last)) as usize];
                return scale(add(add(a, b), scale(p, 6.0)), 0.125);
            }
            let n = out.len() as f64;
            let mut f_avg = [0.0; 3];
            let mut r_avg = [0.0; 3];
            for &h in out {
                f_avg = add(f_avg, face_points[he.face(h)]);
                r_avg = add(r_avg, scale(add(p, verts[he.target(h) as usize]), 0.5));
            }
            let f_avg = scale(f_avg, 1.0 / n);
            let r_avg = scale(r_avg, 1.0 / n);
            scale(
                add(add(f_avg, scale(r_avg, 2.0)), scale(p, n - 3.0)),
                1.0 / n,
            )
        })
        .collect();

    let mut vertices = vertex_points;
    vertices.extend(edge_points);
    vertices.extend(face_points);

    let mut new_faces = Vec::with_capacity(4 * nf);
    for (f, face) in faces.iter().enumerate() {
        // Total fits in u32 (checked above), so these casts are exact.
        let fp = (nv + ne + f) as u32;
        let e = |k: usize| (nv + he.edge(4 * f + k)) as u32;
        for (k, &corner) in face.iter().enumerate() {
            new_faces.push([corner, e(k), fp, e((k + 3) % 4)]);
        }
    }
    QuadMesh::new(vertices, new_faces)
}
