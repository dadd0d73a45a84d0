//! The G1 fitter's domain on the command line (`shroud smooth` and the
//! `smooth` node): a quad mesh, the cube-sphere or a rectangle.

use anyhow::{bail, Context, Result};
use shroud_shapes::mesh::{parse_obj, G1Domain, QuadMesh};
use shroud_shapes::smooth::{cube_sphere, is_planar, Parametrisation};
use std::path::PathBuf;

/// The fitting domain, shared by `shroud smooth` and the `smooth` node.
#[derive(clap::Args, Debug, Clone)]
pub struct SmoothDomainArgs {
    /// The domain: a quad mesh as OBJ (every face a quad, manifold). In the
    /// plane z = 0 the cloud is fitted as a graph z(x, y); in space, as a
    /// parametric surface (each point starts at its foot point on the mesh).
    #[arg(long, required_unless_present = "domain", conflicts_with = "domain")]
    pub mesh: Option<PathBuf>,
    /// Or a built-in domain: `sphere` or `sphere:LEVELS`, the cube-sphere
    /// refined LEVELS times (default 2: the paper's 96 faces), to fit a radial
    /// function r(direction) of points around the origin; or
    /// `plane:X0,Y0,X1,Y1[,N]`, the rectangle split into N x N quads (default
    /// 4), to fit a graph z(x, y).
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
            DomainKind::Planar => Parametrisation::graph(&domain.mesh)
                .with_context(|| format!("{name}: not a planar domain"))?,
            DomainKind::Sphere => Parametrisation::radial(&domain.mesh),
            DomainKind::Space => Parametrisation::parametric(&domain.mesh)
                .with_context(|| format!("{name}: cannot refine the mesh"))?,
        };
        Ok((domain, parametrisation))
    }
}

/// Which kind of domain the points are fitted over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DomainKind {
    /// In the plane z = 0: graphs.
    Planar,
    /// The cube-sphere: radial functions.
    Sphere,
    /// A mesh in space: parametric surfaces.
    Space,
}

fn domain_mesh(args: &SmoothDomainArgs) -> Result<(QuadMesh, DomainKind, String)> {
    if let Some(path) = &args.mesh {
        let bytes =
            std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
        let mesh = parse_obj(&bytes).with_context(|| format!("{}", path.display()))?;
        let kind = if is_planar(&mesh) {
            DomainKind::Planar
        } else {
            DomainKind::Space
        };
        return Ok((mesh, kind, path.display().to_string()));
    }
    let text = args.domain.as_deref().unwrap_or_default();
    let (name, parameters) = text.split_once(':').unwrap_or((text, ""));
    match name {
        "sphere" => {
            let levels = match parameters {
                "" => 2,
                n => n
                    .parse::<usize>()
                    .ok()
                    .filter(|n| *n <= 5)
                    .with_context(|| format!("--domain {text}: LEVELS must be 0 to 5"))?,
            };
            Ok((
                cube_sphere(levels)?,
                DomainKind::Sphere,
                format!("the cube-sphere ({levels} levels)"),
            ))
        }
        "plane" => Ok((
            plane_domain(text, parameters)?,
            DomainKind::Planar,
            format!("the rectangle {parameters}"),
        )),
        _ => bail!("--domain {text:?}: expected sphere[:LEVELS] or plane:X0,Y0,X1,Y1[,N]"),
    }
}

/// `X0,Y0,X1,Y1[,N]`: the rectangle split into N x N quads.
fn plane_domain(text: &str, parameters: &str) -> Result<QuadMesh> {
    let numbers: Vec<f64> = parameters
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .ok()
        .filter(|v: &Vec<f64>| (4..=5).contains(&v.len()) && v.iter().all(|x| x.is_finite()))
        .with_context(|| format!("--domain {text}: expected plane:X0,Y0,X1,Y1[,N] (numbers)"))?;
    let (x0, y0, x1, y1) = (numbers[0], numbers[1], numbers[2], numbers[3]);
    anyhow::ensure!(
        x1 > x0 && y1 > y0,
        "--domain {text}: the rectangle must have X1 > X0 and Y1 > Y0"
    );
    let n = match numbers.get(4) {
        None => 4,
        Some(&n) if n.fract() == 0.0 && (1.0..=256.0).contains(&n) => n as u32,
        Some(_) => bail!("--domain {text}: N must be a whole number from 1 to 256"),
    };
    Ok(shroud_shapes::mesh::rectangle_mesh([x0, y0], [x1, y1], n)?)
}
