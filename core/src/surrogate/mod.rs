//! Safe spline surrogates (Myles & Peters): curve heuristics of Sections 3-5, the
//! surface reduction of Section 6 with trimming, tightening, and certification.

pub mod bins;
mod broken_line;
mod candidates;
mod certify;
mod collinear;
mod error;
mod fitter;
mod footprint;
mod lower_bound;
mod model;
mod reduction;
mod scattered_curve;
mod stats;
mod tighten;
mod trial_and_error;
pub mod trim;
mod uncross;
mod upper_hull;

pub use broken_line::{fit_broken_line_above, BrokenLineFit};
pub use candidates::{candidates_of, Candidate};
pub use certify::{certify_surface, PaddedSurface};
pub use error::FitError;
pub use fitter::{fit_surrogate, FitOptions, SurrogateFitter, Tightness, MAX_GRID};
pub use footprint::domain_of_cloud;
pub use lower_bound::{broken_line_lower_bound, negative_differences, scattered_lower_bound};
pub use model::{Certificate, Domain, Locator, SafeSurface, Side, Sides, Surrogate, DOMAIN_SLACK};
pub use reduction::Orientation;
pub use scattered_curve::{
    fit_curve_above, fit_sorted_candidates_above, hull_per_interval, CurveWarmStart,
    ScatteredCurveFit, DEFAULT_MAX_SOLVES,
};
pub use stats::{FitStats, Histogram};
pub use tighten::lower_onto_candidates;
pub use trial_and_error::{fit_curve_by_trial_and_error, TrialAndErrorFit};
pub use trim::TrimMask;
pub use upper_hull::upper_hull;
