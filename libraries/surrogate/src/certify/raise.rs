//! The monotone local correction: a point on the wrong side is fixed by moving the
//! one coefficient with the largest B-spline weight at it, away from the cloud.
//! B-splines are non-negative, so the surface moves away from the cloud
//! everywhere and no other point can become wrong; the move is confined to the
//! 4 x 4 cells that coefficient acts on, so only their points need a new check.

use super::gaps::rounding_margin;
use super::tiles::TileGrid;
use crate::error::FitError;
use crate::model::{Locator, Side};
use shroud_geometry::spline::{basis_weights, knot_interval, UniformCubicSurface};

/// Raises `surface` (in the direction of `side`) so that each `(point, excess)` of
/// `wrong` gains at least `excess` plus a rounding margin, and marks in `touched`
/// the tiles whose surface changed. Fails on a non-finite excess (a point that
/// cannot be compared with the surface).
pub(super) fn raise_wrong_points(
    points: &[[f32; 3]],
    locator: &Locator,
    surface: &mut UniformCubicSurface,
    side: Side,
    wrong: &[(u32, f64)],
    tiles: &TileGrid,
    touched: &mut [bool],
) -> Result<(), FitError> {
    let (cols, rows) = (surface.cols, surface.rows);
    let mut need = vec![0.0f64; surface.coefficients.len()];
    for &(index, excess) in wrong {
        let point = points
            .get(index as usize)
            .ok_or(FitError::Uncertifiable(wrong.len()))?;
        let (s, t, w) = locator.locate_f32(point);
        let (h, u) = knot_interval(s, cols);
        let (g, v) = knot_interval(t, rows);
        // The margin the point will be held to: the raise grows the cell's
        // coefficients by at most 16 times the amount (see below).
        let scale = surface
            .cell_coefficients(h, g)
            .iter()
            .flatten()
            .fold(0.0f64, |m, c| m.max(c.abs()));
        let amount = excess * (1.0 + 1e-9) + rounding_margin(w + excess, scale + 32.0 * excess);
        if !amount.is_finite() {
            return Err(FitError::Uncertifiable(wrong.len()));
        }
        let (q, a) = largest(basis_weights(u));
        let (r, b) = largest(basis_weights(v));
        // The coefficient's weight at the point is at least a * b (the clamped ends
        // can add a second term), and a * b >= 1/16 since the weights sum to one.
        let j = (h + q).saturating_sub(1).min(cols - 1);
        let k = (g + r).saturating_sub(1).min(rows - 1);
        let slot = &mut need[k * cols + j];
        *slot = slot.max(amount / (a * b));
        // Coefficient j acts on cells j-2 ..= j+1.
        tiles.mark(
            touched,
            (j.saturating_sub(2), j + 1),
            (k.saturating_sub(2), k + 1),
        );
    }
    let sign = side.sign();
    surface
        .coefficients
        .iter_mut()
        .zip(&need)
        .for_each(|(c, n)| *c += sign * n);
    Ok(())
}

/// Index and value of the largest of four weights.
fn largest(weights: [f64; 4]) -> (usize, f64) {
    (1..4).fold((0, weights[0]), |best, q| {
        if weights[q] > best.1 {
            (q, weights[q])
        } else {
            best
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Domain;
    use crate::DomainLocate;
    use glam::DVec3;
    use shroud_geometry::math::Frame;

    #[test]
    fn a_raise_lifts_the_point_and_touches_only_nearby_tiles() {
        let frame = Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap();
        let domain = Domain {
            u_min: 0.0,
            v_min: -12.0,
            u_step: 1.0,
            v_step: 1.0,
            cols: 12,
            rows: 12,
        };
        let locator = domain.locator(&frame);
        let tiles = TileGrid::new(11, 11, 1000, 1);
        let points = [[-5.3f32, -6.8, 1.0]];
        let (s, t, w) = locator.locate_f32(&points[0]);
        let (h, g) = (s as usize, t as usize);
        assert!(
            s > 1.0 && s < 10.0 && t > 1.0 && t < 10.0 && w == 1.0,
            "({s}, {t}, {w})"
        );
        let before = UniformCubicSurface::constant(12, 12, 1.0).unwrap();
        for side in [Side::Upper, Side::Lower] {
            let mut surface = before.clone();
            let mut touched = vec![false; tiles.len()];
            raise_wrong_points(
                &points,
                &locator,
                &mut surface,
                side,
                &[(0, 0.25)],
                &tiles,
                &mut touched,
            )
            .unwrap();
            let gap = side.sign() * (surface.eval(s, t) - before.eval(s, t));
            assert!(gap >= 0.25 + rounding_margin(1.0, 1.0), "gap {gap}");
            assert_eq!(
                surface.coefficients.iter().filter(|&&c| c != 1.0).count(),
                1
            );
            assert!(touched.iter().filter(|&&t| t).count() <= 16 && touched[g * 11 + h]);
            // Far from the touched tiles the surface did not move.
            let far = (
                if s > 5.5 { 0.5 } else { 10.5 },
                if t > 5.5 { 0.5 } else { 10.5 },
            );
            assert_eq!(surface.eval(far.0, far.1), before.eval(far.0, far.1));
        }
    }

    #[test]
    fn a_nan_excess_is_an_error() {
        let frame = Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap();
        let domain = Domain {
            u_min: 0.0,
            v_min: 0.0,
            u_step: 1.0,
            v_step: 1.0,
            cols: 4,
            rows: 4,
        };
        let tiles = TileGrid::new(3, 3, 10, 1);
        let mut surface = UniformCubicSurface::constant(4, 4, 0.0).unwrap();
        let mut touched = vec![false; tiles.len()];
        let wrong = [(0, f64::NAN)];
        let result = raise_wrong_points(
            &[[1.0, 1.0, 1.0]],
            &domain.locator(&frame),
            &mut surface,
            Side::Upper,
            &wrong,
            &tiles,
            &mut touched,
        );
        assert_eq!(result, Err(FitError::Uncertifiable(1)));
    }
}
