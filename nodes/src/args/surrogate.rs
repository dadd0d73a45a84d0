//! How a surrogate is shaped on the command line: grid, direction, tightness,
//! trimming (`shroud fit` and the `fit` node).

use crate::parse;
use anyhow::Result;
use clap::Args;
use shroud_surrogate::{FitOptions, Sides, Tightness};

/// How a surrogate is shaped: grid, direction, tightness, trimming. Shared by
/// `shroud fit` and the `fit` node.
#[derive(Debug, Clone, Args)]
pub struct SurrogateShapeArgs {
    /// Control points along u and v, e.g. 20x20 or 30x12.
    #[arg(long, default_value = "20x20")]
    pub grid: String,
    /// Viewing direction x,y,z; heights grow against it (the default looks down).
    #[arg(long, default_value = "0,0,-1", allow_hyphen_values = true)]
    pub dir: String,
    /// Reach the optimum of the linear program (tightest safe surface).
    #[arg(long)]
    pub tight: bool,
    /// The paper's heuristic alone, without the lowering pass.
    #[arg(long, conflicts_with = "tight")]
    pub plain: bool,
    /// Average the u-first and v-first reductions.
    #[arg(long)]
    pub symmetrize: bool,
    /// Keep the whole rectangle instead of trimming cells without data.
    #[arg(long)]
    pub no_trim: bool,
    /// Sub-cells per cell and direction in the one-pass reduction.
    #[arg(long, default_value_t = 4)]
    pub sub_cells: usize,
}

impl SurrogateShapeArgs {
    pub fn options(&self, sides: Sides) -> Result<FitOptions> {
        let (cols, rows) = parse::grid(&self.grid)?;
        let direction = parse::numbers::<3>(&self.dir, "direction")?;
        Ok(FitOptions {
            cols,
            rows,
            direction,
            sides,
            symmetrize: self.symmetrize,
            trim: !self.no_trim,
            tightness: match (self.tight, self.plain) {
                (true, _) => Tightness::Optimal,
                (_, true) => Tightness::Plain,
                _ => Tightness::Lowered,
            },
            sub_cells: self.sub_cells.clamp(1, 64),
            ..FitOptions::default()
        })
    }
}
