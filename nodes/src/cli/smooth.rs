//! `shroud smooth --mesh domain.obj --info`: the quad-mesh domain of the G1
//! smooth fitter (paper 004): its classification (Section 2) and the dimension
//! of its G1 space (Corollary 1). The least-squares fit over that space is not
//! part of this version, so `--info` is required.

use anyhow::{Context, Result};
use shroud_core::mesh::{parse_obj, G1Domain};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct SmoothArgs {
    /// The domain: a quad mesh as OBJ (every face a quad, manifold).
    #[arg(long)]
    pub mesh: PathBuf,
    /// Print the mesh's classification and the dimension of its G1 space.
    #[arg(long, required = true)]
    pub info: bool,
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
    Ok(())
}
