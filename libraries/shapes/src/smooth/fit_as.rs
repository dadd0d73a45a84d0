//! One entry point for fitting located points as their parametrisation asks:
//! graphs and radial functions have exact parameters and are fitted once;
//! parametric surfaces are fitted in R^3 with parameter correction, warm-started
//! on an earlier fit when there is one. The command line and the node share it.

use super::error::SmoothError;
use super::fit::{FitErrors, SmoothFitter, SmoothSurface};
use super::parametrisation::Parametrisation;
use super::sample::Sample;
use crate::mesh::{MeshError, QuadMesh};

/// Correction rounds of a parametric fit unless asked otherwise.
pub const DEFAULT_CORRECTIONS: usize = 3;

/// A fit and the errors (28) of each round (one unless corrected).
#[derive(Debug, Clone)]
pub struct FitRounds {
    pub surface: SmoothSurface,
    pub rounds: Vec<FitErrors>,
    /// For parametric fits: the distances at the foot points.
    pub distances: Option<FitErrors>,
}

impl FitRounds {
    /// The errors of the last round.
    pub fn errors(&self) -> FitErrors {
        self.rounds.last().copied().unwrap_or_default()
    }
}

impl Parametrisation {
    /// The correction rounds to run: `asked`, or [`DEFAULT_CORRECTIONS`] for a
    /// parametric fit; graphs and radial functions take none (asking for some
    /// is an error: their parameters are exact).
    pub fn corrections(&self, asked: Option<usize>) -> Result<usize, SmoothError> {
        match (asked, self) {
            (None, Self::Parametric(_)) => Ok(DEFAULT_CORRECTIONS),
            (Some(k), Self::Parametric(_)) => Ok(k),
            (None | Some(0), _) => Ok(0),
            (Some(_), p) => Err(SmoothError::ExactParameters { kind: p.kind() }),
        }
    }

    /// `surface` as a quad mesh over `domain`, placed as this parametrisation
    /// places values (`n` x `n` quads per patch).
    pub fn tessellate(
        &self,
        surface: &SmoothSurface,
        domain: &QuadMesh,
        n: usize,
    ) -> Result<QuadMesh, MeshError> {
        match self {
            Self::Graph(_) => surface.tessellate_graph(domain, n),
            Self::Radial(_) => surface.tessellate_radial(domain, n),
            Self::Parametric(_) => surface.tessellate_parametric(domain, n),
        }
    }
}

impl SmoothFitter {
    /// Fits `values` at `samples` (from `parametrisation`) with smoothing
    /// `lambda`; a parametric fit runs `corrections` rounds, starting from
    /// `warm` (an earlier fit of the same object) when given.
    pub fn fit_as(
        &self,
        parametrisation: &Parametrisation,
        samples: &[Sample],
        values: &[f64],
        (lambda, corrections): (f64, usize),
        warm: Option<&SmoothSurface>,
    ) -> Result<FitRounds, SmoothError> {
        if let Parametrisation::Parametric(_) = parametrisation {
            let fit = match warm {
                Some(previous) => {
                    self.fit_parametric_warm(previous, samples, values, lambda, corrections)?
                }
                None => self.fit_parametric(samples, values, lambda, corrections)?,
            };
            return Ok(FitRounds {
                surface: fit.surface,
                rounds: fit.rounds,
                distances: Some(fit.distances),
            });
        }
        let surface = self.fit(samples, values, 1, lambda)?;
        let rounds = vec![surface.errors(samples, values)];
        Ok(FitRounds {
            surface,
            rounds,
            distances: None,
        })
    }
}
