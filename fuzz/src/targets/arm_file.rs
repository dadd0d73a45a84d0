//! Arm files (`ArmFile::from_toml_str`): the arm, its trajectory and guard
//! settings, validated; a decoded arm poses.

use crate::check::named;
use shroud_guard::ArmFile;

pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match ArmFile::from_toml_str(text) {
        Ok(file) => crate::arm::poses(&file.arm),
        Err(e) => named(&e),
    }
}

pub fn seeds() -> Vec<Vec<u8>> {
    vec![include_bytes!("../../../launch/arms/demo_arm.toml").to_vec()]
}
