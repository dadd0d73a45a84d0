//! `shroud sim`: write a test scene to a cloud file.

use crate::files;
use anyhow::{Context, Result};
use clap::Args;
use shroud_sim::Scene;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SimArgs {
    /// moving-spheres, terrain or table-top.
    pub scene: String,
    /// Number of points.
    #[arg(long, default_value_t = 30_000)]
    pub points: usize,
    /// Time in seconds (moves the spheres; static scenes ignore it).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub time: f64,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// A JSON scene configuration (see `shroud_sim::Scene`), overriding the name's defaults.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Output cloud: .ply (binary), .xyz or .csv.
    #[arg(short, long)]
    pub output: PathBuf,
}

pub fn run(args: SimArgs) -> Result<()> {
    let scene = match &args.config {
        Some(path) => {
            let text =
                std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
            serde_json::from_slice::<Scene>(&text)
                .with_context(|| format!("bad scene configuration {}", path.display()))?
        }
        None => Scene::by_name(&args.scene, args.points, args.seed)?,
    };
    let points = scene.generate(args.time)?;
    files::write_cloud(&args.output, &points)?;
    println!(
        "wrote {} points of {} (t = {}) to {}",
        points.len(),
        scene.name(),
        args.time,
        args.output.display()
    );
    Ok(())
}
