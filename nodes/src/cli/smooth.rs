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
use shroud_core::mesh::{parse_obj, write_obj, G1Basis, G1Domain, MeshError, QuadMesh};
use shroud_core::smooth::{cube_sphere, Parametrisation, SmoothFitter};
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct SmoothArgs {
    /// The cloud to fit (.ply, .xyz, .csv): a graph z(x, y) over the domain.
    pub input: Option<PathBuf>,
    #[command(flatten)]
    pub domain: SmoothDomainArgs,
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

/// The fitting domain, shared by `shroud smooth` and the `smooth` node.
#[derive(clap::Args, Debug, Clone)]
pub struct SmoothDomainArgs {
    /// The domain: a quad mesh as OBJ (every face a quad, manifold; in z = 0
    /// to fit a graph z(x, y)).
    #[arg(long, required_unless_present = "domain", conflicts_with = "domain")]
    pub mesh: Option<PathBuf>,
    /// Or a built-in domain: `sphere` or `sphere:LEVELS`, the cube-sphere
    /// refined LEVELS times (default 2: the paper's 96 faces), to fit a radial
    /// function r(direction) of points around the origin.
    #[arg(long)]
    pub domain: Option<String>,
}

impl SmoothDomainArgs {
    /// The domain (refined once if its EVs touch, and said so) and the name to
    /// use in messages.
    pub fn domain(&self) -> Result<(G1Domain, DomainKind, String)> {
        let (mesh, kind, name) = domain_mesh(self)?;
        let domain =
            G1Domain::new(mesh).with_context(|| format!("{name}: cannot refine the mesh"))?;
        if domain.refined {
            println!(
                "note: {name} has adjacent extraordinary vertices; refined once (Catmull-Clark) so that they are isolated"
            );
        }
        Ok((domain, kind, name))
    }

    /// The domain and how points become samples over it.
    pub fn load(&self) -> Result<(G1Domain, Parametrisation)> {
        let (domain, kind, name) = self.domain()?;
        let parametrisation = match kind {
            DomainKind::Planar => Parametrisation::graph(&domain.mesh).with_context(|| {
                format!("{name}: a fitting domain from a file must be planar (z = 0)")
            })?,
            DomainKind::Sphere => Parametrisation::radial(&domain.mesh),
        };
        Ok((domain, parametrisation))
    }
}

/// Which kind of domain the points are fitted over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DomainKind {
    Planar,
    Sphere,
}

pub fn run(args: &SmoothArgs) -> Result<()> {
    if args.input.is_none() && !args.info {
        bail!("give an input cloud to fit, or --info");
    }
    if args.info {
        info(&args.domain.domain()?.0)?;
    }
    match &args.input {
        Some(input) => fit(args, input),
        None => Ok(()),
    }
}

fn domain_mesh(args: &SmoothDomainArgs) -> Result<(QuadMesh, DomainKind, String)> {
    if let Some(path) = &args.mesh {
        let bytes =
            std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
        let mesh = parse_obj(&bytes).with_context(|| format!("{}", path.display()))?;
        return Ok((mesh, DomainKind::Planar, path.display().to_string()));
    }
    let text = args.domain.as_deref().unwrap_or_default();
    let levels = match text.split_once(':') {
        None if text == "sphere" => 2,
        Some(("sphere", n)) => n
            .parse::<usize>()
            .ok()
            .filter(|n| *n <= 5)
            .with_context(|| format!("--domain {text}: LEVELS must be 0 to 5"))?,
        _ => bail!("--domain {text:?}: expected sphere or sphere:LEVELS"),
    };
    Ok((
        cube_sphere(levels)?,
        DomainKind::Sphere,
        format!("the cube-sphere ({levels} levels)"),
    ))
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

fn fit(args: &SmoothArgs, input: &std::path::Path) -> Result<()> {
    let start = Instant::now();
    let (domain, parametrisation) = args.domain.load()?;
    let points = files::read_cloud(input)?;
    let xyz: Vec<[f64; 3]> = points.iter().map(|p| p.map(f64::from)).collect();
    let (samples, values) = parametrisation
        .sample_all(&xyz)
        .with_context(|| format!("{} over the domain", input.display()))?;
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
        Some("obj") => write_obj(&match parametrisation {
            Parametrisation::Graph(_) => surface.tessellate_graph(&mesh, args.tessellation)?,
            Parametrisation::Radial(_) => surface.tessellate_radial(&mesh, args.tessellation)?,
        }),
        Some("json") => serde_json::to_vec(&serde_json::json!({
            "format": "shroud-g1-patches",
            "version": 1,
            "degree": 5,
            "dim": surface.dim,
            "kind": parametrisation.kind(),
            "domain": { "vertices": mesh.vertices(), "faces": mesh.faces() },
            "patches": surface.coefficients.chunks(36 * surface.dim).collect::<Vec<_>>(),
            "errors": { "min": e.min, "max": e.max, "rmse": e.rmse },
        }))?,
        _ => bail!("{}: the output must be .json or .obj", output.display()),
    };
    files::write(output, &bytes)?;
    Ok(())
}
