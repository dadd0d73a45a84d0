//! One look at the points of a certification: every point (or those of some
//! tiles) measured against one surface or both sides of a sandwich, in parallel
//! parts whose split depends on the number of points only, so sums come out the
//! same however rayon schedules the parts.

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

/// What every look at the points of one certification shares. The sides of a
/// sandwich share a grid, so they share the points' locations and basis weights
/// too: one look locates and weighs each point once and measures it against
/// every side (most of a look's work is locating and weighing).
pub(super) struct Pass<'a> {
    pub points: &'a [[f32; 3]],
    pub locator: Locator,
    pub tiles: TileGrid,
    part_len: usize,
}

/// A surface being certified and the side of the cloud it must stay on.
pub(super) struct Measured<'s> {
    pub surface: &'s UniformCubicSurface,
    pub side: Side,
}

impl<'a> Pass<'a> {
    /// Tiles follow the surface's cells (the domain only places the points).
    pub fn new(points: &'a [[f32; 3]], locator: Locator, surface: &UniformCubicSurface) -> Self {
        let parts = points.len().div_ceil(MIN_PART).clamp(1, MAX_PARTS);
        let part_len = points.len().div_ceil(parts).max(1);
        let (cells_s, cells_t) = surface.cells();
        Self {
            points,
            locator,
            tiles: TileGrid::new(cells_s, cells_t, points.len(), parts),
            part_len,
        }
    }

    /// Measures every point against each surface (one tally each, in order);
    /// records each point's tile in `tile_of` if given.
    pub fn measure(&self, surfaces: &[Measured], tile_of: Option<&mut [u16]>) -> Vec<Tally> {
        let padded: Vec<(PaddedSurface, f64)> = surfaces
            .iter()
            .map(|m| (PaddedSurface::new(m.surface), m.side.sign()))
            .collect();
        let parts: Vec<Vec<Tally>> = match tile_of {
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
        (0..surfaces.len())
            .map(|k| self.combine(parts.iter().map(|part| &part[k])))
            .collect()
    }

    fn measure_part(
        &self,
        surfaces: &[(PaddedSurface, f64)],
        points: &[[f32; 3]],
        first: usize,
        mut tile_of: Option<&mut [u16]>,
    ) -> Vec<Tally> {
        let mut tallies: Vec<Tally> = surfaces
            .iter()
            .map(|_| Tally::new(self.tiles.len()))
            .collect();
        let Some((grid, _)) = surfaces.first() else {
            return tallies;
        };
        let mut block = GapBlock::default();
        for (b, chunk) in points.chunks(BLOCK).enumerate() {
            // Location and weights depend on the grid only, which the sides share.
            block.locate(chunk, &self.locator, grid, &self.tiles);
            block.weigh(grid);
            let base = first + b * BLOCK;
            for ((padded, sign), tally) in surfaces.iter().zip(&mut tallies) {
                block.measure(padded, *sign);
                tally.add_block(&block, padded, |i| (base + i) as u32);
            }
            if let Some(tile_of) = tile_of.as_deref_mut() {
                // TileGrid keeps tile numbers below 2^16.
                let out = &mut tile_of[b * BLOCK..b * BLOCK + chunk.len()];
                out.iter_mut()
                    .zip(&block.tile)
                    .for_each(|(o, &t)| *o = t as u16);
            }
        }
        tallies
    }

    /// Measures again, against `after`, the points of the `touched` tiles (found
    /// through `tile_of`); the sum of the result is the change of their gaps
    /// since `before`.
    pub fn remeasure(
        &self,
        before: &PaddedSurface,
        after: &Measured,
        tile_of: &[u16],
        touched: &[bool],
    ) -> Tally {
        let sign = after.side.sign();
        let after = PaddedSurface::new(after.surface);
        let parts: Vec<Tally> = tile_of
            .par_chunks(self.part_len)
            .enumerate()
            .map(|(part, tile_of)| {
                let first = part * self.part_len;
                self.remeasure_part(before, &after, sign, first, tile_of, touched)
            })
            .collect();
        self.combine(parts.iter())
    }

    fn remeasure_part(
        &self,
        before: &PaddedSurface,
        after: &PaddedSurface,
        sign: f64,
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
                let batch = (&mut batch, len);
                self.remeasure_batch(before, after, sign, batch, &mut block, &mut tally);
                len = 0;
            }
        }
        if len > 0 {
            let batch = (&mut batch, len);
            self.remeasure_batch(before, after, sign, batch, &mut block, &mut tally);
        }
        tally
    }

    /// Gaps of the first `len` points of a batch to `before` and to `after`,
    /// added as a change.
    fn remeasure_batch(
        &self,
        before: &PaddedSurface,
        after: &PaddedSurface,
        sign: f64,
        (batch, len): (&mut Batch, usize),
        block: &mut GapBlock,
        tally: &mut Tally,
    ) {
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
    fn combine<'t>(&self, parts: impl Iterator<Item = &'t Tally>) -> Tally {
        parts.fold(Tally::new(self.tiles.len()), |mut total, part| {
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
