//! The parameters of a data point on a multipatch: which patch, and where in
//! its unit square. Locators produce them; the fitter and the foot-point search
//! take them.

/// A data point's parameters: a patch and a point of its unit square.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub face: usize,
    pub u: f64,
    pub v: f64,
}
