//! `shroud smooth`: the G1 smooth fitter (paper 004). With `--info`, the
//! quad-mesh domain's classification (Section 2), the dimension of its G1
//! space (Corollary 1) and the size of the computed local basis. With an
//! input cloud, the least-squares fit (eq. 26) of the cloud as a graph over a
//! planar quad-mesh domain: each point (x, y, z) is located in the domain by
//! inverse bilinear maps and z is fitted; the error measures (28) and timing
//! are printed, and the surface written as patches (JSON) or a tessellated
//! mesh (OBJ).

use crate::files;
use anyhow::{bail, Context, Result};
use shroud_core::mesh::{parse_obj, write_obj, G1Basis, G1Domain, MeshError};
use shroud_core::smooth::{PlanarLocator, SmoothFitter};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct SmoothArgs {
    /// The cloud to fit (.ply, .xyz, .csv): a graph z(x, y) over the domain.
    pub input: Option<PathBuf>,
    /// The domain: a quad mesh as OBJ (every face a quad, manifold; in z = 0 to fit).
    #[arg(long)]
    pub mesh: PathBuf,
    /// Print the mesh's classification and the dimension of its G1 space.
    #[arg(long)]
    pub info: bool,
    /// Thin-plate smoothing weight lambda of eq. (26).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub lambda: f64,
    /// Output: .json (patch coefficients, see core/FORMATS.md) or .obj (tessellated).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Grid per patch of the tessellated output.
    #[arg(long, default_value_t = 16)]
    pub tessellation: usize,
}

pub fn run(args: &SmoothArgs) -> Result<()> {
    let bytes = std::fs::read(&args.mesh)
        .with_context(|| format!("cannot read {}", args.mesh.display()))?;
    let mesh = parse_obj(&bytes).with_context(|| format!("{}", args.mesh.display()))?;
    let domain = G1Domain::new(mesh)
        .with_context(|| format!("{}: cannot refine the mesh", args.mesh.display()))?;
    if domain.refined {
        println!(
            "note: {} has adjacent extraordinary vertices; refined once (Catmull-Clark) so that they are isolated",
            args.mesh.display()
        );
    }
    if args.info {
        info(&domain)?;
    }
    match &args.input {
        Some(input) => fit(args, input, domain),
        None if args.info => Ok(()),
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
    let basis = match G1Basis::new(domain) {
        Ok(basis) => basis,
        Err(MeshError::Unsupported { what }) => {
            println!("basis: not computed ({what} is not supported yet)");
            return Ok(());
        }
        Err(e) => return Err(e).context("cannot build the G1 basis"),
    };
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

fn fit(args: &SmoothArgs, input: &std::path::Path, domain: G1Domain) -> Result<()> {
    let start = Instant::now();
    let points = files::read_cloud(input)?;
    let locator = PlanarLocator::new(&domain.mesh)
        .with_context(|| format!("{}: the fitting domain must be planar", args.mesh.display()))?;
    let xy: Vec<[f64; 2]> = points.iter().map(|p| [p[0] as f64, p[1] as f64]).collect();
    let samples = locator
        .locate_all(&xy)
        .with_context(|| format!("{} over {}", input.display(), args.mesh.display()))?;
    let values: Vec<f64> = points.iter().map(|p| p[2] as f64).collect();
    let mesh = domain.mesh.clone();
    let fitter = SmoothFitter::new(domain).context("cannot build the G1 basis")?;
    let surface = fitter
        .fit(&samples, &values, 1, args.lambda)
        .with_context(|| format!("cannot fit {}", input.display()))?;
    let seconds = start.elapsed().as_secs_f64();
    let e = surface.errors(&samples, &values);
    println!(
        "fitted {} points with {} G1 functions on {} patches (lambda {}) in {seconds:.3} s",
        points.len(),
        fitter.basis.len(),
        mesh.face_count(),
        args.lambda
    );
    println!(
        "errors: min {:.3e}  L-inf {:.3e}  RMSE {:.3e}",
        e.min, e.max, e.rmse
    );
    let Some(output) = &args.output else {
        return Ok(());
    };
    let ext = output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let bytes = match ext.as_deref() {
        Some("obj") => write_obj(&surface.tessellate_graph(&mesh, args.tessellation)?),
        Some("json") => serde_json::to_vec(&serde_json::json!({
            "format": "shroud-g1-patches",
            "version": 1,
            "degree": 5,
            "dim": surface.dim,
            "domain": { "vertices": mesh.vertices(), "faces": mesh.faces() },
            "patches": surface.coefficients.chunks(36 * surface.dim).collect::<Vec<_>>(),
            "errors": { "min": e.min, "max": e.max, "rmse": e.rmse },
        }))?,
        _ => bail!("{}: the output must be .json or .obj", output.display()),
    };
    files::write(output, &bytes)?;
    Ok(())
}
