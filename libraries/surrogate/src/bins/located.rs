//! Points located a block at a time: parameters, height, cell and position in the
//! cell, kept in separate arrays so that the compiler vectorises the arithmetic
//! (the per-point passes over the cloud spend most of their time here).

use crate::model::Locator;

/// Points per block: large enough to amortise the loop set-up, small enough that
/// the arrays stay in L1.
pub(crate) const BLOCK: usize = 64;

/// `(s, t, w)` of up to [`BLOCK`] points with their knot intervals `(h, g)` and
/// local coordinates `(u, v)`, exactly as `Locator::locate_f32` and
/// `knot_interval` compute them (same operations, same order, so the same bits).
/// The interval indices stay floats (exact small integers): users combine them
/// into one index and convert once, as conversions do not vectorise well.
#[derive(Clone)]
pub(crate) struct LocatedBlock {
    pub len: usize,
    pub s: [f64; BLOCK],
    pub t: [f64; BLOCK],
    pub w: [f64; BLOCK],
    pub h: [f64; BLOCK],
    pub g: [f64; BLOCK],
    pub u: [f64; BLOCK],
    pub v: [f64; BLOCK],
}

impl Default for LocatedBlock {
    fn default() -> Self {
        Self {
            len: 0,
            s: [0.0; BLOCK],
            t: [0.0; BLOCK],
            w: [0.0; BLOCK],
            h: [0.0; BLOCK],
            g: [0.0; BLOCK],
            u: [0.0; BLOCK],
            v: [0.0; BLOCK],
        }
    }
}

impl LocatedBlock {
    /// Locates `points` (at most [`BLOCK`]) on a `cols x rows` spline grid.
    #[inline]
    pub fn locate(&mut self, points: &[[f32; 3]], locator: &Locator, cols: usize, rows: usize) {
        debug_assert!(points.len() <= BLOCK && cols >= 2 && rows >= 2);
        self.len = points.len().min(BLOCK);
        for (i, p) in points.iter().take(BLOCK).enumerate() {
            (self.s[i], self.t[i], self.w[i]) = locator.locate_f32(p);
        }
        // The tail of a short block keeps stale values; they are located like any
        // other (finite or not, `knot_interval` maps them into the grid) and ignored.
        let (s_last, s_cell) = ((cols - 1) as f64, (cols - 2) as f64);
        let (t_last, t_cell) = ((rows - 1) as f64, (rows - 2) as f64);
        for i in 0..BLOCK {
            let (h, u) = knot_interval_f(self.s[i], s_last, s_cell);
            let (g, v) = knot_interval_f(self.t[i], t_last, t_cell);
            (self.u[i], self.v[i], self.h[i], self.g[i]) = (u, v, h, g);
        }
    }
}

/// `knot_interval(s, n)` with `last = n - 1` and `cell = n - 2` as floats and the
/// interval index as a float too (`floor` of a clamped non-negative value equals
/// the truncating cast there), which vectorises.
#[inline(always)]
fn knot_interval_f(s: f64, last: f64, cell: f64) -> (f64, f64) {
    let s = if s >= 0.0 { s.min(last) } else { 0.0 };
    let h = s.floor().min(cell);
    (h, s - h)
}

/// The value of `x`, a non-negative integer below `2^31` held in a float. Adding
/// `2^52` puts it in the low mantissa bits; unlike `as` (which saturates, a
/// dozen scalar instructions) this vectorises.
#[inline(always)]
pub(crate) fn small_integer(x: f64) -> u32 {
    const SHIFT: f64 = (1u64 << 52) as f64;
    (x + SHIFT).to_bits() as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Domain;
    use crate::DomainLocate;
    use glam::DVec3;
    use shroud_geometry::math::Frame;
    use shroud_geometry::spline::knot_interval;

    #[test]
    fn small_integers_convert_exactly() {
        for x in [0u32, 1, 2, 17, 1022, 65_535, 1 << 30, (1u32 << 31) - 1] {
            assert_eq!(small_integer(x as f64), x);
        }
    }

    #[test]
    fn blocks_match_the_scalar_locate_and_knot_interval() {
        let frame = Frame::from_direction(DVec3::new(0.3, -0.2, -1.0)).unwrap();
        let domain = Domain {
            u_min: -1.5,
            v_min: -1.25,
            u_step: 0.17,
            v_step: 0.23,
            cols: 20,
            rows: 13,
        };
        let locator = domain.locator(&frame);
        let points: Vec<[f32; 3]> = (0..200)
            .map(|i| {
                let x = (i as f32 * 0.731).sin() * 2.5;
                let y = (i as f32 * 1.377).cos() * 2.0;
                [x, y, x * y - 0.5]
            })
            .collect();
        let mut block = LocatedBlock::default();
        for chunk in points.chunks(BLOCK) {
            block.locate(chunk, &locator, domain.cols, domain.rows);
            assert_eq!(block.len, chunk.len());
            for (i, p) in chunk.iter().enumerate() {
                let (s, t, w) = locator.locate_f32(p);
                assert_eq!((block.s[i], block.t[i], block.w[i]), (s, t, w));
                let (h, u) = knot_interval(s, domain.cols);
                let (g, v) = knot_interval(t, domain.rows);
                assert_eq!((small_integer(block.h[i]) as usize, block.u[i]), (h, u));
                assert_eq!((small_integer(block.g[i]) as usize, block.v[i]), (g, v));
            }
        }
    }
}
