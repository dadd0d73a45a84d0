//! PLY point clouds (`format::parse_ply`): ascii and both binary encodings.

use crate::check::named;
use crate::round_trip;
use shroud_shapes::format::{parse_ply, write_ply_points};

pub fn run(data: &[u8]) {
    match parse_ply(data) {
        Ok(cloud) => {
            round_trip::cloud(&cloud, |p, i| write_ply_points(p, i, false), parse_ply);
            round_trip::cloud(&cloud, |p, i| write_ply_points(p, i, true), parse_ply);
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let points = [[0.0, 1.5, -2.25], [1e-3, 2e6, 3.0], [-0.0, 4.0, 5.5]];
    let intensity = [0.5, 7.0, 100.0];
    let big_endian = b"ply\nformat binary_big_endian 1.0\nelement vertex 1\n\
        property double x\nproperty double y\nproperty double z\nproperty uchar red\n\
        element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let mut big = big_endian.to_vec();
    for v in [1.0f64, -2.0, 3.5] {
        big.extend_from_slice(&v.to_be_bytes());
    }
    big.push(200);
    big.extend_from_slice(&[3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
    vec![
        write_ply_points(&points, None, false),
        write_ply_points(&points, Some(&intensity), false),
        write_ply_points(&points, Some(&intensity), true),
        big,
    ]
}
