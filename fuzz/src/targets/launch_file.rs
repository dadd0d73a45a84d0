//! Launch files (`LaunchFile::from_toml_str`): TOML, then validated. A
//! decoded file validates again.

use crate::check::named;
use shroud_graph::launch::LaunchFile;

pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match LaunchFile::from_toml_str(text) {
        Ok(file) => file.validate().expect("a decoded launch file is valid"),
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    [
        include_str!("../../../launch/blend.toml"),
        include_str!("../../../launch/demo.toml"),
        include_str!("../../../launch/hosts.toml"),
        include_str!("../../../launch/lidar.toml"),
        include_str!("../../../launch/multiview.toml"),
        include_str!("../../../launch/radar.toml"),
        include_str!("../../../launch/replay.toml"),
        include_str!("../../../launch/scan.toml"),
    ]
    .iter()
    .map(|t| t.as_bytes().to_vec())
    .collect()
}
