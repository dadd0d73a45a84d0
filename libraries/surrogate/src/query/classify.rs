//! Where a world point lies relative to the surfaces of a surrogate. Heights come
//! from the locator and `UniformCubicSurface::eval`, the exact operations of the
//! certificate, so every certified cloud point classifies on its promised side:
//! below an upper surface, above a lower one, between a sandwich.

use super::kept::kept_closed;
use super::view::{Present, SideView, SurrogateView};
use crate::Side;
use glam::DVec3;

/// A point's place along the frame's `w` axis. Gaps are `>= 0` frame-`w` distances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PointClass {
    /// The projection misses the parameter domain.
    OutsideDomain,
    /// The projection falls in a trimmed-out triangle: no surface there.
    Trimmed,
    /// Strictly above the topmost present surface (toward the viewer).
    Above { gap: f64 },
    /// Strictly below the bottom-most present surface; for a lone upper surface
    /// also on it (`gap = 0`), the side the certificate promises.
    Below { gap: f64 },
    /// Sandwich only: `lower <= w <= upper`.
    Between { above_lower: f64, below_upper: f64 },
}

/// Classification of world points.
pub trait Classify {
    fn classify(&self, p: DVec3) -> PointClass;
}

impl Classify for SideView<'_> {
    fn classify(&self, p: DVec3) -> PointClass {
        let (s, t, w) = self.locate(p);
        if let Err(class) = place(self, s, t) {
            return class;
        }
        against(w, Heights::of(self.side(), self.surface().eval(s, t)))
    }
}

impl Classify for SurrogateView<'_> {
    fn classify(&self, p: DVec3) -> PointClass {
        let any = self.any();
        let (s, t, w) = any.locate(p);
        if let Err(class) = place(&any, s, t) {
            return class;
        }
        let heights = match self.present() {
            Present::Sandwich { upper, lower } => Heights::Both {
                upper: upper.surface().eval(s, t),
                lower: lower.surface().eval(s, t),
            },
            Present::One(one) => Heights::of(one.side(), one.surface().eval(s, t)),
        };
        against(w, heights)
    }
}

/// `Ok` when `(s, t)` is in the domain and kept, otherwise the class saying why not.
#[inline]
fn place(view: &SideView, s: f64, t: f64) -> Result<(), PointClass> {
    if !view.domain().contains_param(s, t) {
        Err(PointClass::OutsideDomain)
    } else if !kept_closed(view.trim(), s, t) {
        Err(PointClass::Trimmed)
    } else {
        Ok(())
    }
}

/// The surface heights over one place.
#[derive(Debug, Clone, Copy)]
enum Heights {
    Upper(f64),
    Lower(f64),
    Both { upper: f64, lower: f64 },
}

impl Heights {
    fn of(side: Side, height: f64) -> Self {
        match side {
            Side::Upper => Heights::Upper(height),
            Side::Lower => Heights::Lower(height),
        }
    }
}

/// Compares a height with the present surfaces. Points exactly on a surface fall
/// on the cloud's side of it (the side certification promises, with gap 0).
/// Should the sandwich cross (the fit prevents it on kept cells), points above
/// the upper surface report `Above` first.
#[inline]
fn against(w: f64, heights: Heights) -> PointClass {
    match heights {
        Heights::Upper(up) | Heights::Both { upper: up, .. } if w > up => {
            PointClass::Above { gap: w - up }
        }
        Heights::Lower(low) | Heights::Both { lower: low, .. } if w < low => {
            PointClass::Below { gap: low - w }
        }
        Heights::Both { upper, lower } => PointClass::Between {
            above_lower: w - lower,
            below_upper: upper - w,
        },
        Heights::Upper(up) => PointClass::Below { gap: up - w },
        Heights::Lower(low) => PointClass::Above { gap: w - low },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_sides_put_points_on_the_surface_on_the_cloud_side() {
        assert_eq!(
            against(1.0, Heights::Upper(1.0)),
            PointClass::Below { gap: 0.0 }
        );
        assert_eq!(
            against(1.5, Heights::Upper(1.0)),
            PointClass::Above { gap: 0.5 }
        );
        assert_eq!(
            against(1.0, Heights::Lower(1.0)),
            PointClass::Above { gap: 0.0 }
        );
        assert_eq!(
            against(0.5, Heights::Lower(1.0)),
            PointClass::Below { gap: 0.5 }
        );
    }

    #[test]
    fn sandwich_classes() {
        assert_eq!(
            against(
                3.0,
                Heights::Both {
                    upper: 2.0,
                    lower: 0.0
                }
            ),
            PointClass::Above { gap: 1.0 }
        );
        assert_eq!(
            against(
                -1.0,
                Heights::Both {
                    upper: 2.0,
                    lower: 0.0
                }
            ),
            PointClass::Below { gap: 1.0 }
        );
        assert_eq!(
            against(
                0.5,
                Heights::Both {
                    upper: 2.0,
                    lower: 0.0
                }
            ),
            PointClass::Between {
                above_lower: 0.5,
                below_upper: 1.5
            }
        );
        assert_eq!(
            against(
                2.0,
                Heights::Both {
                    upper: 2.0,
                    lower: 0.0
                }
            ),
            PointClass::Between {
                above_lower: 2.0,
                below_upper: 0.0
            }
        );
    }
}
