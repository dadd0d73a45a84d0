//! `shroud fit`: read a cloud, fit, print the certificate, write the surrogate.

use crate::args::SurrogateShapeArgs;
use crate::files;
use anyhow::{Context, Result};
use clap::Args;
use shroud_shapes::format;
use shroud_surrogate::{Certificate, FitOptions, Sides, Surrogate, SurrogateFitter};
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct FitArgs {
    /// Point cloud: .ply (ascii or binary), .pcd (ascii, binary or binary_compressed), .xyz, .csv.
    pub input: PathBuf,
    /// upper (points below the surface), lower (points above), or sandwich (both).
    #[arg(long, default_value = "upper")]
    pub side: Sides,
    #[command(flatten)]
    pub shape: SurrogateShapeArgs,
    /// Where to write the surrogate: .json, or anything else for the compact binary.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Also write a triangle mesh of the trimmed surface(s): .obj or .ply.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// Mesh subdivisions per cell triangle.
    #[arg(long, default_value_t = 4)]
    pub mesh_resolution: usize,
    /// Print the summary as one JSON object.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: FitArgs) -> Result<()> {
    let options = options(&args)?;
    let points = files::read_cloud(&args.input)?;
    let start = Instant::now();
    let surrogate = SurrogateFitter::new(options)?
        .fit(&points)
        .context("fit failed")?;
    let elapsed_ms = start.elapsed().as_secs_f64() * 1e3;
    if let Some(path) = &args.output {
        files::write_surrogate(path, &surrogate)?;
    }
    if let Some(path) = &args.mesh {
        write_mesh(path, &surrogate, args.mesh_resolution)?;
    }
    report(&args, &surrogate, elapsed_ms);
    Ok(())
}

fn options(args: &FitArgs) -> Result<FitOptions> {
    args.shape.options(args.side)
}

fn write_mesh(path: &std::path::Path, surrogate: &Surrogate, per_cell: usize) -> Result<()> {
    let mesh = format::tessellate_all(surrogate, per_cell.clamp(1, 64));
    let bytes = match path.extension().and_then(|e| e.to_str()) {
        Some("obj") => mesh.to_obj(),
        Some("ply") => mesh.to_ply(false),
        other => anyhow::bail!(
            "{}: mesh extension {:?} is not .obj or .ply",
            path.display(),
            other.unwrap_or("")
        ),
    };
    files::write(path, &bytes)
}

fn report(args: &FitArgs, s: &Surrogate, elapsed_ms: f64) {
    if args.json {
        let summary = serde_json::json!({
            "points": s.stats.points,
            "grid": [s.domain.cols, s.domain.rows],
            "fit_ms": elapsed_ms,
            "certificates": s.surfaces().map(|x| &x.certificate).collect::<Vec<_>>(),
            "kept_triangles": s.trim.kept_triangles(),
            "stats": &s.stats,
        });
        println!("{summary}");
        return;
    }
    println!(
        "fitted {} surrogate, grid {}x{}, {} points, in {:.2} ms (fit + certification)",
        format!("{:?}", args.side).to_lowercase(),
        s.domain.cols,
        s.domain.rows,
        s.stats.points,
        elapsed_ms
    );
    for surface in s.surfaces() {
        println!("{}", certificate_line(&surface.certificate));
    }
    let total = 4 * s.trim.cells_s * s.trim.cells_t;
    println!(
        "trim: {} of {} cell triangles kept",
        s.trim.kept_triangles(),
        total
    );
}

/// One line a person reads, with every field of the certificate.
pub fn certificate_line(c: &Certificate) -> String {
    let [x, y, z] = c.direction;
    format!(
        "certificate {:?} along ({x:.4},{y:.4},{z:.4}): {} points checked, {} violations, gap min {:.3e} max {:.3e} mean {:.3e}, {} corrected",
        c.side, c.points_checked, c.violations, c.min_gap, c.max_gap, c.mean_gap, c.corrected_points
    )
    .to_lowercase()
}
