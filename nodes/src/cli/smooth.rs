//! `shroud smooth --mesh domain.obj --info`: the quad-mesh domain of the G1
//! smooth fitter (paper 004): its classification (Section 2), the dimension of
//! its G1 space (Corollary 1) and the size of the computed local basis. The
//! least-squares fit over that space is not part of this version, so `--info`
//! is required.

use anyhow::{Context, Result};
use shroud_core::mesh::{parse_obj, G1Basis, G1Domain, MeshError};
use std::path::PathBuf;
use std::time::Instant;

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
    // The computed basis must agree with the formula; say so either way.
    let start = Instant::now();
    let basis = match G1Basis::new(&domain) {
        Ok(basis) => basis,
        Err(MeshError::Unsupported { what }) => {
            println!("basis: not computed ({what} is not supported yet)");
            return Ok(());
        }
        Err(e) => {
            return Err(e)
                .with_context(|| format!("{}: cannot build the G1 basis", args.mesh.display()))
        }
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
