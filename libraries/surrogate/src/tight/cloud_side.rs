//! One side of a located cloud: the points, the frame and domain that place them
//! in parameter space, the kept region, and which side a surface must stay on.
//! The common input of the excess-volume measure and the LP reference.

use crate::DomainLocate;
use crate::{Candidate, Domain, Side, Surrogate, TrimMask};
use shroud_geometry::math::Frame;

#[derive(Debug, Clone, Copy)]
pub struct CloudSide<'a> {
    pub points: &'a [[f32; 3]],
    pub frame: &'a Frame,
    pub domain: &'a Domain,
    pub trim: &'a TrimMask,
    pub side: Side,
}

impl<'a> CloudSide<'a> {
    /// The cloud a surrogate was fitted to, seen from `side`.
    pub fn of(surrogate: &'a Surrogate, points: &'a [[f32; 3]], side: Side) -> Self {
        Self {
            points,
            frame: &surrogate.frame,
            domain: &surrogate.domain,
            trim: &surrogate.trim,
            side,
        }
    }

    /// Every point as a constraint `f(s, t) >= side.sign() * w` (upper sense).
    pub fn constraints(&self) -> impl Iterator<Item = Candidate> + '_ {
        let locator = self.domain.locator(self.frame);
        let sign = self.side.sign();
        self.points.iter().map(move |p| {
            let (s, t, w) = locator.locate_f32(p);
            Candidate {
                s,
                t,
                height: sign * w,
            }
        })
    }
}
