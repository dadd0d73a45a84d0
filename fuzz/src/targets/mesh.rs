//! Triangle meshes (`format::parse_triangle_mesh`): OBJ text, or PLY with a
//! `face` element. A decoded mesh written as OBJ and as PLY reads back the same.

use crate::check::{named, same};
use shroud_core::format::{parse_triangle_mesh, TriangleMesh};

pub fn run(data: &[u8]) {
    match parse_triangle_mesh(data) {
        Ok(mesh) => {
            for bytes in [mesh.to_obj(), mesh.to_ply(true), mesh.to_ply(false)] {
                let again = parse_triangle_mesh(&bytes).expect("a written mesh reads back");
                same(&mesh, &again, "meshes after a round trip");
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
