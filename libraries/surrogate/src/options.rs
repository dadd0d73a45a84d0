//! What a fit is asked for: the grid, the viewing direction, the sides, and
//! how hard to tighten. Apart from the fitter, so that the tightening code
//! (`tight`), which takes the default sub-cells, needs no fitter.

use super::model::Sides;
use super::scattered_curve::DEFAULT_MAX_SOLVES;
use serde::{Deserialize, Serialize};

/// How hard to push the surface onto the cloud.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Tightness {
    /// The paper's heuristic alone.
    Plain,
    /// The heuristic followed by the coordinate-descent lowering pass (default).
    Lowered,
    /// The optimum of the linear program over the candidates (`--tight`).
    Optimal,
}

/// Everything a fit needs besides the points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitOptions {
    /// Control points along `u` (s) and `v` (t).
    pub cols: usize,
    pub rows: usize,
    /// The viewing direction; need not be unit length.
    pub direction: [f64; 3],
    pub sides: Sides,
    /// Average the u-first and v-first reductions (still safe).
    pub symmetrize: bool,
    /// Trim cells (triangles) without data.
    pub trim: bool,
    pub tightness: Tightness,
    /// Sub-cells per cell along each parameter in the streaming pass (at most
    /// `MAX_SUB_CELLS / 2` = 16; larger values are clamped).
    pub sub_cells: usize,
    /// Solve budget of Heuristic(σ, b, λ) per line.
    pub max_solves: usize,
    /// Coordinate-descent sweeps of the lowering pass.
    pub sweeps: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            cols: 20,
            rows: 20,
            direction: [0.0, 0.0, -1.0],
            sides: Sides::Upper,
            symmetrize: false,
            trim: true,
            tightness: Tightness::Lowered,
            sub_cells: 4,
            max_solves: DEFAULT_MAX_SOLVES,
            sweeps: 3,
        }
    }
}
