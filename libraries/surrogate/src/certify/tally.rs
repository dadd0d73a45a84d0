//! What a look at the points found: the sum and largest of the gaps, the smallest
//! gap per tile, and the points on the wrong side. Kept so that a correction can
//! be folded in from the touched tiles alone.

use super::gaps::GapBlock;
use super::padded::PaddedSurface;
use super::tiles::lower_minima;
use crate::bins::located::BLOCK;
use crate::model::{Certificate, Side};
use shroud_geometry::math::Frame;

/// Gap statistics of every point of a pass.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Tally {
    pub count: u64,
    pub sum: f64,
    pub max: f64,
    /// Tile of the (first) point with the largest gap.
    pub max_tile: usize,
    /// Smallest gap per tile (infinite for a tile without points).
    pub minima: Vec<f64>,
    /// `(point index, excess)` of the points short of their rounding margin.
    pub wrong: Vec<(u32, f64)>,
}

impl Tally {
    pub fn new(tiles: usize) -> Self {
        Self {
            count: 0,
            sum: 0.0,
            max: f64::NEG_INFINITY,
            max_tile: 0,
            minima: vec![f64::INFINITY; tiles],
            wrong: Vec::new(),
        }
    }

    /// Adds the measured gaps of `block`; `index(i)` is the cloud index of its
    /// point `i`.
    #[inline]
    pub fn add_block(
        &mut self,
        block: &GapBlock,
        surface: &PaddedSurface,
        index: impl Fn(usize) -> u32,
    ) {
        let n = block.located.len;
        self.count += n as u64;
        self.sum += sum_in_lanes(&block.gap[..n]);
        self.add_extremes(block, surface, index);
    }

    /// Like [`Self::add_block`], but sums the change of the gaps since `before`
    /// (the gaps of the same points to the surface before a correction).
    #[inline]
    pub fn add_changed_block(
        &mut self,
        block: &GapBlock,
        surface: &PaddedSurface,
        before: &[f64],
        index: impl Fn(usize) -> u32,
    ) {
        let n = block.located.len;
        let change: [f64; BLOCK] =
            std::array::from_fn(|i| if i < n { block.gap[i] - before[i] } else { 0.0 });
        self.count += n as u64;
        self.sum += sum_in_lanes(&change[..n]);
        self.add_extremes(block, surface, index);
    }

    fn add_extremes(
        &mut self,
        block: &GapBlock,
        surface: &PaddedSurface,
        index: impl Fn(usize) -> u32,
    ) {
        let gaps = &block.gap[..block.located.len];
        let max = gaps
            .iter()
            .fold(f64::NEG_INFINITY, |m, &v| if v > m { v } else { m });
        // Rare after the first blocks: only then find where the maximum is.
        if max > self.max {
            if let Some(i) = gaps.iter().position(|&v| v == max) {
                (self.max, self.max_tile) = (max, block.tile[i] as usize);
            }
        }
        lower_minima(&mut self.minima, &block.tile[..gaps.len()], gaps);
        block.for_each_wrong(surface, |i, excess| self.wrong.push((index(i), excess)));
    }

    /// Appends a later part (parts are merged in order, so the sum is the same
    /// however the parts were scheduled).
    pub fn merge(&mut self, other: &Tally) {
        self.count += other.count;
        self.sum += other.sum;
        if other.max > self.max {
            (self.max, self.max_tile) = (other.max, other.max_tile);
        }
        self.minima
            .iter_mut()
            .zip(&other.minima)
            .for_each(|(a, &b)| *a = a.min(b));
        self.wrong.extend_from_slice(&other.wrong);
    }

    /// Folds in the points of the `touched` tiles measured again after a
    /// correction: `revised.sum` holds the change of their gaps, which only grew.
    pub fn revise(&mut self, touched: &[bool], revised: Tally) {
        for (tile, minimum) in self.minima.iter_mut().enumerate() {
            if touched[tile] {
                *minimum = revised.minima[tile];
            }
        }
        // The old largest gap stands unless its point was touched; a touched
        // point's gap only grew, so then the new largest is among the touched.
        if touched[self.max_tile] || revised.max > self.max {
            (self.max, self.max_tile) = (revised.max, revised.max_tile);
        }
        self.sum += revised.sum;
        self.wrong = revised.wrong;
    }

    pub fn min(&self) -> f64 {
        self.minima.iter().fold(f64::INFINITY, |m, &x| m.min(x))
    }

    pub fn certificate(&self, frame: &Frame, side: Side, corrected: u64) -> Certificate {
        Certificate {
            side,
            direction: frame.direction.to_array(),
            points_checked: self.count,
            violations: self.wrong.len() as u64,
            // No point checked: gaps of 0 (finite, as every reader demands)
            // rather than the empty fold's infinities.
            min_gap: if self.count > 0 { self.min() } else { 0.0 },
            max_gap: if self.count > 0 { self.max } else { 0.0 },
            mean_gap: if self.count > 0 {
                self.sum / self.count as f64
            } else {
                0.0
            },
            corrected_points: corrected,
        }
    }
}

/// Sum of `x` in four interleaved lanes (one vector), then `(l0 + l2) + (l1 + l3)`.
#[inline]
pub(super) fn sum_in_lanes(x: &[f64]) -> f64 {
    let mut lanes = [0.0f64; 4];
    let groups = x.chunks_exact(4);
    let rest = groups.remainder();
    for group in groups {
        for l in 0..4 {
            lanes[l] += group[l];
        }
    }
    for (l, &v) in rest.iter().enumerate() {
        lanes[l] += v;
    }
    (lanes[0] + lanes[2]) + (lanes[1] + lanes[3])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lane_sums() {
        assert_eq!(sum_in_lanes(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]), 28.0);
        assert_eq!(sum_in_lanes(&[]), 0.0);
    }

    #[test]
    fn a_revision_replaces_touched_tiles_and_keeps_the_rest() {
        let mut tally = Tally::new(3);
        (tally.count, tally.sum, tally.max, tally.max_tile) = (10, 5.0, 2.0, 1);
        tally.minima = vec![0.5, -0.1, 0.2];
        tally.wrong = vec![(4, 0.1)];
        let mut revised = Tally::new(3);
        (revised.sum, revised.max, revised.max_tile) = (0.3, 1.5, 1);
        revised.minima[1] = 0.05;
        let touched = [false, true, false];
        let mut a = tally.clone();
        a.revise(&touched, revised.clone());
        assert_eq!(
            (a.count, a.sum, a.max, a.min(), a.wrong.len()),
            (10, 5.3, 1.5, 0.05, 0)
        );
        // Untouched largest gap: it stands against a smaller revised one.
        tally.max_tile = 2;
        tally.revise(&touched, revised);
        assert_eq!((tally.max, tally.max_tile), (2.0, 2));
    }
}
