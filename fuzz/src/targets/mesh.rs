//! Triangle meshes (`format::parse_triangle_mesh`): OBJ text, or PLY with a
//! `face` element. A decoded mesh written as OBJ reads back the same, and as
//! PLY the same with its vertices narrowed to f32 (as `to_ply` documents).

use crate::check::{named, same};
use shroud_shapes::format::{parse_triangle_mesh, TriangleMesh};

pub fn run(data: &[u8]) {
    match parse_triangle_mesh(data) {
        Ok(mesh) => {
            let narrowed = TriangleMesh {
                vertices: mesh
                    .vertices
                    .iter()
                    .map(|v| v.map(|c| f64::from(c as f32)))
                    .collect(),
                triangles: mesh.triangles.clone(),
            };
            // A coordinate beyond f32's range becomes infinite in PLY, which
            // every reader refuses: only the OBJ round trip applies then.
            let fits_f32 = narrowed.vertices.iter().flatten().all(|c| c.is_finite());
            let mut trips = vec![(mesh.to_obj(), &mesh)];
            if fits_f32 {
                trips.push((mesh.to_ply(true), &narrowed));
                trips.push((mesh.to_ply(false), &narrowed));
            }
            for (bytes, expected) in trips {
                let again = parse_triangle_mesh(&bytes).expect("a written mesh reads back");
                same(expected, &again, "meshes after a round trip");
            }
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let quad = TriangleMesh::from_quads(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.5],
            [0.0, 1.0, -0.25],
        ],
        &[[0, 1, 2, 3]],
    );
    vec![
        quad.to_obj(),
        quad.to_ply(true),
        quad.to_ply(false),
        b"v 0 0 0\nv 1 0 0 1\nv 1 1 0 0.5 0.5 0.5\nvt 0 0\nvn 0 0 1\ng part\n\
          f 1/1/1 2//1 3/1 -1\nf -3 -2 -1\n"
            .to_vec(),
    ]
}
