//! XYZ, CSV and TSV text clouds (`format::parse_xyz`).

use crate::check::{named, same};
use shroud_shapes::format::{parse_xyz, write_xyz};

pub fn run(data: &[u8]) {
    match parse_xyz(data) {
        Ok(points) => {
            let again = parse_xyz(&write_xyz(&points)).expect("written text reads back");
            same(&points, &again, "points after a round trip");
        }
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![
        write_xyz(&[[0.0, 1.5, -2.25], [1e-3, 2e6, 3.0]]),
        b"x,y,z,intensity\n1,2,3,4\n# comment\n-1.5e3,2,3\n".to_vec(),
        b"\xEF\xBB\xBFx;y;z\n1,5;2,25;3\n// c\n4;5;6\n".to_vec(),
        b"1\t2\t3\n4\t5\t6\n".to_vec(),
    ]
}
