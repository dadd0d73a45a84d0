//! A cloud's sectors, each fitted along its own axis into a surrogate that
//! states its sector as its field of view (`shroud_geometry::cloud::sector`).
//!
//! A surrogate along the axis of a wide perspective view counts the space
//! that a solid's top shades along that axis as occupied, though the
//! sensor's rays crossed it beside the solid; along a sector's axis the
//! shading strays from the rays by at most the sector's half angle. Each
//! sector's surrogate holds for what its cone saw and states everything
//! outside it as unseen, so a guard may take the best bound of the whole view
//! and its sectors, shape by shape.

use super::fitter::SurrogateFitter;
use super::{FitError, FitOptions, Surrogate};
use shroud_geometry::cloud::{
    check_sectors, no_return_in_sector, points_in_sector, sector, SectorError,
};
use shroud_msg::{FieldOfView, NoReturn};

/// One sector's surrogate and what it states besides its surfaces.
#[derive(Debug, Clone)]
pub struct SectorFit {
    pub surrogate: Surrogate,
    /// The sector's cone: outside it the surrogate says nothing.
    pub field_of_view: FieldOfView,
    /// The cloud's cones of empty rays that reach into the sector.
    pub no_return: Option<NoReturn>,
}

/// Why a sector was not fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SectorFitError {
    #[error("sector: {0}")]
    Sector(#[from] SectorError),
    #[error("sector {index}: {error}")]
    Fit { index: usize, error: FitError },
}

/// Fits the `grid x grid` sectors of clouds that state their field of view,
/// each along its own axis with the shape of `options` (its direction aside),
/// warm-started from the same sector of the previous cloud while the sensor
/// stays where it was.
#[derive(Debug)]
pub struct SectorFitter {
    grid: usize,
    reach: f64,
    options: FitOptions,
    /// Per sector: the axis its fitter looks along, and the fitter.
    fitters: Vec<Option<([f64; 3], SurrogateFitter)>>,
    points: Vec<[f32; 3]>,
}

impl SectorFitter {
    /// Refuses a grid outside `1..=MAX_SECTOR_GRID`, a reach below 1 and
    /// options no fitter accepts.
    pub fn new(grid: usize, reach: f64, options: FitOptions) -> Result<Self, SectorFitError> {
        check_sectors(grid, reach)?;
        SurrogateFitter::new(options.clone())
            .map_err(|error| SectorFitError::Fit { index: 0, error })?;
        Ok(Self {
            grid,
            reach,
            options,
            fitters: (0..grid * grid).map(|_| None).collect(),
            points: Vec::new(),
        })
    }

    /// How many sectors a cloud has: `grid x grid`.
    pub fn count(&self) -> usize {
        self.fitters.len()
    }

    /// Sector `index` of a cloud of `points` whose sensor stated `fov` and
    /// `no_return`: `Ok(None)` when no point lies in it, an error when the
    /// sector has no room in `fov` or its points cannot be fitted.
    pub fn fit(
        &mut self,
        index: usize,
        fov: &FieldOfView,
        no_return: Option<&NoReturn>,
        points: &[[f32; 3]],
    ) -> Result<Option<SectorFit>, SectorFitError> {
        let part = sector(fov, self.grid, index, self.reach)?;
        self.points.clear();
        points_in_sector(&part, points, &mut self.points);
        if self.points.is_empty() {
            return Ok(None);
        }
        let fit_error = |error| SectorFitError::Fit { index, error };
        let slot = &mut self.fitters[index];
        if slot.as_ref().is_none_or(|(axis, _)| *axis != part.axis) {
            let options = FitOptions {
                direction: part.axis,
                ..self.options.clone()
            };
            *slot = Some((part.axis, SurrogateFitter::new(options).map_err(fit_error)?));
        }
        let Some((_, fitter)) = slot.as_mut() else {
            unreachable!("the slot was filled above")
        };
        let surrogate = fitter.fit(&self.points).map_err(fit_error)?;
        Ok(Some(SectorFit {
            surrogate,
            field_of_view: part,
            no_return: no_return.map(|n| no_return_in_sector(&part, n)),
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Sides;
    use glam::DVec3;
    use shroud_msg::Aperture;

    /// A floor at z = 0 seen from (0, 0, 2) through a cone of 0.6 rad.
    fn floor_scan() -> (FieldOfView, Vec<[f32; 3]>) {
        let fov = FieldOfView {
            apex: [0.0, 0.0, 2.0],
            axis: [0.0, 0.0, -1.0],
            aperture: Aperture::Cone { half_angle: 0.6 },
            max_range: 4.0,
        };
        let reach = 2.0 * 0.6f64.tan();
        let mut points = Vec::new();
        for i in -40..=40 {
            for j in -40..=40 {
                let (x, y) = (i as f64 * reach / 40.0, j as f64 * reach / 40.0);
                if (x * x + y * y).sqrt() <= reach {
                    points.push([x as f32, y as f32, 0.0]);
                }
            }
        }
        (fov, points)
    }

    fn options() -> FitOptions {
        FitOptions {
            cols: 8,
            rows: 8,
            sides: Sides::Upper,
            ..FitOptions::default()
        }
    }

    #[test]
    fn each_sector_is_fitted_along_its_axis_from_its_own_points() {
        let (fov, points) = floor_scan();
        let mut fitter = SectorFitter::new(2, 1.5, options()).unwrap();
        assert_eq!(fitter.count(), 4);
        for index in 0..4 {
            let fit = fitter.fit(index, &fov, None, &points).unwrap().unwrap();
            let axis = DVec3::from_array(fit.field_of_view.axis);
            let direction = fit.surrogate.frame.direction;
            assert!((direction - axis).length() < 1e-9, "sector {index}");
            assert!(fit.surrogate.stats.points < points.len() as u64);
            assert!(fit.surrogate.stats.points > 100);
            assert!(fit.no_return.is_none());
        }
    }

    #[test]
    fn a_sector_without_points_is_none_and_bad_settings_are_named() {
        let (fov, points) = floor_scan();
        // A fine grid: a cone's corner sectors have no room in it.
        let mut fine = SectorFitter::new(4, 1.5, options()).unwrap();
        assert!(matches!(
            fine.fit(0, &fov, None, &points),
            Err(SectorFitError::Sector(SectorError::NoRoom { .. }))
        ));
        let mut fitter = SectorFitter::new(2, 1.0, options()).unwrap();
        let far: Vec<[f32; 3]> = points.iter().map(|p| [p[0] + 50.0, p[1], p[2]]).collect();
        assert!(fitter.fit(0, &fov, None, &far).unwrap().is_none());
        assert!(matches!(
            SectorFitter::new(9, 1.5, options()),
            Err(SectorFitError::Sector(SectorError::Grid(9)))
        ));
        assert!(matches!(
            SectorFitter::new(2, 0.5, options()),
            Err(SectorFitError::Sector(SectorError::Reach(_)))
        ));
        let tiny = FitOptions {
            cols: 1,
            ..options()
        };
        assert!(matches!(
            SectorFitter::new(2, 1.5, tiny),
            Err(SectorFitError::Fit { .. })
        ));
    }
}
