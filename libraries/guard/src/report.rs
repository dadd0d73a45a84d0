//! The guard's verdict for a whole arm: clearance per shape and per link, the
//! closest link, and whether to stop.

use super::config::GuardConfig;
use super::envelope::Envelope;
use super::error::GuardError;
use super::kinematics::ArmPose;
use super::shape::WorldShape;
use serde::{Deserialize, Serialize};

/// One shape's result. Every distance is in `[0, max_report]`
/// (`max_report` means "at least that"; a view of a cloud with a position
/// error is checked with `max_report` raised by it, so its `occupied` and
/// `unseen` may reach that raised cap).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShapeClearance {
    /// The link carrying the shape.
    pub link: usize,
    /// The bound the verdict uses: a lower bound on the distance to anything
    /// the view could hold, `min(occupied, unseen)` for one view (the
    /// guard's combination of views and its policy may differ).
    pub clearance: f64,
    /// Lower bound on the distance to the occupied region the view saw.
    pub occupied: f64,
    /// Lower bound on the distance to space the view did not see: outside
    /// its domain and over trimmed triangles at every height, outside its
    /// stated field of view, along its stated rays without a return.
    pub unseen: f64,
    /// The bound is set by unseen space (for combined views: in every view
    /// that vouches for the shape): an obstacle there was not seen, only
    /// not excluded.
    pub unobserved: bool,
}

impl ShapeClearance {
    /// One view's result for a shape: the bound is the nearer of what it saw
    /// occupied and what it did not see.
    pub fn of_view(link: usize, occupied: f64, unseen: f64) -> Self {
        Self {
            link,
            clearance: occupied.min(unseen),
            occupied,
            unseen,
            unobserved: unseen < occupied,
        }
    }
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
    /// Every shape below the stop distance is there because of unseen space
    /// alone (see [`ShapeClearance::unobserved`]): the verdict is `unobserved`
    /// rather than `stop`. False when nothing is below it.
    pub unobserved: bool,
}

impl GuardReport {
    /// Combines the verdicts of the same shapes against two envelopes by the
    /// smaller bound per shape (always sound, and the tightest choice when each
    /// envelope holds a different part of the scene). The guard's views
    /// combine the other way, by the larger bound, which is sound because each
    /// view's bound counts the space it did not see (`CollisionGuard`). `None`
    /// when the two reports are of different arms.
    pub fn merged(&self, other: &GuardReport, config: &GuardConfig) -> Option<GuardReport> {
        if self.shapes.len() != other.shapes.len() || self.links.len() != other.links.len() {
            return None;
        }
        let shapes = self
            .shapes
            .iter()
            .zip(&other.shapes)
            .map(|(a, b)| if b.clearance < a.clearance { *b } else { *a })
            .collect();
        Some(summarise(shapes, self.links.len(), config))
    }
}

/// Checks every shape of an arm pose (from [`crate::ArmModel::forward`]).
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
    check_shapes_counting(envelope, shapes, link_count, config, false)
}

/// [`check_shapes`], where `unseen_counts` says that the caller counts
/// unseen space as occupied (`UnobservedPolicy::Stop`). Then what the view
/// saw occupied is searched only up to just beyond its unseen bound, so a
/// shape that lies outside the view (a sector's, say) costs almost nothing.
/// Where the clearance (the nearer of the two) reaches the stop distance, it
/// and whether unseen space set it are the same as with the full search;
/// below the stop distance the clearance may be lower and its cause may be
/// named `occupied` instead (cells are not refined there), which stops the
/// arm all the same. The `occupied` distance is capped there.
pub(crate) fn check_shapes_counting(
    envelope: &Envelope,
    shapes: &[WorldShape],
    link_count: usize,
    config: &GuardConfig,
    unseen_counts: bool,
) -> Result<GuardReport, GuardError> {
    config.validate()?;
    validate_shapes(shapes, link_count)?;
    let results = shape_clearances(envelope, shapes, config, unseen_counts);
    Ok(summarise(results, link_count, config))
}

/// Refuses a shape carried by no link of `0..link_count`, or not valid
/// (the first such, in order).
pub(crate) fn validate_shapes(shapes: &[WorldShape], link_count: usize) -> Result<(), GuardError> {
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
    Ok(())
}

/// The per-shape results of [`check_shapes_counting`], for shapes and a
/// config already validated.
pub(crate) fn shape_clearances(
    envelope: &Envelope,
    shapes: &[WorldShape],
    config: &GuardConfig,
    unseen_counts: bool,
) -> Vec<ShapeClearance> {
    shapes
        .iter()
        .map(|s| {
            let unseen = envelope.unseen_clearance(&s.shape, config);
            let occupied = if unseen_counts {
                // Anything above `unseen` gives the same minimum and the
                // same `unseen < occupied`.
                let cap = unseen.max(0.0) + UNSEEN_CAP_MARGIN;
                envelope.clearance_up_to(&s.shape, config, cap)
            } else {
                envelope.clearance_unchecked(&s.shape, config)
            };
            ShapeClearance::of_view(s.link, occupied, unseen)
        })
        .collect()
}

/// How far past a view's unseen bound its occupied bound is still searched
/// (m): any positive margin keeps `unseen < occupied` exact.
const UNSEEN_CAP_MARGIN: f64 = 1e-6;

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
    let below = |s: &&ShapeClearance| s.clearance < config.stop_distance || s.clearance <= 0.0;
    let stop = min_clearance < config.stop_distance || min_clearance <= 0.0;
    GuardReport {
        closest_link: closest.map(|(i, _)| shapes[i].link),
        closest_shape: closest.map(|(i, _)| i),
        stop,
        unobserved: stop && shapes.iter().filter(below).all(|s| s.unobserved),
        min_clearance,
        links,
        shapes,
    }
}
