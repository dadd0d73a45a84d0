//! Several views of one cloud, combined per shape.
//!
//! Each view's sandwich contains the whole cloud (every point lies in every
//! view's domain), so each view's clearance of a shape is a lower bound on the
//! shape's distance to the cloud, whether or not the shape's reach stays in
//! that view's domain: the largest bound holds, and it is much tighter than one
//! top-down sandwich beside vertical faces. A shape is unobserved when its
//! reach leaves every view's domain: no view says anything about the space
//! there, which the cloud may simply not have seen.

use crate::guard::report::summarise;
use crate::guard::{GuardConfig, GuardReport, ShapeClearance};

/// One fresh view's report and how far obstacles may have moved since its
/// cloud was taken.
pub(super) struct ViewReport {
    pub report: GuardReport,
    pub allowance: f64,
}

/// The combined report: per shape the best bound over the views, after each
/// view's motion allowance, flagged `leaves_domain` when its reach leaves
/// every view's domain.
pub(super) fn combine(
    views: &[ViewReport],
    link_count: usize,
    config: &GuardConfig,
) -> GuardReport {
    let shapes = views.first().map_or(0, |v| v.report.shapes.len());
    let combined = (0..shapes)
        .map(|i| {
            let per_view = views.iter().map(|v| (&v.report.shapes[i], v.allowance));
            ShapeClearance {
                link: views[0].report.shapes[i].link,
                clearance: per_view
                    .clone()
                    .map(|(s, allowance)| (s.clearance - allowance).max(0.0))
                    .fold(0.0, f64::max),
                leaves_domain: per_view.clone().all(|(s, _)| s.leaves_domain),
            }
        })
        .collect();
    summarise(combined, link_count, config)
}
