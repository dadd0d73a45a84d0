//! An interactive blending session (Zou et al., Section 3): the parent and the
//! child are prepared once (kd-trees, normals, polygon of interest), and every
//! drop or adjustment re-blends from them, fast enough to follow a drag.
//! Committing bakes the current blend into the parent, so that the next drop
//! blends onto the composed scene (compound blending, Section 1, Fig. 11a).

use super::error::BlendError;
use super::merge::{Merged, Source};
use super::pipeline::{blend, BlendParams, BlendReport};
use super::prepared::{Child, Prepared};
use glam::DVec3;
use shroud_msg::{BlendCommand, LocalAdjust};

/// Where the child is: the target point and normal on the parent, and the
/// local adjustment about them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DropState {
    pub p_t: DVec3,
    pub v_t: DVec3,
    pub adjust: LocalAdjust,
}

/// A parent, a child and the blend of the child where the user put it.
#[derive(Debug)]
pub struct BlendSession {
    parent: Prepared,
    child: Child,
    params: BlendParams,
    drop: Option<DropState>,
    adjust: LocalAdjust,
    blended: Option<Merged>,
    commits: usize,
}

impl BlendSession {
    pub fn new(parent: Prepared, child: Child, params: BlendParams) -> Self {
        Self {
            parent,
            child,
            params,
            drop: None,
            adjust: LocalAdjust::default(),
            blended: None,
            commits: 0,
        }
    }

    /// Applies `command`. On success the model has changed and the report of
    /// the new blend is returned (`None` after `Clear` and `Commit`, which blend
    /// nothing). On failure the session is unchanged: a drop that cannot be
    /// blended (off the surface, a region left empty) keeps the last good model.
    pub fn apply(&mut self, command: &BlendCommand) -> Result<Option<BlendReport>, BlendError> {
        match *command {
            BlendCommand::Drop { at, normal } => {
                let (p_t, mut v_t) = self.parent.surface_pair(at, 16)?;
                if let Some(n) = normal {
                    v_t = unit(n)?;
                }
                self.blend_at(DropState {
                    p_t,
                    v_t,
                    adjust: self.adjust,
                })
                .map(Some)
            }
            BlendCommand::Adjust(adjust) => {
                check_adjust(&adjust)?;
                let Some(state) = self.drop else {
                    self.adjust = adjust;
                    return Ok(None);
                };
                let report = self.blend_at(DropState { adjust, ..state })?;
                Ok(Some(report))
            }
            BlendCommand::Clear => {
                self.drop = None;
                self.blended = None;
                Ok(None)
            }
            BlendCommand::Commit => {
                let Some(merged) = self.blended.take() else {
                    return Err(BlendError::NothingDropped);
                };
                self.parent = Prepared::with_normals(merged.points, merged.normals, "blended")?;
                self.drop = None;
                self.commits += 1;
                Ok(None)
            }
        }
    }

    fn blend_at(&mut self, state: DropState) -> Result<BlendReport, BlendError> {
        let placement = self.child.placement(state.p_t, state.v_t, &state.adjust);
        let result = blend(&self.parent, &self.child, &placement, &self.params)?;
        self.drop = Some(state);
        self.adjust = state.adjust;
        self.blended = Some(result.merged);
        Ok(result.report)
    }

    /// Holds `child` from now on and gives back the one it held. A child that
    /// was dropped and not committed is taken away (the model is the parent
    /// again); the local adjustment is kept for the next drop.
    pub fn replace_child(&mut self, child: Child) -> Child {
        self.drop = None;
        self.blended = None;
        std::mem::replace(&mut self.child, child)
    }

    /// The current model: the blend if a child is dropped, else the parent.
    /// Sources say where each point comes from.
    pub fn model(&self) -> (&[DVec3], ModelSources<'_>) {
        match &self.blended {
            Some(m) => (&m.points, ModelSources::Mixed(&m.sources)),
            None => (self.parent.points(), ModelSources::AllParent),
        }
    }

    /// Where the child is, if dropped.
    pub fn drop_state(&self) -> Option<DropState> {
        self.drop
    }

    /// Blends committed into the parent so far.
    pub fn commits(&self) -> usize {
        self.commits
    }
}

/// The commands of `pending` that still matter, in order: a drop followed by
/// another drop, or an adjustment followed by another adjustment, before the
/// next clear or commit, is superseded (a drag sends drops faster than a blend
/// may take; the child ends where the last one put it). Clear and commit are
/// never skipped.
pub fn supersede(pending: &[BlendCommand]) -> Vec<BlendCommand> {
    supersede_indices(pending)
        .into_iter()
        .map(|i| pending[i])
        .collect()
}

/// The positions in `pending` of the commands [`supersede`] keeps, for a
/// caller that carries more with each command (which part a drop pastes).
pub fn supersede_indices(pending: &[BlendCommand]) -> Vec<usize> {
    let is_barrier = |c: &BlendCommand| matches!(c, BlendCommand::Clear | BlendCommand::Commit);
    let same_kind =
        |a: &BlendCommand, b: &BlendCommand| std::mem::discriminant(a) == std::mem::discriminant(b);
    (0..pending.len())
        .filter(|&i| {
            let c = &pending[i];
            is_barrier(c)
                || !pending[i + 1..]
                    .iter()
                    .take_while(|later| !is_barrier(later))
                    .any(|later| same_kind(c, later))
        })
        .collect()
}

/// The sources of a session's model.
#[derive(Debug, Clone, Copy)]
pub enum ModelSources<'a> {
    AllParent,
    Mixed(&'a [Source]),
}

impl ModelSources<'_> {
    pub fn get(&self, i: usize) -> Source {
        match self {
            Self::AllParent => Source::Parent,
            Self::Mixed(s) => s.get(i).copied().unwrap_or(Source::Parent),
        }
    }
}

fn unit(v: DVec3) -> Result<DVec3, BlendError> {
    let n = v.normalize_or_zero();
    if n == DVec3::ZERO || !n.is_finite() {
        return Err(BlendError::InvalidParameter {
            name: "normal",
            value: v.length(),
            reason: "the normal must be a finite non-zero vector",
        });
    }
    Ok(n)
}

fn check_adjust(adjust: &LocalAdjust) -> Result<(), BlendError> {
    for (name, value) in [
        ("lift", adjust.lift),
        ("spin", adjust.spin),
        ("tilt", adjust.tilt[0]),
        ("tilt", adjust.tilt[1]),
    ] {
        if !value.is_finite() {
            return Err(BlendError::InvalidParameter {
                name,
                value,
                reason: "must be finite",
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn drop_at(x: f64) -> BlendCommand {
        BlendCommand::Drop {
            at: DVec3::new(x, 0.0, 0.0),
            normal: None,
        }
    }

    fn adjust(spin: f64) -> BlendCommand {
        BlendCommand::Adjust(LocalAdjust {
            spin,
            ..Default::default()
        })
    }

    #[test]
    fn later_drops_and_adjustments_supersede_earlier_ones_up_to_a_barrier() {
        use BlendCommand::{Clear, Commit};
        let pending = [
            drop_at(1.0),
            adjust(0.1),
            drop_at(2.0),
            adjust(0.2),
            drop_at(3.0),
            Commit,
            drop_at(4.0),
            drop_at(5.0),
            Clear,
            adjust(0.3),
        ];
        assert_eq!(
            supersede(&pending),
            vec![
                adjust(0.2),
                drop_at(3.0),
                Commit,
                drop_at(5.0),
                Clear,
                adjust(0.3)
            ]
        );
        assert!(supersede(&[]).is_empty());
    }
}
