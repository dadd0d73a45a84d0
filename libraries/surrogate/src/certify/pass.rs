//! One look at the points of a certification: every point (or those of some
//! tiles) measured against a surface, in parallel parts whose split depends on
//! the number of points only, so sums come out the same however rayon schedules
//! the parts.

use super::gaps::GapBlock;
use super::padded::PaddedSurface;
use super::tally::Tally;
use super::tiles::TileGrid;
use crate::bins::located::BLOCK;
use crate::model::{Locator, Side};
use rayon::prelude::*;
use shroud_geometry::spline::UniformCubicSurface;

/// Points per part at least, and parts at most.
const MIN_PART: usize = 8 * 1024;
const MAX_PARTS: usize = 8;

/// What every look at the points of one certification shares.
pub(super) struct Pass<'a> {
    points: &'a [[f32; 3]],
    pub locator: Locator,
    side: Side,
    pub tiles: TileGrid,
    part_len: usize,
}

impl<'a> Pass<'a> {
    /// Tiles follow the surface's cells (the domain only places the points).
    pub fn new(
        points: &'a [[f32; 3]],
        locator: Locator,
        surface: &UniformCubicSurface,
        side: Side,
    ) -> Self {
        let parts = points.len().div_ceil(MIN_PART).clamp(1, MAX_PARTS);
        let part_len = points.len().div_ceil(parts).max(1);
        let (cells_s, cells_t) = surface.cells();
        Self {
            points,
            locator,
            side,
            tiles: TileGrid::new(cells_s, cells_t, points.len(), parts),
            part_len,
        }
    }

    /// Measures every point; records each point's tile in `tile_of` if given.
    pub fn measure(&self, surface: &UniformCubicSurface, tile_of: Option<&mut [u16]>) -> Tally {
        let padded = PaddedSurface::new(surface);
        let parts: Vec<Tally> = match tile_of {
            Some(tile_of) => self
                .points
                .par_chunks(self.part_len)
                .zip(tile_of.par_chunks_mut(self.part_len))
                .enumerate()
                .map(|(part, (points, tile_of))| {
                    self.measure_part(&padded, points, part * self.part_len, Some(tile_of))
                })
                .collect(),
            None => self
                .points
                .par_chunks(self.part_len)
                .enumerate()
                .map(|(part, points)| {
                    self.measure_part(&padded, points, part * self.part_len, None)
                })
                .collect(),
        };
        self.combine(parts)
    }

    fn measure_part(
        &self,
        padded: &PaddedSurface,
        points: &[[f32; 3]],
        first: usize,
        mut tile_of: Option<&mut [u16]>,
    ) -> Tally {
        let sign = self.side.sign();
        let mut tally = Tally::new(self.tiles.len());
        let mut block = GapBlock::default();
        for (b, chunk) in points.chunks(BLOCK).enumerate() {
            block.locate(chunk, &self.locator, padded, &self.tiles);
            block.weigh(padded);
            block.measure(padded, sign);
            let base = first + b * BLOCK;
            tally.add_block(&block, padded, |i| (base + i) as u32);
            if let Some(tile_of) = tile_of.as_deref_mut() {
                // TileGrid keeps tile numbers below 2^16.
                let out = &mut tile_of[b * BLOCK..b * BLOCK + chunk.len()];
                out.iter_mut()
                    .zip(&block.tile)
                    .for_each(|(o, &t)| *o = t as u16);
            }
        }
        tally
    }

    /// Measures again, against `after`, the points of the `touched` tiles (found
    /// through `tile_of`); the sum of the result is the change of their gaps
    /// since `before`.
    pub fn remeasure(
        &self,
        before: &PaddedSurface,
        after: &UniformCubicSurface,
        tile_of: &[u16],
        touched: &[bool],
    ) -> Tally {
        let after = PaddedSurface::new(after);
        let parts: Vec<Tally> = tile_of
            .par_chunks(self.part_len)
            .enumerate()
            .map(|(part, tile_of)| {
                self.remeasure_part(before, &after, part * self.part_len, tile_of, touched)
            })
            .collect();
        self.combine(parts)
    }

    fn remeasure_part(
        &self,
        before: &PaddedSurface,
        after: &PaddedSurface,
        first: usize,
        tile_of: &[u16],
        touched: &[bool],
    ) -> Tally {
        let mut tally = Tally::new(self.tiles.len());
        let mut block = GapBlock::default();
        let mut batch = Batch::default();
        // The count lives in a local: in the batch it would be stored and
        // reloaded on every point.
        let mut len = 0;
        for (i, &tile) in tile_of.iter().enumerate() {
            // Branch-free: the index is always written and kept only for a
            // touched tile (which tiles are touched is unpredictable).
            batch.index[len % BLOCK] = (first + i) as u32;
            len += usize::from(touched[tile as usize]);
            if len == BLOCK {
                self.remeasure_batch(before, after, &mut batch, len, &mut block, &mut tally);
                len = 0;
            }
        }
        if len > 0 {
            self.remeasure_batch(before, after, &mut batch, len, &mut block, &mut tally);
        }
        tally
    }

    /// Gaps of the first `len` points of a batch to `before` and to `after`,
    /// added as a change.
    fn remeasure_batch(
        &self,
        before: &PaddedSurface,
        after: &PaddedSurface,
        batch: &mut Batch,
        len: usize,
        block: &mut GapBlock,
        tally: &mut Tally,
    ) {
        let sign = self.side.sign();
        for (point, &index) in batch.points.iter_mut().zip(&batch.index[..len]) {
            *point = self.points[index as usize];
        }
        block.locate(&batch.points[..len], &self.locator, after, &self.tiles);
        block.weigh(after);
        block.measure(before, sign);
        let old = block.gap;
        block.measure(after, sign);
        tally.add_changed_block(block, after, &old[..len], |i| batch.index[i]);
    }

    /// Parts in order.
    fn combine(&self, parts: Vec<Tally>) -> Tally {
        parts
            .iter()
            .fold(Tally::new(self.tiles.len()), |mut total, part| {
                total.merge(part);
                total
            })
    }
}

/// Points gathered from anywhere in the cloud, with their indices.
struct Batch {
    points: [[f32; 3]; BLOCK],
    index: [u32; BLOCK],
}

impl Default for Batch {
    fn default() -> Self {
        Self {
            points: [[0.0; 3]; BLOCK],
            index: [0; BLOCK],
        }
    }
}
