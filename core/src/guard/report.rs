//! The guard's verdict for a whole arm: clearance per shape and per link, the
//! closest link, and whether to stop.

use super::config::GuardConfig;
use super::envelope::Envelope;
use super::error::GuardError;
use super::kinematics::ArmPose;
use super::shape::WorldShape;
use serde::{Deserialize, Serialize};

/// One shape's result.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShapeClearance {
    /// The link carrying the shape.
    pub link: usize,
    /// Lower bound on the distance to the occupied region in the domain, in
    /// `[0, max_report]` (`max_report` means "at least that").
    pub clearance: f64,
    /// The shape's reach (`radius + max_report`) leaves the surrogate's domain:
    /// space there is not represented, so obstacles there are not seen.
    pub leaves_domain: bool,
}

/// The verdict for one arm pose against one envelope.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GuardReport {
    /// Per shape, in the order given.
    pub shapes: Vec<ShapeClearance>,
    /// Per link (index = link index): the smallest clearance of its shapes,
    /// `max_report` for a link without shapes.
    pub links: Vec<f64>,
    /// The smallest clearance of all (`max_report` without shapes).
    pub min_clearance: f64,
    /// Link and shape index of `min_clearance` (the first one on ties); `None`
    /// without shapes.
    pub closest_link: Option<usize>,
    pub closest_shape: Option<usize>,
    /// Some clearance is below `stop_distance`, or is 0 (contact stops even
    /// with `stop_distance = 0`).
    pub stop: bool,
    /// Some shape's reach leaves the domain (see [`ShapeClearance::leaves_domain`]).
    pub leaves_domain: bool,
}

impl GuardReport {
    /// Combines the verdicts of the same shapes against envelopes of
    /// *different* clouds (each holding part of the scene): per shape and link
    /// the smaller clearance wins. Views of one cloud combine the other way,
    /// by the larger bound (`CollisionGuard`). `None` when the two reports are
    /// of different arms.
    pub fn merged(&self, other: &GuardReport, config: &GuardConfig) -> Option<GuardReport> {
        if self.shapes.len() != other.shapes.len() || self.links.len() != other.links.len() {
            return None;
        }
        let shapes = self
            .shapes
            .iter()
            .zip(&other.shapes)
            .map(|(a, b)| ShapeClearance {
                link: a.link,
                clearance: a.clearance.min(b.clearance),
                leaves_domain: a.leaves_domain || b.leaves_domain,
            })
            .collect();
        Some(summarise(shapes, self.links.len(), config))
    }
}

/// Checks every shape of an arm pose (from [`crate::guard::ArmModel::forward`]).
pub fn check_arm(
    envelope: &Envelope,
    pose: &ArmPose,
    config: &GuardConfig,
) -> Result<GuardReport, GuardError> {
    check_shapes(envelope, &pose.shapes, pose.link_count(), config)
}

/// Checks world shapes carried by links `0..link_count`.
pub fn check_shapes(
    envelope: &Envelope,
    shapes: &[WorldShape],
    link_count: usize,
    config: &GuardConfig,
) -> Result<GuardReport, GuardError> {
    config.validate()?;
    for (index, s) in shapes.iter().enumerate() {
        if s.link >= link_count {
            return Err(GuardError::ShapeLink {
                index,
                link: s.link,
                links: link_count,
            });
        }
        if !s.shape.is_valid() {
            return Err(GuardError::BadShape {
                index,
                link: s.link,
            });
        }
    }
    let results = shapes
        .iter()
        .map(|s| ShapeClearance {
            link: s.link,
            clearance: envelope.clearance_unchecked(&s.shape, config),
            leaves_domain: envelope.reach_leaves_domain(&s.shape, config),
        })
        .collect();
    Ok(summarise(results, link_count, config))
}

pub(crate) fn summarise(
    shapes: Vec<ShapeClearance>,
    link_count: usize,
    config: &GuardConfig,
) -> GuardReport {
    let mut links = vec![config.max_report; link_count];
    let mut closest: Option<(usize, f64)> = None;
    for (i, s) in shapes.iter().enumerate() {
        if let Some(l) = links.get_mut(s.link) {
            *l = l.min(s.clearance);
        }
        if closest.is_none_or(|(_, c)| s.clearance < c) {
            closest = Some((i, s.clearance));
        }
    }
    let min_clearance = closest.map_or(config.max_report, |(_, c)| c);
    GuardReport {
        closest_link: closest.map(|(i, _)| shapes[i].link),
        closest_shape: closest.map(|(i, _)| i),
        stop: min_clearance < config.stop_distance || min_clearance <= 0.0,
        leaves_domain: shapes.iter().any(|s| s.leaves_domain),
        min_clearance,
        links,
        shapes,
    }
}
