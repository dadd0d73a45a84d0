//! Reading and writing the files the CLI works with, with errors that name the file.

use anyhow::{bail, Context, Result};
use shroud_shapes::format::{self, CloudFormat, PcdEncoding};
use std::path::Path;

/// Reads a point cloud (PLY ascii/binary, PCD ascii/binary/binary_compressed,
/// XYZ, CSV) and checks it is usable. PCD points marked invalid (NaN
/// coordinates) are left out with a warning that counts them.
pub fn read_cloud(path: &Path) -> Result<Vec<[f32; 3]>> {
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    if bytes.is_empty() {
        bail!("{} is empty", path.display());
    }
    let format = cloud_format(path, &bytes);
    let cloud = format::parse_cloud(&bytes, format)
        .with_context(|| format!("cannot parse {}", path.display()))?;
    if cloud.skipped_invalid > 0 {
        tracing::warn!(
            "{}: left out {} invalid points (NaN coordinates), as PCL's removeNaNFromPointCloud does; {} remain",
            path.display(),
            cloud.skipped_invalid,
            cloud.points.len()
        );
    }
    shroud_geometry::cloud::validate_points(&cloud.points)
        .with_context(|| format!("bad point cloud {}", path.display()))?;
    Ok(cloud.points)
}

fn cloud_format(path: &Path, bytes: &[u8]) -> CloudFormat {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    CloudFormat::from_extension(ext).unwrap_or_else(|| CloudFormat::sniff(bytes))
}

/// Writes a cloud in the format its extension names: `.ply` (binary), `.pcd`
/// (`pcd_encoding`, binary when `None`), `.xyz`/`.txt`/`.asc` or `.csv`/`.tsv`
/// (space-separated text). A `pcd_encoding` for any other extension is an error.
pub fn write_cloud(
    path: &Path,
    points: &[[f32; 3]],
    pcd_encoding: Option<PcdEncoding>,
) -> Result<()> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let format = CloudFormat::from_extension(ext);
    if pcd_encoding.is_some() && format != Some(CloudFormat::Pcd) {
        bail!(
            "{}: a PCD encoding was given, but the output is not a .pcd file",
            path.display()
        );
    }
    let bytes = match format {
        Some(CloudFormat::Ply) => format::write_ply_points(points, None, false),
        Some(CloudFormat::Pcd) => format::write_pcd(points, None, pcd_encoding.unwrap_or_default())
            .with_context(|| format!("cannot write {}", path.display()))?,
        Some(CloudFormat::Xyz) | Some(CloudFormat::Csv) => format::write_xyz(points),
        None => bail!(
            "{}: unknown cloud extension '{ext}' (use .ply, .pcd, .xyz or .csv)",
            path.display()
        ),
    };
    write(path, &bytes)
}

pub fn write(path: &Path, bytes: &[u8]) -> Result<()> {
    std::fs::write(path, bytes).with_context(|| format!("cannot write {}", path.display()))
}

/// Reads a surrogate written by `shroud fit` (`.json` or the binary `.shrd`).
pub fn read_surrogate(path: &Path) -> Result<shroud_surrogate::Surrogate> {
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    let parsed = if is_json(path, &bytes) {
        format::surrogate_from_json(&bytes)
    } else {
        format::surrogate_from_binary(&bytes)
    };
    parsed.with_context(|| format!("cannot load surrogate {}", path.display()))
}

/// Writes a surrogate as JSON (`.json`) or compact binary (anything else).
pub fn write_surrogate(path: &Path, surrogate: &shroud_surrogate::Surrogate) -> Result<()> {
    let bytes = if path.extension().is_some_and(|e| e == "json") {
        format::surrogate_to_json(surrogate)
    } else {
        format::surrogate_to_binary(surrogate)
    };
    write(path, &bytes)
}

fn is_json(path: &Path, bytes: &[u8]) -> bool {
    path.extension().is_some_and(|e| e == "json")
        || bytes.iter().find(|b| !b.is_ascii_whitespace()) == Some(&b'{')
}

/// A scene configuration file (JSON, `shroud_sim::Scene` with its `"kind"`
/// tag; missing fields take their defaults).
pub fn read_scene_config(path: &Path) -> Result<shroud_sim::Scene> {
    let text = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    serde_json::from_slice::<shroud_sim::Scene>(&text)
        .with_context(|| format!("bad scene configuration {}", path.display()))
}
