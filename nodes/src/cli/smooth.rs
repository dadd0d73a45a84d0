//! `shroud smooth`: the G1 smooth fitter (paper 004). With `--info`, the
//! quad-mesh domain's classification (Section 2), the dimension of its G1
//! space (Corollary 1) and the size of the computed local basis. With an
//! input cloud, the least-squares fit (eq. 26): a graph z(x, y) over a planar
//! domain, a radial function over the cube-sphere, or a parametric surface in
//! R^3 over a quad mesh in space, improved by parameter correction. The error
//! measures (28) and timing are printed, and the surface written as patches
//! (JSON) or a tessellated mesh (OBJ, PLY).

use crate::args::SmoothDomainArgs;
use crate::files;
use anyhow::{bail, Context, Result};
use shroud_shapes::format::TriangleMesh;
use shroud_shapes::mesh::{write_obj, G1Basis, G1Domain, QuadMesh};
use shroud_shapes::smooth::{FitErrors, Parametrisation, SmoothFitter, SmoothSurface};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct SmoothArgs {
    /// The cloud to fit (.ply, .pcd, .xyz, .csv): a graph z(x, y) over a planar
    /// domain, a radial function over the sphere, or a surface in R^3 over a
    /// quad mesh in space.
    pub input: Option<PathBuf>,
    #[command(flatten)]
    pub domain: SmoothDomainArgs,
    /// Print the mesh's classification and the dimension of its G1 space.
    #[arg(long)]
    pub info: bool,
    /// Thin-plate smoothing weight lambda of eq. (26).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub lambda: f64,
    /// Rounds of parameter correction (foot points on the fitted surface,
    /// then a refit) for a parametric fit; default 3 there. Graphs and radial
    /// functions have exact parameters and take none.
    #[arg(long)]
    pub corrections: Option<usize>,
    /// Output: .json (patch coefficients, see docs/formats.md), or .obj / .ply
    /// (the surface tessellated). Repeat for several: `-o fit.json -o fit.ply`.
    #[arg(short, long)]
    pub output: Vec<PathBuf>,
    /// Grid per patch of the tessellated output (1 to 256).
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u16).range(1..=256))]
    pub tessellation: u16,
}

pub fn run(args: &SmoothArgs) -> Result<()> {
    match &args.input {
        Some(input) => fit(args, input),
        None if args.info => info(&args.domain.domain()?.0),
        None => bail!("give an input cloud to fit, or --info"),
    }
}

fn info(domain: &G1Domain) -> Result<()> {
    let c = &domain.classification;
    let d = domain.dimension();
    println!(
        "faces: {}\nedges: {} (regular {}, extraordinary {}, boundary {})",
        c.n_f, c.n_e, c.n_re, c.n_ee, c.n_be
    );
    println!(
        "vertices: {} (inner regular {}, inner extraordinary {}, boundary regular {}, boundary extraordinary {}, corners {})",
        c.n_v, c.n_rv, c.n_iev, c.n_brv, c.n_bev, c.n_c
    );
    println!(
        "basis functions: {} on vertices, {} on edges, {} on faces",
        d.vertex, d.edge, d.face
    );
    println!("dimension: {}", d.total());
    let start = Instant::now();
    let basis = G1Basis::new(domain).context("cannot build the G1 basis")?;
    let matches = basis.len() == d.total();
    println!(
        "basis: {} functions computed in {:.1} ms ({})",
        basis.len(),
        start.elapsed().as_secs_f64() * 1e3,
        if matches {
            "matches the dimension"
        } else {
            "DOES NOT match the dimension"
        }
    );
    anyhow::ensure!(
        matches,
        "the computed basis has {} functions, Corollary 1 says {}",
        basis.len(),
        d.total()
    );
    Ok(())
}

fn fit(args: &SmoothArgs, input: &std::path::Path) -> Result<()> {
    let start = Instant::now();
    anyhow::ensure!(
        args.lambda.is_finite() && args.lambda >= 0.0,
        "--lambda {} must be finite and >= 0",
        args.lambda
    );
    let (domain, parametrisation) = args.domain.load()?;
    if args.info {
        info(&domain)?;
    }
    let corrections = parametrisation.corrections(args.corrections)?;
    // A wrong extension is found before a long fit, not after.
    for output in &args.output {
        output_kind(output)?;
    }
    let points = files::read_cloud(input)?;
    let xyz: Vec<[f64; 3]> = points.iter().map(|p| p.map(f64::from)).collect();
    let (samples, values) = parametrisation
        .sample_all(&xyz)
        .with_context(|| format!("{} over the domain", input.display()))?;
    let located = start.elapsed().as_secs_f64();
    let mesh = domain.mesh.clone();
    let fitter = SmoothFitter::new(domain).context("cannot build the G1 basis")?;
    let fit = fitter
        .fit_as(
            &parametrisation,
            &samples,
            &values,
            (args.lambda, corrections),
            None,
        )
        .with_context(|| format!("cannot fit {}", input.display()))?;
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "fitted {} points ({}) with {} G1 functions on {} patches (lambda {}) in {seconds:.3} s (locating {located:.3} s)",
        points.len(),
        parametrisation.kind(),
        fitter.basis.len(),
        mesh.face_count(),
        args.lambda
    );
    for (round, e) in fit.rounds.iter().enumerate().take(fit.rounds.len() - 1) {
        println!(
            "after {round} corrections: min {:.3e}  L-inf {:.3e}  RMSE {:.3e}",
            e.min, e.max, e.rmse
        );
    }
    let e = fit.errors();
    println!(
        "errors: min {:.3e}  L-inf {:.3e}  RMSE {:.3e}",
        e.min, e.max, e.rmse
    );
    if let Some(d) = fit.distances {
        println!(
            "distance to the surface (foot points): min {:.3e}  L-inf {:.3e}  RMSE {:.3e}",
            d.min, d.max, d.rmse
        );
    }
    for output in &args.output {
        write_output(args, output, &mesh, &parametrisation, &fit.surface, e)?;
    }
    Ok(())
}

/// What an output path asks for, by its extension.
#[derive(Debug, Clone, Copy, PartialEq)]
enum OutputKind {
    Patches,
    Obj,
    Ply,
}

fn output_kind(output: &std::path::Path) -> Result<OutputKind> {
    let ext = output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("json") => Ok(OutputKind::Patches),
        Some("obj") => Ok(OutputKind::Obj),
        Some("ply") => Ok(OutputKind::Ply),
        _ => bail!(
            "{}: the output must be .json, .obj or .ply",
            output.display()
        ),
    }
}

fn write_output(
    args: &SmoothArgs,
    output: &std::path::Path,
    mesh: &QuadMesh,
    parametrisation: &Parametrisation,
    surface: &SmoothSurface,
    e: FitErrors,
) -> Result<()> {
    let tessellated = || parametrisation.tessellate(surface, mesh, args.tessellation.into());
    let bytes = match output_kind(output)? {
        OutputKind::Obj => write_obj(&tessellated()?),
        OutputKind::Ply => {
            let (vertices, quads) = tessellated()?.into_parts();
            TriangleMesh::from_quads(vertices, &quads).to_ply(false)
        }
        OutputKind::Patches => serde_json::to_vec(&serde_json::json!({
            "format": "shroud-g1-patches",
            "version": 1,
            "degree": 5,
            "dim": surface.dim,
            "kind": parametrisation.kind(),
            "domain": { "vertices": mesh.vertices(), "faces": mesh.faces() },
            "patches": surface.coefficients.chunks(36 * surface.dim).collect::<Vec<_>>(),
            "errors": { "min": e.min, "max": e.max, "rmse": e.rmse },
        }))?,
    };
    files::write(output, &bytes)
}
