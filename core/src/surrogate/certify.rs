//! Certification: the final surface is evaluated in f64 at every input point. Any
//! point on the wrong side (rounding, or a non-candidate point the reduction did
//! not see) is fixed by a monotone local correction, and only the points of the
//! tiles the correction touched are evaluated again, so a surrogate is never
//! returned uncertified and a correction costs no second pass over the cloud.

mod exact_weights;
mod gaps;
mod padded;
mod raise;
mod tally;
mod tiles;

pub use padded::PaddedSurface;

use super::error::FitError;
use super::model::{Certificate, Domain, Locator, Side};
use crate::math::Frame;
use crate::spline::UniformCubicSurface;
use crate::surrogate::bins::located::BLOCK;
use gaps::GapBlock;
use rayon::prelude::*;
use tally::Tally;
use tiles::TileGrid;

/// Correction rounds before the fallback (a uniform shift). One round fixes every
/// point short of rounding trouble; the rest are insurance.
const MAX_ROUNDS: usize = 4;

/// Points per part at least, and parts at most. The split depends on the number
/// of points only, so sums come out the same however rayon schedules the parts.
const MIN_PART: usize = 8 * 1024;
const MAX_PARTS: usize = 8;

/// Evaluates every point, corrects until none is on the wrong side, and returns
/// the certificate of the final surface.
pub fn certify_surface(
    points: &[[f32; 3]],
    frame: &Frame,
    domain: &Domain,
    surface: &mut UniformCubicSurface,
    side: Side,
) -> Result<Certificate, FitError> {
    let pass = Pass::new(points, domain.locator(frame), surface, side);
    // The tile of every point, so that a correction finds its points again
    // without locating the whole cloud.
    let mut tile_of = vec![0u16; points.len()];
    let mut tally = pass.measure(surface, Some(&mut tile_of));
    let mut corrected = 0u64;
    for _ in 0..MAX_ROUNDS {
        if tally.wrong.is_empty() {
            return Ok(tally.certificate(frame, side, corrected));
        }
        corrected += tally.wrong.len() as u64;
        let before = PaddedSurface::new(surface);
        let mut touched = vec![false; pass.tiles.len()];
        raise::raise_wrong_points(points, &pass.locator, surface, side, &tally.wrong, &pass.tiles, &mut touched)?;
        let revised = pass.remeasure(&before, surface, &tile_of, &touched);
        tally.revise(&touched, revised);
    }
    // Never seen: a uniform shift by twice the worst excess, then a full check.
    let worst = tally.wrong.iter().fold(0.0f64, |m, w| m.max(w.1));
    let scale = tally.max.abs().max(tally.min().abs());
    let shift = side.sign() * (2.0 * worst + 64.0 * f64::EPSILON * (1.0 + scale));
    surface.coefficients.iter_mut().for_each(|c| *c += shift);
    corrected += tally.wrong.len() as u64;
    let tally = pass.measure(surface, None);
    match tally.wrong.len() {
        0 => Ok(tally.certificate(frame, side, corrected)),
        n => Err(FitError::Uncertifiable(n)),
    }
}

/// Raises `surface` over the listed points (one measurement, one correction) and
/// returns how many needed it. Fitting calls this on a few check points (the
/// sub-cell maxima) so that certification rarely has anything to correct; a
/// point the correction left short by rounding is certification's to fix.
pub(crate) fn secure_points(
    points: &[[f32; 3]],
    indices: &[u32],
    frame: &Frame,
    domain: &Domain,
    surface: &mut UniformCubicSurface,
    side: Side,
) -> Result<u64, FitError> {
    let subset: Vec<[f32; 3]> = indices.iter().filter_map(|&i| points.get(i as usize).copied()).collect();
    let pass = Pass::new(&subset, domain.locator(frame), surface, side);
    let wrong = pass.measure(surface, None).wrong;
    if !wrong.is_empty() {
        let mut touched = vec![false; pass.tiles.len()];
        raise::raise_wrong_points(&subset, &pass.locator, surface, side, &wrong, &pass.tiles, &mut touched)?;
    }
    Ok(wrong.len() as u64)
}

/// What every look at the points of one certification shares.
struct Pass<'a> {
    points: &'a [[f32; 3]],
    locator: Locator,
    side: Side,
    tiles: TileGrid,
    part_len: usize,
}

impl<'a> Pass<'a> {
    /// Tiles follow the surface's cells (the domain only places the points).
    fn new(points: &'a [[f32; 3]], locator: Locator, surface: &UniformCubicSurface, side: Side) -> Self {
        let parts = points.len().div_ceil(MIN_PART).clamp(1, MAX_PARTS);
        let part_len = points.len().div_ceil(parts).max(1);
        let (cells_s, cells_t) = surface.cells();
        Self { points, locator, side, tiles: TileGrid::new(cells_s, cells_t, points.len(), parts), part_len }
    }

    /// Measures every point; records each point's tile in `tile_of` if given.
    fn measure(&self, surface: &UniformCubicSurface, tile_of: Option<&mut [u16]>) -> Tally {
        let padded = PaddedSurface::new(surface);
        let parts: Vec<Tally> = match tile_of {
            Some(tile_of) => self
                .points
                .par_chunks(self.part_len)
                .zip(tile_of.par_chunks_mut(self.part_len))
                .enumerate()
                .map(|(part, (points, tile_of))| self.measure_part(&padded, points, part * self.part_len, Some(tile_of)))
                .collect(),
            None => self
                .points
                .par_chunks(self.part_len)
                .enumerate()
                .map(|(part, points)| self.measure_part(&padded, points, part * self.part_len, None))
                .collect(),
        };
        self.combine(parts)
    }

    fn measure_part(&self, padded: &PaddedSurface, points: &[[f32; 3]], first: usize, mut tile_of: Option<&mut [u16]>) -> Tally {
        let sign = self.side.sign();
        let mut tally = Tally::new(self.tiles.len());
        let mut block = GapBlock::default();
        for (b, chunk) in points.chunks(BLOCK).enumerate() {
            block.locate(chunk, &self.locator, padded, &self.tiles);
            block.weigh(padded);
            block.measure(padded, sign);
            let base = first + b * BLOCK;
            tally.add_block(&block, |i| (base + i) as u32);
            if let Some(tile_of) = tile_of.as_deref_mut() {
                // TileGrid keeps tile numbers below 2^16.
                let out = &mut tile_of[b * BLOCK..b * BLOCK + chunk.len()];
                out.iter_mut().zip(&block.tile).for_each(|(o, &t)| *o = t as u16);
            }
        }
        tally
    }

    /// Measures again, against `after`, the points of the `touched` tiles (found
    /// through `tile_of`); the sum of the result is the change of their gaps
    /// since `before`.
    fn remeasure(&self, before: &PaddedSurface, after: &UniformCubicSurface, tile_of: &[u16], touched: &[bool]) -> Tally {
        let after = PaddedSurface::new(after);
        let parts: Vec<Tally> = tile_of
            .par_chunks(self.part_len)
            .enumerate()
            .map(|(part, tile_of)| self.remeasure_part(before, &after, part * self.part_len, tile_of, touched))
            .collect();
        self.combine(parts)
    }

    fn remeasure_part(&self, before: &PaddedSurface, after: &PaddedSurface, first: usize, tile_of: &[u16], touched: &[bool]) -> Tally {
        let mut tally = Tally::new(self.tiles.len());
        let mut block = GapBlock::default();
        let mut batch = Batch::default();
        for (i, &tile) in tile_of.iter().enumerate() {
            // Branch-free: the index is always written and kept only for a
            // touched tile (which tiles are touched is unpredictable).
            batch.index[batch.len % BLOCK] = (first + i) as u32;
            batch.len += usize::from(touched[tile as usize]);
            if batch.len == BLOCK {
                self.remeasure_batch(before, after, &mut batch, &mut block, &mut tally);
            }
        }
        if batch.len > 0 {
            self.remeasure_batch(before, after, &mut batch, &mut block, &mut tally);
        }
        tally
    }

    /// Gaps of a batch to `before` and to `after`, added as a change; empties it.
    fn remeasure_batch(&self, before: &PaddedSurface, after: &PaddedSurface, batch: &mut Batch, block: &mut GapBlock, tally: &mut Tally) {
        let sign = self.side.sign();
        for (point, &index) in batch.points.iter_mut().zip(&batch.index[..batch.len]) {
            *point = self.points[index as usize];
        }
        block.locate(&batch.points[..batch.len], &self.locator, after, &self.tiles);
        block.weigh(after);
        block.measure(before, sign);
        let old = block.gap;
        block.measure(after, sign);
        tally.add_changed_block(block, &old[..batch.len], |i| batch.index[i]);
        batch.len = 0;
    }

    /// Parts in order.
    fn combine(&self, parts: Vec<Tally>) -> Tally {
        parts.iter().fold(Tally::new(self.tiles.len()), |mut total, part| {
            total.merge(part);
            total
        })
    }
}

/// Points gathered from anywhere in the cloud, with their indices.
struct Batch {
    len: usize,
    points: [[f32; 3]; BLOCK],
    index: [u32; BLOCK],
}

impl Default for Batch {
    fn default() -> Self {
        Self { len: 0, points: [[0.0; 3]; BLOCK], index: [0; BLOCK] }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn correction_lifts_a_low_surface_over_every_point() {
        let frame = Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap();
        let domain = Domain { u_min: 0.0, v_min: 0.0, u_step: 1.0, v_step: 1.0, cols: 5, rows: 5 };
        let points: Vec<[f32; 3]> = (0..200)
            .map(|i| {
                let x = (i % 20) as f32 * 0.2;
                let y = (i / 20) as f32 * 0.4;
                [x, y, (x * 3.0).sin() + y]
            })
            .collect();
        for side in [Side::Upper, Side::Lower] {
            let mut surf = UniformCubicSurface::constant(5, 5, 0.0).unwrap();
            let cert = certify_surface(&points, &frame, &domain, &mut surf, side).unwrap();
            assert_eq!(cert.violations, 0);
            assert!(cert.min_gap >= 0.0 && cert.corrected_points > 0);
            assert_eq!(cert.points_checked, 200);
        }
    }
}
