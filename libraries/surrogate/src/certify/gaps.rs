//! Gaps `sign * (f(s, t) - w)` of a block of points, evaluated exactly as
//! `UniformCubicSurface::eval` evaluates `f` (same operations, same order), with
//! the per-point arithmetic in vectorisable loops.

use super::padded::PaddedSurface;
use super::tiles::TileGrid;
use crate::bins::located::{small_integer, LocatedBlock, BLOCK};
use crate::exact_weights::{basis_weights_fma, needs_division};
use crate::model::Locator;
use shroud_geometry::spline::basis_weights;

/// Smallest gap a certified point may have. The f64 value of `f` is off by at
/// most about 20 ulps of `scale`, the largest coefficient of the point's cell
/// (weights a few ulps off, products, two four-term sums), and the Bézier form
/// or de Casteljau's order by about as much again; 64 ulps of the scale plus the
/// height (and one unit, against underflow) leaves room for both, so the point
/// is on its side in exact arithmetic and in any such order.
#[inline(always)]
pub(super) fn rounding_margin(w: f64, scale: f64) -> f64 {
    64.0 * f64::EPSILON * (1.0 + w.abs() + scale)
}

/// Whether `gap` falls short of `margin` or is not a number at all.
#[inline(always)]
fn short_of(gap: f64, margin: f64) -> bool {
    gap < margin || gap.is_nan()
}

/// One block's points, their tiles and gaps.
pub(super) struct GapBlock {
    pub located: LocatedBlock,
    pub tile: [u32; BLOCK],
    pub gap: [f64; BLOCK],
    a: [[f64; 4]; BLOCK],
    b: [[f64; 4]; BLOCK],
    first: [u32; BLOCK],
}

impl Default for GapBlock {
    fn default() -> Self {
        Self {
            located: LocatedBlock::default(),
            tile: [0; BLOCK],
            gap: [0.0; BLOCK],
            a: [[0.0; 4]; BLOCK],
            b: [[0.0; 4]; BLOCK],
            first: [0; BLOCK],
        }
    }
}

impl GapBlock {
    /// Locates `points` (at most [`BLOCK`]) and assigns their tiles.
    #[inline]
    pub fn locate(
        &mut self,
        points: &[[f32; 3]],
        locator: &Locator,
        surface: &PaddedSurface,
        tiles: &TileGrid,
    ) {
        self.located
            .locate(points, locator, surface.cols, surface.rows);
        let l = &self.located;
        for i in 0..BLOCK {
            self.tile[i] = small_integer(tiles.tile(l.h[i], l.g[i]));
        }
    }

    /// Basis weights and cell offsets of every located point (they do not depend
    /// on the coefficients, so one call serves several surfaces of one grid).
    #[inline]
    pub fn weigh(&mut self, surface: &PaddedSurface) {
        let stride = surface.stride as f64;
        let l = &self.located;
        for i in 0..BLOCK {
            (self.a[i], self.b[i]) = (basis_weights_fma(l.u[i]), basis_weights_fma(l.v[i]));
            self.first[i] = small_integer(l.g[i] * stride + l.h[i]);
        }
        if (0..BLOCK).fold(false, |any, i| {
            any | needs_division(l.u[i]) | needs_division(l.v[i])
        }) {
            self.divide_tiny_parameters();
        }
    }

    /// Gaps of every weighed point to `surface`.
    #[inline]
    pub fn measure(&mut self, surface: &PaddedSurface, sign: f64) {
        let l = &self.located;
        for i in 0..l.len {
            let (a, b) = (&self.a[i], &self.b[i]);
            self.gap[i] = sign * (surface.eval_in_cell(self.first[i] as usize, a, b) - l.w[i]);
        }
    }

    /// The rare parameters within `1e-90` of a knot take the weights with the
    /// divisions (see `exact_weights`).
    #[cold]
    fn divide_tiny_parameters(&mut self) {
        let l = &self.located;
        for i in 0..BLOCK {
            if needs_division(l.u[i]) || needs_division(l.v[i]) {
                (self.a[i], self.b[i]) = (basis_weights(l.u[i]), basis_weights(l.v[i]));
            }
        }
    }

    /// Calls `wrong(i, excess)` for every measured point closer to `surface` than
    /// its rounding margin (or on the wrong side, or not comparable at all).
    #[inline]
    pub fn for_each_wrong(&self, surface: &PaddedSurface, mut wrong: impl FnMut(usize, f64)) {
        let l = &self.located;
        // First against the largest margin of the surface (no lookups): almost
        // every block clears it, and a point that clears it clears its own.
        let widest = |i: usize| rounding_margin(l.w[i], surface.max_scale);
        if !(0..l.len).fold(false, |any, i| any | short_of(self.gap[i], widest(i))) {
            return;
        }
        for i in 0..l.len {
            let scale = surface
                .scale
                .get(self.first[i] as usize)
                .copied()
                .unwrap_or(f64::INFINITY);
            let margin = rounding_margin(l.w[i], scale);
            if short_of(self.gap[i], margin) {
                wrong(i, margin - self.gap[i]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Domain;
    use crate::DomainLocate;
    use glam::DVec3;
    use shroud_geometry::math::Frame;
    use shroud_geometry::spline::UniformCubicSurface;

    #[test]
    fn block_gaps_are_bit_identical_to_surface_eval() {
        let frame = Frame::from_direction(DVec3::new(0.2, 0.1, -1.0)).unwrap();
        let domain = Domain {
            u_min: -2.0,
            v_min: -1.5,
            u_step: 0.21,
            v_step: 0.17,
            cols: 20,
            rows: 19,
        };
        let coefficients: Vec<f64> = (0..20 * 19)
            .map(|i| ((i * 7919) % 101) as f64 * 0.013 - 0.4)
            .collect();
        let surface = UniformCubicSurface::new(20, 19, coefficients).unwrap();
        let padded = PaddedSurface::new(&surface);
        let locator = domain.locator(&frame);
        let tiles = TileGrid::new(19, 18, 1000, 1);
        // Points inside, on the edges and outside the domain (clamped parameters).
        let points: Vec<[f32; 3]> = (0..1000)
            .map(|i| {
                let x = (i as f32 * 0.37).sin() * 2.5 + 0.5;
                let y = (i as f32 * 0.91).cos() * 2.0 + 0.2;
                [x, y, 0.3 * x - 0.2 * y]
            })
            .chain([[-2.0, -1.5, 0.0], [2.0, 1.6, 0.1]])
            .collect();
        let mut block = GapBlock::default();
        for (c, chunk) in points.chunks(BLOCK).enumerate() {
            for sign in [1.0, -1.0] {
                block.locate(chunk, &locator, &padded, &tiles);
                block.weigh(&padded);
                block.measure(&padded, sign);
                for (i, p) in chunk.iter().enumerate() {
                    let (s, t, w) = locator.locate_f32(p);
                    let expected = sign * (surface.eval(s, t) - w);
                    assert_eq!(
                        block.gap[i].to_bits(),
                        expected.to_bits(),
                        "point {}",
                        c * BLOCK + i
                    );
                }
            }
        }
    }

    /// Parameters within `1e-90` of a knot take the weights with divisions; the
    /// gaps stay those of `UniformCubicSurface::eval`.
    #[test]
    fn tiny_parameters_are_evaluated_exactly() {
        let coefficients: Vec<f64> = (0..16).map(|i| 1.0 + (i * 7 % 5) as f64 * 0.25).collect();
        let surface = UniformCubicSurface::new(4, 4, coefficients).unwrap();
        let padded = PaddedSurface::new(&surface);
        let mut block = GapBlock::default();
        let params = [(1e-200, 0.5), (0.5, 3e-120), (1e-300, 1e-300), (0.25, 0.75)];
        block.located.len = params.len();
        for (i, &(s, t)) in params.iter().enumerate() {
            (block.located.s[i], block.located.t[i], block.located.w[i]) = (s, t, 1.0);
            (
                block.located.u[i],
                block.located.v[i],
                block.located.h[i],
                block.located.g[i],
            ) = (s, t, 0.0, 0.0);
        }
        block.weigh(&padded);
        block.measure(&padded, 1.0);
        for (i, &(s, t)) in params.iter().enumerate() {
            assert_eq!(
                block.gap[i].to_bits(),
                (surface.eval(s, t) - 1.0).to_bits(),
                "({s:e}, {t:e})"
            );
        }
    }

    #[test]
    fn wrong_points_include_the_rounding_band_and_nan() {
        let surface = UniformCubicSurface::constant(4, 4, 2.0).unwrap();
        let padded = PaddedSurface::new(&surface);
        let mut block = GapBlock::default();
        block.located.len = 4;
        block.located.w[..4].copy_from_slice(&[1.0, 1.0, 1.0, 1.0]);
        block.gap[..4].copy_from_slice(&[1.0, 1e-15, -0.5, f64::NAN]);
        let mut wrong = Vec::new();
        block.for_each_wrong(&padded, |i, excess| wrong.push((i, excess)));
        assert_eq!(wrong.iter().map(|w| w.0).collect::<Vec<_>>(), vec![1, 2, 3]);
        assert!(wrong[0].1 > 0.0 && wrong[1].1 > 0.5 && wrong[2].1.is_nan());
        assert_eq!(wrong[1].1, rounding_margin(1.0, 2.0) + 0.5);
    }
}
