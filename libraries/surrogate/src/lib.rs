//! Safe spline surrogates (Myles & Peters): curve heuristics of Sections 3-5, the
//! surface reduction of Section 6 with trimming, tightening, and certification.

pub mod bins;
mod broken_line;
mod candidates;
mod certify;
mod collinear;
pub mod elevation;
mod error;
mod exact_weights;
mod fitter;
pub mod floor;
mod footprint;
mod lower_bound;
mod model;
mod options;
pub mod query;
mod reduction;
#[doc(hidden)]
pub mod samples;
mod scattered_curve;
mod sectors;
pub mod tight;
mod tighten;
mod trial_and_error;
pub mod trim;
mod uncross;
mod upper_hull;
mod validate;
mod wire;

pub use broken_line::{fit_broken_line_above, BrokenLineFit};
pub use candidates::{candidates_of, Candidate};
pub use certify::{certify_surface, PaddedSurface};
pub use error::{FitError, SurrogateDefect};
pub use fitter::{fit_surrogate, SurrogateFitter, MAX_GRID};
pub use footprint::domain_of_cloud;
pub use lower_bound::{broken_line_lower_bound, negative_differences, scattered_lower_bound};
pub use model::{DomainLocate, Locator, SafeSurface, Sides, Surrogate};
pub use options::{FitOptions, Tightness};
pub use reduction::Orientation;
pub use scattered_curve::{
    fit_curve_above, fit_sorted_candidates_above, hull_per_interval, CurveWarmStart,
    ScatteredCurveFit, DEFAULT_MAX_SOLVES,
};
pub use sectors::{SectorFit, SectorFitError, SectorFitter};
/// The wire vocabulary of a surface, defined with the messages so that a
/// consumer needs no fitter to read them.
pub use shroud_msg::{Certificate, Domain, FitStats, Histogram, Side, DOMAIN_SLACK};
pub use tighten::lower_onto_candidates;
pub use trial_and_error::{fit_curve_by_trial_and_error, TrialAndErrorFit};
pub use trim::TrimMask;
pub use upper_hull::upper_hull;
pub use validate::validate_surrogate;
pub use wire::SurrogateWire;
