//! The surface surrogate fitter: one streaming pass, the Section 6 reduction on the
//! candidates, optional symmetrisation and tightening, sandwich un-crossing, and
//! certification of every point.

use super::bins::{bin_points, SubCellMaxima, MAX_SUB_CELLS};
use super::candidates::candidates_of;
use super::certify::{certify_sides, secure_points};
use super::error::FitError;
use super::footprint::domain_of_cloud;
use super::model::{Domain, SafeSurface, Side, Surrogate};
use super::options::{FitOptions, Tightness};
use super::reduction::{fit_by_reduction, Orientation, ReductionWarmStart};
use super::tighten::{lower_reusing, LoweringBuffers};
use super::trim::TrimMask;
use super::uncross::uncross;
use crate::DomainLocate;
use crate::FitStats;
use glam::DVec3;
use rayon::prelude::*;
use shroud_geometry::math::Frame;
use shroud_geometry::spline::UniformCubicSurface;

/// Enclosed empty regions up to this many triangles stay kept (see
/// `TrimMask::fill_small_holes`): none. An empty triangle is space the sensor
/// did not see, and the guard counts it as possibly occupied; a kept one it
/// would trust as seen (a dark object smaller than two cells returned nothing
/// and would vanish).
const SMALL_HOLE: usize = 0;

/// Largest grid side accepted (a guard against absurd allocations from input).
pub const MAX_GRID: usize = 1024;

/// A fitter that keeps warm-start state between frames of an evolving cloud.
#[derive(Debug, Clone)]
pub struct SurrogateFitter {
    options: FitOptions,
    frame: Frame,
    /// Per side, in the order of `Sides::list` (a fitter's sides never
    /// change), and orientation (along s, along t).
    warm: [[ReductionWarmStart; 2]; 2],
    frames: u64,
    /// Storage reused from one frame to the next (it does not change results).
    buffers: FitBuffers,
}

/// The large scratch arrays of a fit: each point's tile during certification
/// (2 bytes a point) and each side's lowering matrix (24 bytes a matrix entry,
/// about 16 per candidate). Kept by the fitter, a stream's fits write over the
/// last frame's arrays instead of allocating and clearing new ones; they are
/// given back when a frame needs less than half of them, and a clone of the
/// fitter starts without them.
#[derive(Default)]
struct FitBuffers {
    tile_of: Vec<u16>,
    lowering: [LoweringBuffers; 2],
}

impl Clone for FitBuffers {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl std::fmt::Debug for FitBuffers {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "FitBuffers({} points, {:?})",
            self.tile_of.len(),
            self.lowering
        )
    }
}

/// Fits a surrogate from scratch (no warm start).
pub fn fit_surrogate(points: &[[f32; 3]], options: &FitOptions) -> Result<Surrogate, FitError> {
    SurrogateFitter::new(options.clone())?.fit(points)
}

impl SurrogateFitter {
    pub fn new(options: FitOptions) -> Result<Self, FitError> {
        let (cols, rows) = (options.cols, options.rows);
        if cols < 2 || rows < 2 {
            return Err(FitError::GridTooSmall { cols, rows });
        }
        if cols > MAX_GRID || rows > MAX_GRID {
            return Err(FitError::GridTooLarge {
                cols,
                rows,
                max: MAX_GRID,
            });
        }
        let frame = Frame::from_direction(DVec3::from_array(options.direction))?;
        Ok(Self {
            options,
            frame,
            warm: Default::default(),
            frames: 0,
            buffers: FitBuffers::default(),
        })
    }

    pub fn options(&self) -> &FitOptions {
        &self.options
    }

    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Forgets the previous frame (the next fit starts cold).
    pub fn reset_warm_start(&mut self) {
        self.warm = Default::default();
        self.frames = 0;
    }

    /// Fits and certifies a surrogate of `points`, warm-started from the last fit.
    pub fn fit(&mut self, points: &[[f32; 3]]) -> Result<Surrogate, FitError> {
        let o = &self.options;
        let frame = self.frame;
        let domain = domain_of_cloud(points, &frame, o.cols, o.rows)?;
        let sub = o.sub_cells.clamp(1, MAX_SUB_CELLS / 2);
        let check = check_factor(points.len(), (o.cols - 1) * (o.rows - 1), sub);
        let binning = bin_points(points, &frame, &domain, o.sides.list(), sub * check);
        let candidates: Vec<u32> = binning
            .maxima
            .iter()
            .flat_map(|m| m.occupied().map(|(_, _, i)| i))
            .collect();
        super::collinear::ensure_not_collinear(points, &frame, &candidates)?;
        let trim = if o.trim {
            let mut trim = binning.trim.clone();
            trim.fill_small_holes(SMALL_HOLE);
            trim
        } else {
            TrimMask::full(o.cols - 1, o.rows - 1)
        };
        let mut stats = FitStats {
            points: points.len() as u64,
            warm_started: self.frames > 0,
            ..Default::default()
        };
        let locator = domain.locator(&frame);
        let param_of = |i: u32| {
            let (s, t, _) = locator.locate_f32(&points[i as usize]);
            (s, t)
        };
        // The sides of a sandwich are independent until un-crossing: each is
        // fitted on its own core (their grid work is mostly serial).
        let options = &self.options;
        let jobs: Vec<_> = binning
            .maxima
            .iter()
            .zip(self.warm.iter_mut().zip(self.buffers.lowering.iter_mut()))
            .collect();
        let fitted: Vec<Result<(Side, UniformCubicSurface, FitStats), FitError>> = jobs
            .into_par_iter()
            .map(|(fine, (warm, lowering))| {
                let coarse = (check > 1).then(|| fine.coarsen(check));
                let maxima = coarse.as_ref().unwrap_or(fine);
                let mut side_stats = FitStats::default();
                let job = SideJob {
                    options,
                    param_of: &param_of,
                    trim: &trim,
                    sub,
                };
                let surface = job.fit(maxima, warm, lowering, &mut side_stats)?;
                Ok((fine.side, surface, side_stats))
            })
            .collect();
        let mut surfaces = Vec::with_capacity(fitted.len());
        for side in fitted {
            let (side, surface, side_stats) = side?;
            stats.add_side(&side_stats);
            surfaces.push((side, surface));
        }
        if let [(Side::Upper, up), (Side::Lower, low)] = surfaces.as_mut_slice() {
            stats.uncrossed_coefficients = uncross(up, low, &trim);
        }
        let mut result = Surrogate {
            frame,
            domain,
            trim,
            upper: None,
            lower: None,
            stats,
        };
        let tile_of = &mut self.buffers.tile_of;
        for safe in secure_and_certify(points, &frame, &domain, surfaces, &binning.maxima, tile_of)?
        {
            match safe.side {
                Side::Upper => result.upper = Some(safe),
                Side::Lower => result.lower = Some(safe),
            }
        }
        self.frames += 1;
        Ok(result)
    }
}

/// What fitting one side needs besides its candidates and warm start.
struct SideJob<'a> {
    options: &'a FitOptions,
    param_of: &'a (dyn Fn(u32) -> (f64, f64) + Sync),
    trim: &'a TrimMask,
    sub: usize,
}

impl SideJob<'_> {
    /// Section 6's reduction on one side's candidates (both orientations averaged
    /// if asked), then the tightening; the surface comes back in real heights.
    fn fit(
        &self,
        maxima: &SubCellMaxima,
        warm: &mut [ReductionWarmStart; 2],
        lowering: &mut LoweringBuffers,
        stats: &mut FitStats,
    ) -> Result<UniformCubicSurface, FitError> {
        let (o, param_of) = (self.options, self.param_of);
        let side = maxima.side;
        let mut coefficients = fit_by_reduction(
            maxima,
            Orientation::AlongS,
            param_of,
            &mut warm[0],
            o.max_solves,
            stats,
        )?;
        if o.symmetrize {
            let other = fit_by_reduction(
                maxima,
                Orientation::AlongT,
                param_of,
                &mut warm[1],
                o.max_solves,
                stats,
            )?;
            coefficients
                .iter_mut()
                .zip(&other)
                .for_each(|(a, b)| *a = 0.5 * (*a + b));
        }
        let mut surface =
            UniformCubicSurface::new(o.cols, o.rows, coefficients).ok_or(FitError::NoSamples)?;
        let candidates = candidates_of(maxima, param_of);
        let (trim, sub) = (self.trim, self.sub);
        stats.tightening_moves += match o.tightness {
            Tightness::Plain => 0,
            Tightness::Lowered => {
                lower_reusing(lowering, &mut surface, &candidates, trim, sub, o.sweeps)
            }
            Tightness::Optimal => {
                crate::tight::lower_to_optimum(&mut surface, &candidates, trim, sub)
            }
        };
        // Back from the upper sense to real heights.
        surface
            .coefficients
            .iter_mut()
            .for_each(|c| *c *= side.sign());
        Ok(surface)
    }
}

/// Secures each side's check points (its sub-cell maxima, a few thousand
/// points: what they catch, certification need not correct with another look
/// at the cloud), then certifies every point against every side in one look.
fn secure_and_certify(
    points: &[[f32; 3]],
    frame: &Frame,
    domain: &Domain,
    mut surfaces: Vec<(Side, UniformCubicSurface)>,
    checks: &[SubCellMaxima],
    tile_of: &mut Vec<u16>,
) -> Result<Vec<SafeSurface>, FitError> {
    let mut secured = Vec::with_capacity(surfaces.len());
    for ((side, surface), check) in surfaces.iter_mut().zip(checks) {
        let check_points: Vec<u32> = check.occupied().map(|(_, _, index)| index).collect();
        secured.push(secure_points(
            points,
            &check_points,
            frame,
            domain,
            surface,
            *side,
        )?);
    }
    let mut sides: Vec<(Side, &mut UniformCubicSurface)> =
        surfaces.iter_mut().map(|(side, s)| (*side, s)).collect();
    let certificates = certify_sides(points, frame, domain, &mut sides, tile_of)?;
    Ok(surfaces
        .into_iter()
        .zip(certificates)
        .zip(secured)
        .map(|(((side, surface), mut certificate), secured)| {
            certificate.corrected_points += secured;
            SafeSurface {
                side,
                surface,
                certificate,
            }
        })
        .collect())
}

/// How much finer than the candidates' sub-cells the check points' sub-cells are:
/// twice (each candidate sub-cell split in four) while that leaves two points per
/// check sub-cell on average, else the candidates themselves. Finer check points
/// catch more of what certification would otherwise correct, but their arrays
/// (one per thread) must stay small next to the cloud, and a sparse cloud has
/// few points besides its candidates anyway. A power of two, so the candidates
/// follow from the check points exactly (`SubCellMaxima::coarsen`).
fn check_factor(points: usize, cells: usize, sub: usize) -> usize {
    if 2 * cells * (2 * sub) * (2 * sub) <= points {
        2
    } else {
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Sides;

    fn cloud(n: usize) -> Vec<[f32; 3]> {
        (0..n)
            .map(|i| {
                let a = i as f32 * 0.618_034;
                let (x, y) = ((a * 1.3).sin() * 2.0, (a * 0.7).cos() * 1.5);
                [
                    x,
                    y,
                    (x * 1.7).sin() * (y * 1.1).cos() + 0.1 * (a * 13.0).sin(),
                ]
            })
            .collect()
    }

    /// Same input, same output bits, however many threads share the work.
    #[test]
    fn fits_are_independent_of_the_thread_count() {
        let points = cloud(40_000);
        for sides in [Sides::Upper, Sides::Sandwich] {
            let options = FitOptions {
                sides,
                ..Default::default()
            };
            let fit_with = |threads: usize| {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                pool.install(|| format!("{:?}", fit_surrogate(&points, &options).unwrap()))
            };
            let one = fit_with(1);
            assert_eq!(one, fit_with(2));
            assert_eq!(one, fit_with(3));
        }
    }

    /// A warm-started sequence too: the state a frame leaves is the same
    /// bits whatever the thread count, so a replayed stream of clouds gives
    /// the recorded surrogates (README, "Record and replay").
    #[test]
    fn warm_started_sequences_are_independent_of_the_thread_count() {
        let base = cloud(20_000);
        let frames: Vec<Vec<[f32; 3]>> = (0..4)
            .map(|k| {
                let dz = 0.05 * k as f32;
                base.iter()
                    .map(|p| [p[0], p[1], p[2] + dz * p[0]])
                    .collect()
            })
            .collect();
        let options = FitOptions {
            sides: Sides::Sandwich,
            ..Default::default()
        };
        let fit_with = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut fitter = SurrogateFitter::new(options.clone()).unwrap();
                frames
                    .iter()
                    .map(|f| format!("{:?}", fitter.fit(f).unwrap()))
                    .collect::<Vec<_>>()
            })
        };
        assert_eq!(fit_with(1), fit_with(3));
    }

    #[test]
    fn check_points_are_finer_only_while_they_are_well_filled() {
        assert_eq!(check_factor(300_000, 19 * 19, 4), 2);
        assert_eq!(check_factor(50_000, 19 * 19, 4), 2);
        assert_eq!(check_factor(30_000, 19 * 19, 4), 1);
        assert_eq!(check_factor(30_000, 59 * 59, 4), 1);
    }

    #[test]
    fn every_point_is_certified_and_the_trim_holds_every_point() {
        let points = cloud(50_000);
        let options = FitOptions {
            sides: Sides::Sandwich,
            ..Default::default()
        };
        let surrogate = fit_surrogate(&points, &options).unwrap();
        let locator = surrogate.domain.locator(&surrogate.frame);
        let mut mask = TrimMask::empty(options.cols - 1, options.rows - 1);
        for p in &points {
            let (s, t, _) = locator.locate_f32(p);
            mask.mark(s, t);
        }
        mask.fill_small_holes(SMALL_HOLE);
        assert_eq!(mask, surrogate.trim);
        for safe in surrogate.surfaces() {
            let c = &safe.certificate;
            assert_eq!((c.points_checked, c.violations), (50_000, 0));
            for p in &points {
                let (s, t, w) = locator.locate_f32(p);
                assert!(safe.side.sign() * (safe.surface.eval(s, t) - w) >= c.min_gap);
            }
        }
    }
}
