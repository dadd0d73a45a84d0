//! OBJ quad meshes (`mesh::parse_obj`), the domains of smooth surfaces.

use crate::check::{named, same};
use shroud_shapes::mesh::{cube_mesh, parse_obj, rectangle_mesh, write_obj};

pub fn run(data: &[u8]) {
    match parse_obj(data) {
        Ok(mesh) => {
            let again = parse_obj(&write_obj(&mesh)).expect("a written quad mesh reads back");
            same(
                &mesh.vertices(),
                &again.vertices(),
                "vertices after a round trip",
            );
            same(&mesh.faces(), &again.faces(), "faces after a round trip");
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![
        write_obj(&cube_mesh()),
        write_obj(&rectangle_mesh([0.0, 0.0], [2.0, 1.0], 2).expect("a valid rectangle")),
        b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 # corner\nf 1/1 2/2/2 3//3 -1\n".to_vec(),
    ]
}
