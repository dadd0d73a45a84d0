//! `shroud sim`: write a test scene to a cloud file, or a cloud sampled from
//! the Catmull-Clark limit surface of a quad mesh (the clouds of paper 004,
//! Section 6.2) together with that mesh, the domain to fit it over.

use crate::files;
use anyhow::{bail, Context, Result};
use clap::Args;
use shroud_shapes::format::PcdEncoding;
use shroud_shapes::mesh::{
    l_block, levels_within, parse_obj, ring_block, sample_limit_surface, step_block, write_obj,
    QuadMesh,
};
use shroud_sim::Scene;
use std::path::PathBuf;

/// Refinements before sampling a limit surface (see `sample_limit_surface`):
/// six, fewer on meshes so large that the refined mesh would pass a million
/// faces.
const LIMIT_DEPTH: usize = 6;
const MAX_REFINED_FACES: usize = 1 << 20;

#[derive(Debug, Args)]
pub struct SimArgs {
    /// moving-spheres, terrain, table-top, scan-terrain, scan-table-top, or
    /// limit-surface (with --quads).
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
    /// For limit-surface: the quad mesh whose Catmull-Clark limit surface is
    /// sampled, an OBJ file or a built-in polycube: l-block, ring, steps.
    #[arg(long)]
    pub quads: Option<String>,
    /// For limit-surface: also write the quad mesh as OBJ (a domain for
    /// `shroud smooth --mesh`).
    #[arg(long)]
    pub write_quads: Option<PathBuf>,
    /// Output cloud: .ply (binary), .pcd (binary unless --pcd-encoding), .xyz or .csv.
    #[arg(short, long)]
    pub output: PathBuf,
    /// For a .pcd output: ascii, binary or binary_compressed (default binary).
    #[arg(long, value_parser = parse_pcd_encoding)]
    pub pcd_encoding: Option<PcdEncoding>,
}

fn parse_pcd_encoding(text: &str) -> Result<PcdEncoding, String> {
    PcdEncoding::from_name(text)
        .ok_or_else(|| format!("{text:?}: expected ascii, binary or binary_compressed"))
}

/// Points of the limit surface of `--quads`, at uniformly random parameters.
fn limit_surface(args: &SimArgs) -> Result<()> {
    let Some(name) = args.quads.as_deref() else {
        bail!("limit-surface needs --quads FILE.obj or --quads l-block|ring|steps");
    };
    if args.points == 0 {
        bail!("--points must be at least 1");
    }
    let mesh = quads(name)?;
    let depth = levels_within(&mesh, LIMIT_DEPTH, MAX_REFINED_FACES);
    let samples = sample_limit_surface(&mesh, args.points, args.seed, depth)
        .with_context(|| format!("cannot refine {name}"))?;
    let points: Vec<[f32; 3]> = samples.iter().map(|s| s.point.map(|x| x as f32)).collect();
    files::write_cloud(&args.output, &points, args.pcd_encoding)?;
    if let Some(path) = &args.write_quads {
        files::write(path, &write_obj(&mesh))?;
    }
    println!(
        "wrote {} points of the limit surface of {name} ({} quads) to {}",
        points.len(),
        mesh.face_count(),
        args.output.display()
    );
    Ok(())
}

fn quads(name: &str) -> Result<QuadMesh> {
    Ok(match name {
        "l-block" => l_block(),
        "ring" => ring_block(),
        "steps" => step_block(),
        path => {
            let bytes = std::fs::read(path).with_context(|| format!("cannot read {path}"))?;
            parse_obj(&bytes).with_context(|| path.to_owned())?
        }
    })
}

pub fn run(args: SimArgs) -> Result<()> {
    if args.scene == "limit-surface" {
        return limit_surface(&args);
    }
    if args.quads.is_some() || args.write_quads.is_some() {
        bail!("--quads and --write-quads belong to the limit-surface scene");
    }
    let scene = match &args.config {
        Some(path) => files::read_scene_config(path)?,
        None => Scene::by_name(&args.scene, args.points, args.seed)?,
    };
    let points = scene.generate(args.time)?;
    files::write_cloud(&args.output, &points, args.pcd_encoding)?;
    println!(
        "wrote {} points of {} (t = {}) to {}",
        points.len(),
        scene.name(),
        args.time,
        args.output.display()
    );
    Ok(())
}
