//! Several views, combined per shape.
//!
//! Each view's bound for a shape is the nearer of what it saw occupied and
//! what it did not see (`guard::unseen`), less how far an obstacle may have
//! moved since its cloud was taken and until the verdict expires. Such a bound
//! holds for that view alone, whatever cloud it came from and whatever the
//! other views say, so the largest bound over the views holds too: views of
//! different clouds, of different ages, from different sensors combine
//! soundly. A shape is unobserved when its bound is set by unseen space in
//! every view; under [`UnobservedPolicy::Ignore`] unseen space does not count
//! and views combine as if every cloud had seen everything (sound only when
//! they did).

use super::policy::UnobservedPolicy;
use crate::report::summarise;
use crate::{GuardConfig, GuardReport, ShapeClearance};

/// One fresh view's results per shape and how far obstacles may have moved
/// since its cloud was taken (and until the verdict expires).
pub(super) struct ViewReport {
    pub shapes: Vec<ShapeClearance>,
    pub allowance: f64,
}

/// The combined report: per shape the best bound over the views, after each
/// view's allowance.
pub(super) fn combine(
    views: &[ViewReport],
    link_count: usize,
    config: &GuardConfig,
    policy: UnobservedPolicy,
) -> GuardReport {
    let shapes = views.first().map_or(0, |v| v.shapes.len());
    let combined = (0..shapes)
        .map(|i| {
            let per_view = views
                .iter()
                .map(|v| view_bound(&v.shapes[i], v.allowance, policy));
            per_view.reduce(best_of).expect("at least one view")
        })
        .collect();
    summarise(combined, link_count, config)
}

/// One view's bound for a shape after its allowance; the distances keep
/// what the view measured, the clearance is what the policy counts.
fn view_bound(s: &ShapeClearance, allowance: f64, policy: UnobservedPolicy) -> ShapeClearance {
    let counted = match policy {
        UnobservedPolicy::Stop => s.occupied.min(s.unseen),
        UnobservedPolicy::Ignore => s.occupied,
    };
    ShapeClearance {
        clearance: (counted - allowance).max(0.0),
        ..*s
    }
}

/// The larger bound of two views; unobserved only when both are.
fn best_of(a: ShapeClearance, b: ShapeClearance) -> ShapeClearance {
    let unobserved = a.unobserved && b.unobserved;
    let best = if b.clearance > a.clearance { b } else { a };
    ShapeClearance { unobserved, ..best }
}
