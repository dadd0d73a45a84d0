//! The one streaming pass over the cloud: every point lands in a sub-cell of its
//! grid cell, and each sub-cell keeps only its extreme point (per side) plus the
//! trim bits. Everything after this pass works on a few thousand candidates.

pub(crate) mod located;
mod maxima;

pub use maxima::SubCellMaxima;

use super::model::{Domain, Side};
use super::trim::{triangle_of, TrimMask};
use crate::DomainLocate;
use located::{small_integer, LocatedBlock, BLOCK};
use rayon::prelude::*;
use shroud_geometry::math::Frame;

/// The output of the streaming pass.
#[derive(Debug, Clone)]
pub struct Binning {
    pub maxima: Vec<SubCellMaxima>,
    pub trim: TrimMask,
}

impl Binning {
    fn empty(sides: &[Side], cells_s: usize, cells_t: usize, sub: usize) -> Self {
        Self {
            maxima: sides
                .iter()
                .map(|&side| SubCellMaxima::new(side, cells_s, cells_t, sub, sub))
                .collect(),
            trim: TrimMask::empty(cells_s, cells_t),
        }
    }

    /// Maxima and trim bits are unions, so merging in any order gives one result.
    fn merge(mut self, other: Binning) -> Binning {
        self.trim.merge(&other.trim);
        self.maxima
            .iter_mut()
            .zip(&other.maxima)
            .for_each(|(a, b)| a.merge(b));
        self
    }
}

/// Sub-cells per cell along each parameter at most: more would only cost memory
/// (the candidates already are nearly every point), and slot numbers must stay
/// below `2^31` on the largest grid.
pub const MAX_SUB_CELLS: usize = 32;

/// Bins every point once (in parallel). `sub` is the number of sub-cells per cell
/// along each parameter (clamped to `1..=MAX_SUB_CELLS`).
pub fn bin_points(
    points: &[[f32; 3]],
    frame: &Frame,
    domain: &Domain,
    sides: &[Side],
    sub: usize,
) -> Binning {
    let sub = sub.clamp(1, MAX_SUB_CELLS);
    let (cs, ct) = (domain.cols - 1, domain.rows - 1);
    let locator = domain.locator(frame);
    // One part per thread: every part fills and merges its own sub-cell arrays,
    // so parts must stay few (merging is order-independent).
    let parts = rayon::current_num_threads().max(1);
    let part_len = points.len().div_ceil(parts).max(BLOCK);
    points
        .par_chunks(part_len)
        .enumerate()
        .map(|(part, pts)| {
            let mut acc = Binning::empty(sides, cs, ct, sub);
            let mut block = LocatedBlock::default();
            let mut slots = Slots::default();
            for (b, chunk) in pts.chunks(BLOCK).enumerate() {
                block.locate(chunk, &locator, domain.cols, domain.rows);
                slots.compute(&block, cs, sub);
                slots.scatter(&block, &mut acc, part * part_len + b * BLOCK);
            }
            acc
        })
        .reduce_with(Binning::merge)
        .unwrap_or_else(|| Binning::empty(sides, cs, ct, sub))
}

/// Where each point of a block goes: its sub-cell slot, cell and trim triangle.
struct Slots {
    slot: [u32; BLOCK],
    cell: [u32; BLOCK],
    triangle: [u8; BLOCK],
}

impl Default for Slots {
    fn default() -> Self {
        Self {
            slot: [0; BLOCK],
            cell: [0; BLOCK],
            triangle: [0; BLOCK],
        }
    }
}

impl Slots {
    /// Splitting this arithmetic from the dependent read-modify-write updates
    /// keeps both loops tight (the arithmetic vectorises). Indices are computed
    /// in floats, exactly (small integers), and converted once.
    #[inline]
    fn compute(&mut self, block: &LocatedBlock, cells_s: usize, sub: usize) {
        let (cells_s, subf, last) = (cells_s as f64, sub as f64, (sub - 1) as f64);
        for i in 0..BLOCK {
            // `floor` is the truncating cast of the original (u, v >= 0).
            let qs = (block.u[i] * subf).floor().min(last);
            let qt = (block.v[i] * subf).floor().min(last);
            let cell = block.g[i] * cells_s + block.h[i];
            self.cell[i] = small_integer(cell);
            self.slot[i] = small_integer((cell * subf + qt) * subf + qs);
            self.triangle[i] = triangle_of(block.u[i], block.v[i]);
        }
    }

    #[inline]
    fn scatter(&self, block: &LocatedBlock, acc: &mut Binning, first: usize) {
        let n = block.len;
        let bits = &mut acc.trim.bits[..];
        for i in 0..n {
            bits[self.cell[i] as usize] |= self.triangle[i];
        }
        for m in &mut acc.maxima {
            let sign = m.side.sign();
            let (height, index) = m.slots_mut();
            for i in 0..n {
                offer(
                    height,
                    index,
                    self.slot[i] as usize,
                    sign * block.w[i],
                    (first + i) as u32,
                );
            }
        }
    }
}

/// Keeps `(h, i)` in `slot` if it beats the slot's point. Points are offered in
/// increasing index order within a pass, so a tie keeps the earlier point.
#[inline(always)]
fn offer(height: &mut [f64], index: &mut [u32], slot: usize, h: f64, i: u32) {
    if h > height[slot] {
        height[slot] = h;
        index[slot] = i;
    }
}
