//! PCL point cloud data (`format::parse_pcd`): ascii, binary and
//! binary_compressed (LZF) bodies, organised clouds with NaN markers.

use crate::check::named;
use crate::round_trip;
use shroud_shapes::format::{parse_pcd, write_pcd, PcdEncoding};

pub fn run(data: &[u8]) {
    match parse_pcd(data) {
        Ok(cloud) => {
            for encoding in [
                PcdEncoding::Ascii,
                PcdEncoding::Binary,
                PcdEncoding::BinaryCompressed,
            ] {
                let write = |p: &[[f32; 3]], i: Option<&[f32]>| {
                    write_pcd(p, i, encoding).expect("a decoded cloud fits in a PCD file")
                };
                round_trip::cloud(&cloud, write, parse_pcd);
            }
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    let points = [[0.0, 1.5, -2.25], [1e-3, 2e6, 3.0], [-0.0, 4.0, 5.5]];
    let intensity = [0.5, 7.0, 100.0];
    let mut seeds: Vec<Vec<u8>> = [
        PcdEncoding::Ascii,
        PcdEncoding::Binary,
        PcdEncoding::BinaryCompressed,
    ]
    .into_iter()
    .map(|e| write_pcd(&points, Some(&intensity), e).expect("three points fit"))
    .collect();
    seeds.extend(FIXTURES.iter().map(|f| f.to_vec()));
    seeds
}

/// The PCD files of shroud-shapes' tests (written by PCL and by make_fixtures.py).
const FIXTURES: [&[u8]; 8] = [
    include_bytes!("../../../libraries/shapes/tests/data/pcd/intensity_first_binary.pcd"),
    include_bytes!("../../../libraries/shapes/tests/data/pcd/organised_nan_ascii.pcd"),
    include_bytes!("../../../libraries/shapes/tests/data/pcd/organised_nan_binary.pcd"),
    include_bytes!("../../../libraries/shapes/tests/data/pcd/pcl113_fpfh_binary_compressed.pcd"),
    include_bytes!("../../../libraries/shapes/tests/data/pcd/pcl113_organised_nan_binary.pcd"),
    include_bytes!("../../../libraries/shapes/tests/data/pcd/xyz_rgb_fpfh_intensity_compressed.pcd"),
    include_bytes!("../../../libraries/shapes/tests/data/pcd/xyz_rgb_intensity_ascii.pcd"),
    include_bytes!("../../../libraries/shapes/tests/data/pcd/xyzi_padded_binary.pcd"),
];
