//! Open-boundary detection on point clouds (the role of Qian et al. 2005 in Zou
//! et al., Section 3.1): the rim of a part, its polygon of interest P_inter.
//! Parts come from users' scans, sampled irregularly and with noise, so:
//! [`criteria`] marks rim candidates by scores normalised by the local spacing
//! (Bendels et al. 2006), [`loops`] orders them into closed loops over a graph
//! that bridges unmarked rim points, and [`diagnosis`] picks the rim or says
//! why there is none.

mod criteria;
mod diagnosis;
mod loops;

pub use criteria::{neighbourhoods, Neighbourhood};
pub use diagnosis::BoundaryFailure;
pub use loops::BoundaryLoop;

use super::neighbours::NeighbourIndex;
use glam::DVec3;

/// Tuning of [`boundary_points`], [`boundary_loops`] and [`find_rim`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryParams {
    /// Neighbours looked at around each point.
    pub k: usize,
    /// Smallest mean of the angle and half-disc probabilities (each in [0, 1])
    /// that makes a point a rim candidate.
    pub min_score: f64,
    /// Candidates closer than this many times the larger of their
    /// neighbourhood radii are linked into one rim chain (bridging rim points
    /// the criteria missed).
    pub link: f64,
    /// Rim chains with fewer candidates are dropped (sampling gaps, noise).
    pub min_loop_points: usize,
    /// A second loop at least this fraction of the longest one's length makes
    /// the rim ambiguous ([`BoundaryFailure::SeveralLoops`]).
    pub ambiguous_ratio: f64,
    /// More than this fraction of the points as candidates means the cloud is
    /// too sparse for its neighbourhoods ([`BoundaryFailure::TooSparse`]).
    pub max_candidate_fraction: f64,
    /// A median k-neighbourhood radius above this fraction of the cloud's
    /// bounding-box diagonal also means too sparse (the part is only a few
    /// neighbourhoods across).
    pub max_reach: f64,
}

impl Default for BoundaryParams {
    fn default() -> Self {
        Self {
            k: 20,
            min_score: 0.8,
            link: 2.0,
            min_loop_points: 12,
            ambiguous_ratio: 0.75,
            max_candidate_fraction: 0.4,
            max_reach: 0.15,
        }
    }
}

/// What the detection saw, shared by the public entry points.
struct Analysis {
    neighbourhoods: Vec<Neighbourhood>,
    /// Candidates as (index, neighbourhood radius).
    candidates: Vec<(usize, f64)>,
    /// Connected chains of candidates with at least `min_loop_points`.
    pieces: Vec<Vec<(usize, f64)>>,
    /// Candidates in the longest chain (dropped ones included).
    longest_piece: usize,
}

fn analyse(index: &NeighbourIndex, params: &BoundaryParams) -> Analysis {
    let neighbourhoods = neighbourhoods(index, params.k);
    let candidates: Vec<(usize, f64)> = neighbourhoods
        .iter()
        .enumerate()
        .filter(|(_, n)| n.score >= params.min_score)
        .map(|(i, n)| (i, n.radius))
        .collect();
    let mut pieces = loops::rim_pieces(index.points(), &candidates, params.link);
    let longest_piece = pieces.iter().map(Vec::len).max().unwrap_or(0);
    pieces.retain(|p| p.len() >= params.min_loop_points.max(4));
    Analysis {
        neighbourhoods,
        candidates,
        pieces,
        longest_piece,
    }
}

impl Analysis {
    /// Closed loops of the chains, longest first.
    fn loops(&self, points: &[DVec3], link: f64) -> Vec<BoundaryLoop> {
        let mut loops: Vec<BoundaryLoop> = self
            .pieces
            .iter()
            .filter_map(|piece| loops::close_loop(points, piece, link))
            .collect();
        loops.sort_by(|a, b| b.length.total_cmp(&a.length));
        loops
    }
}

/// Marks the rim candidates of `index` (see [`criteria`]).
pub fn boundary_points(index: &NeighbourIndex, params: &BoundaryParams) -> Vec<bool> {
    neighbourhoods(index, params.k)
        .iter()
        .map(|n| n.score >= params.min_score)
        .collect()
}

/// Every closed loop of rim candidates, longest first.
pub fn boundary_loops(index: &NeighbourIndex, params: &BoundaryParams) -> Vec<BoundaryLoop> {
    analyse(index, params).loops(index.points(), params.link)
}

/// The rim of the cloud in `index`: its longest open-boundary loop, unless the
/// cloud is too sparse, has no gap, has rim pieces that do not close, or has
/// several loops of similar length; each is a [`BoundaryFailure`] with its
/// numbers.
pub fn find_rim(
    index: &NeighbourIndex,
    params: &BoundaryParams,
) -> Result<BoundaryLoop, BoundaryFailure> {
    let analysis = analyse(index, params);
    let points = index.len();
    let candidates = analysis.candidates.len();
    let reach = reach(index, &analysis);
    if candidates as f64 > params.max_candidate_fraction * points as f64 || reach > params.max_reach
    {
        return Err(too_sparse(index.len(), candidates, reach, params));
    }
    if analysis.pieces.is_empty() {
        return Err(BoundaryFailure::NoGap {
            points,
            candidates,
            longest: analysis.longest_piece,
            min: params.min_loop_points,
        });
    }
    diagnosis::choose_rim(analysis.loops(index.points(), params.link), params)?.ok_or(
        BoundaryFailure::OpenRim {
            candidates,
            pieces: analysis.pieces.len(),
            longest: analysis.longest_piece,
            min: params.min_loop_points,
            k: params.k,
        },
    )
}

/// The neighbourhood reach a cloud should have for its rim to show: 5 % of its
/// size (a 6,000-point hemisphere has 2.7 % at k = 20).
const COMFORTABLE_REACH: f64 = 0.05;

/// Median k-neighbourhood radius over the bounding-box diagonal (1 when the
/// cloud has no extent).
fn reach(index: &NeighbourIndex, analysis: &Analysis) -> f64 {
    let (low, high) = index.points().iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let size = low.distance(high);
    let mut radii: Vec<f64> = analysis.neighbourhoods.iter().map(|n| n.radius).collect();
    let mid = radii.len() / 2;
    if radii.is_empty() || !(size > 0.0) {
        1.0
    } else {
        *radii.select_nth_unstable_by(mid, f64::total_cmp).1 / size
    }
}

fn too_sparse(
    points: usize,
    candidates: usize,
    reach: f64,
    params: &BoundaryParams,
) -> BoundaryFailure {
    // The k-neighbourhood's radius shrinks like 1 / sqrt(points) on a surface.
    let scale = (reach / COMFORTABLE_REACH).powi(2).max(1.0);
    BoundaryFailure::TooSparse {
        points,
        candidates,
        k: params.k,
        reach,
        // Never fewer than a neighbourhood and a rim's worth of points (an
        // empty or tiny cloud would otherwise be told to scan "0 points").
        suggested: ((points as f64 * scale).ceil() as usize)
            .max(params.k + 1)
            .max(params.min_loop_points),
    }
}
