//! The blend's tunables on the command line (`shroud blend` and the `blend`
//! node), and point lists such as a polygon of interest.

use crate::parse;
use anyhow::Result;
use glam::DVec3;
use shroud_shapes::blend::BlendParams;

/// The blend's tunables, shared by `shroud blend` and the `blend` node.
#[derive(clap::Args, Debug, Clone)]
pub struct BlendShapeArgs {
    /// RBF centre budget.
    #[arg(long, default_value_t = 1200)]
    pub centres: usize,
    /// Marching-tetrahedra cell, in point spacings.
    #[arg(long, default_value_t = 1.5)]
    pub cell: f64,
    /// Gap, ring and front sizes as fractions of the polygon's radius: g,r,f.
    #[arg(long, default_value = "0.35,0.3,0.3")]
    pub regions: String,
}

impl BlendShapeArgs {
    pub fn params(&self) -> Result<BlendParams> {
        let [gap, ring, front] = parse::numbers::<3>(&self.regions, "regions")?;
        let mut params = BlendParams::default();
        params.regions.gap = gap;
        params.regions.ring = ring;
        params.regions.front = front;
        params.rbf.max_centres = self.centres;
        params.cell = self.cell;
        Ok(params)
    }
}

/// `"x,y,z;x,y,z;..."`.
pub fn points3(text: &str, what: &str) -> Result<Vec<DVec3>> {
    text.split(';')
        .filter(|s| !s.trim().is_empty())
        .map(|s| parse::numbers::<3>(s, what).map(DVec3::from))
        .collect()
}
