//! Certification: the final surface is evaluated in f64 at every input point. Any
//! point on the wrong side (rounding, or a non-candidate point the reduction did
//! not see) is fixed by a monotone local correction, and only the points of the
//! tiles the correction touched are evaluated again, so a surrogate is never
//! returned uncertified and a correction costs no second pass over the cloud.

mod gaps;
mod padded;
mod pass;
mod raise;
mod tally;
mod tiles;

pub use padded::PaddedSurface;

use super::error::FitError;
use super::model::{Certificate, Domain, Side};
use crate::DomainLocate;
use pass::{Measured, Pass};
use shroud_geometry::math::Frame;
use shroud_geometry::spline::UniformCubicSurface;
use tally::Tally;

/// Correction rounds before the fallback (a uniform shift). One round fixes every
/// point short of rounding trouble; the rest are insurance.
const MAX_ROUNDS: usize = 4;

/// Evaluates every point, corrects until none is on the wrong side, and returns
/// the certificate of the final surface.
pub fn certify_surface(
    points: &[[f32; 3]],
    frame: &Frame,
    domain: &Domain,
    surface: &mut UniformCubicSurface,
    side: Side,
) -> Result<Certificate, FitError> {
    let mut tile_of = Vec::new();
    let mut certificates =
        certify_sides(points, frame, domain, &mut [(side, surface)], &mut tile_of)?;
    certificates.pop().ok_or(FitError::NoSamples)
}

/// [`certify_surface`] for every side of a sandwich at once: the sides share a
/// grid, so one look at the cloud locates and weighs each point once and
/// measures it against both sides (the certificates are those of separate
/// certifications, bit for bit). Certificates come in the order of `sides`.
/// `tile_of` is storage for each point's tile (a fitter keeps it from one
/// frame to the next; every element is written before it is read).
pub(crate) fn certify_sides(
    points: &[[f32; 3]],
    frame: &Frame,
    domain: &Domain,
    sides: &mut [(Side, &mut UniformCubicSurface)],
    tile_of: &mut Vec<u16>,
) -> Result<Vec<Certificate>, FitError> {
    let Some((_, first)) = sides.first() else {
        return Ok(Vec::new());
    };
    let grid = (first.cols, first.rows);
    if sides.iter().any(|(_, s)| (s.cols, s.rows) != grid) {
        return sides
            .iter_mut()
            .map(|(side, surface)| certify_surface(points, frame, domain, surface, *side))
            .collect();
    }
    let pass = Pass::new(points, domain.locator(frame), first);
    // The tile of every point, so that a correction finds its points again
    // without locating the whole cloud.
    tile_of.truncate(points.len());
    tile_of.resize(points.len(), 0);
    // A much smaller cloud than the last gives the rest back.
    if tile_of.capacity() > 2 * points.len() {
        tile_of.shrink_to(points.len());
    }
    let measured: Vec<Measured> = sides
        .iter()
        .map(|(side, surface)| Measured {
            surface,
            side: *side,
        })
        .collect();
    let tallies = pass.measure(&measured, Some(tile_of));
    sides
        .iter_mut()
        .zip(tallies)
        .map(|((side, surface), tally)| correct(&pass, tile_of, frame, surface, *side, tally))
        .collect()
}

/// Corrects `surface` until no point of the first look's `tally` is on the
/// wrong side, measuring again only the points of the tiles a correction
/// touched.
fn correct(
    pass: &Pass,
    tile_of: &[u16],
    frame: &Frame,
    surface: &mut UniformCubicSurface,
    side: Side,
    mut tally: Tally,
) -> Result<Certificate, FitError> {
    let mut corrected = 0u64;
    for _ in 0..MAX_ROUNDS {
        if tally.wrong.is_empty() {
            return Ok(tally.certificate(frame, side, corrected));
        }
        corrected += tally.wrong.len() as u64;
        let before = PaddedSurface::new(surface);
        let mut touched = vec![false; pass.tiles.len()];
        raise::raise_wrong_points(
            pass.points,
            &pass.locator,
            surface,
            side,
            &tally.wrong,
            &pass.tiles,
            &mut touched,
        )?;
        let after = Measured { surface, side };
        let revised = pass.remeasure(&before, &after, tile_of, &touched);
        tally.revise(&touched, revised);
    }
    // Never seen: a uniform shift by twice the worst excess, then a full check.
    let worst = tally.wrong.iter().fold(0.0f64, |m, w| m.max(w.1));
    let scale = surface
        .coefficients
        .iter()
        .fold(0.0f64, |m, c| m.max(c.abs()));
    let shift = side.sign() * (2.0 * worst + 64.0 * f64::EPSILON * (1.0 + scale));
    surface.coefficients.iter_mut().for_each(|c| *c += shift);
    corrected += tally.wrong.len() as u64;
    let tally = pass.measure(&[Measured { surface, side }], None);
    match tally.first().map(|t| t.wrong.len()) {
        Some(0) => Ok(tally[0].certificate(frame, side, corrected)),
        Some(n) => Err(FitError::Uncertifiable(n)),
        None => Err(FitError::NoSamples),
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
    let subset: Vec<[f32; 3]> = indices
        .iter()
        .filter_map(|&i| points.get(i as usize).copied())
        .collect();
    let pass = Pass::new(&subset, domain.locator(frame), surface);
    let wrong = pass
        .measure(&[Measured { surface, side }], None)
        .pop()
        .map(|tally| tally.wrong)
        .unwrap_or_default();
    if !wrong.is_empty() {
        let mut touched = vec![false; pass.tiles.len()];
        raise::raise_wrong_points(
            &subset,
            &pass.locator,
            surface,
            side,
            &wrong,
            &pass.tiles,
            &mut touched,
        )?;
    }
    Ok(wrong.len() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn down() -> Frame {
        Frame::from_direction(DVec3::new(0.0, 0.0, -1.0)).unwrap()
    }

    #[test]
    fn correction_lifts_a_low_surface_over_every_point() {
        let domain = Domain {
            u_min: 0.0,
            v_min: 0.0,
            u_step: 1.0,
            v_step: 1.0,
            cols: 5,
            rows: 5,
        };
        let points: Vec<[f32; 3]> = (0..200)
            .map(|i| {
                let x = (i % 20) as f32 * 0.2;
                let y = (i / 20) as f32 * 0.4;
                [x, y, (x * 3.0).sin() + y]
            })
            .collect();
        for side in [Side::Upper, Side::Lower] {
            let mut surf = UniformCubicSurface::constant(5, 5, 0.0).unwrap();
            let cert = certify_surface(&points, &down(), &domain, &mut surf, side).unwrap();
            assert_eq!(cert.violations, 0);
            assert!(cert.min_gap >= 0.0 && cert.corrected_points > 0);
            assert_eq!(cert.points_checked, 200);
        }
    }

    /// A few points poke through a flat surface: the correction touches a few
    /// tiles, and the certificate folded together from the untouched tiles and
    /// the touched ones is what a fresh look at the final surface reports.
    #[test]
    fn a_local_correction_certifies_like_a_fresh_pass() {
        let domain = Domain {
            u_min: -12.0,
            v_min: 0.0,
            u_step: 1.0,
            v_step: 1.0,
            cols: 13,
            rows: 13,
        };
        let mut points: Vec<[f32; 3]> = (0..20_000)
            .map(|i| {
                let (x, y) = ((i % 137) as f32 * 0.0875, (i / 137) as f32 * 0.0821);
                [x, y, 0.5 + 0.3 * (x * 0.7).sin() * (y * 0.9).cos()]
            })
            .collect();
        points[5_000][2] = 1.3;
        points[17_000][2] = 1.1;
        let frame = down();
        let mut surface = UniformCubicSurface::constant(13, 13, 1.0).unwrap();
        let corrected =
            certify_surface(&points, &frame, &domain, &mut surface, Side::Upper).unwrap();
        assert_eq!((corrected.corrected_points, corrected.violations), (2, 0));
        let fresh =
            certify_surface(&points, &frame, &domain, &mut surface.clone(), Side::Upper).unwrap();
        assert_eq!(
            (
                fresh.corrected_points,
                fresh.violations,
                fresh.points_checked
            ),
            (0, 0, 20_000)
        );
        assert_eq!(
            (corrected.min_gap, corrected.max_gap),
            (fresh.min_gap, fresh.max_gap)
        );
        assert!((corrected.mean_gap - fresh.mean_gap).abs() <= 1e-12 * fresh.mean_gap.abs());
        // Only the neighbourhoods of the two points moved.
        let unchanged = surface.coefficients.iter().filter(|&&c| c == 1.0).count();
        assert!(
            unchanged >= 13 * 13 - 2,
            "{unchanged} coefficients unchanged"
        );
    }

    /// Both sides of a sandwich certified in one look at the cloud get exactly
    /// the certificates and corrections of two separate certifications.
    #[test]
    fn sides_certified_together_match_sides_certified_apart() {
        let domain = Domain {
            u_min: -3.0,
            v_min: -2.0,
            u_step: 0.5,
            v_step: 0.5,
            cols: 9,
            rows: 9,
        };
        let points: Vec<[f32; 3]> = (0..30_000)
            .map(|i| {
                let (x, y) = ((i % 173) as f32 * 0.02, (i / 173) as f32 * 0.0231);
                [
                    x,
                    y,
                    0.4 * (x * 1.9).sin() + 0.2 * (y * 2.3).cos() + 0.05 * (i % 7) as f32,
                ]
            })
            .collect();
        let frame = down();
        // Surfaces a little inside the cloud on both sides: corrections happen.
        let upper = UniformCubicSurface::constant(9, 9, 0.5).unwrap();
        let lower = UniformCubicSurface::constant(9, 9, -0.3).unwrap();
        let (mut up_apart, mut low_apart) = (upper.clone(), lower.clone());
        let apart = [
            certify_surface(&points, &frame, &domain, &mut up_apart, Side::Upper).unwrap(),
            certify_surface(&points, &frame, &domain, &mut low_apart, Side::Lower).unwrap(),
        ];
        let (mut up, mut low) = (upper, lower);
        let together = certify_sides(
            &points,
            &frame,
            &domain,
            &mut [(Side::Upper, &mut up), (Side::Lower, &mut low)],
            // Storage left over from a larger cloud: every tile is rewritten.
            &mut vec![u16::MAX; 3 * points.len()],
        )
        .unwrap();
        assert!(apart
            .iter()
            .all(|c| c.corrected_points > 0 && c.violations == 0));
        assert_eq!(together, apart);
        assert_eq!((up, low), (up_apart, low_apart));
    }

    #[test]
    fn check_points_are_secured_before_certification() {
        let domain = Domain {
            u_min: -4.0,
            v_min: 0.0,
            u_step: 1.0,
            v_step: 1.0,
            cols: 5,
            rows: 5,
        };
        let points: Vec<[f32; 3]> = (0..100)
            .map(|i| [(i % 10) as f32 * 0.4, (i / 10) as f32 * 0.4, 0.1 * i as f32])
            .collect();
        let frame = down();
        let mut surface = UniformCubicSurface::constant(5, 5, 0.0).unwrap();
        let raised = secure_points(
            &points,
            &[99, 50, 3],
            &frame,
            &domain,
            &mut surface,
            Side::Upper,
        )
        .unwrap();
        assert_eq!(raised, 3);
        let locator = domain.locator(&frame);
        for i in [99usize, 50, 3] {
            let (s, t, w) = locator.locate_f32(&points[i]);
            assert!(surface.eval(s, t) > w, "check point {i}");
        }
        // Nothing left to secure.
        assert_eq!(
            secure_points(
                &points,
                &[99, 50, 3],
                &frame,
                &domain,
                &mut surface,
                Side::Upper
            ),
            Ok(0)
        );
    }
}
