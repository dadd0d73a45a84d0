//! Reading an arm file (TOML, schema in `launch/arms/demo_arm.toml`) for the
//! guard and arm nodes.

use anyhow::{Context, Result};
use shroud_guard::ArmFile;
use std::path::Path;

pub fn read_arm_file(path: &Path) -> Result<ArmFile> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read arm file {}", path.display()))?;
    ArmFile::from_toml_str(&text).with_context(|| format!("arm file {}", path.display()))
}

/// Names of the joints a joint state carries: the actuated ones, in chain order.
pub fn joint_names(file: &ArmFile) -> Vec<String> {
    file.arm
        .actuated_joints()
        .map(|j| j.name().to_string())
        .collect()
}
