//! Dark cones (`guard::no_return`) gathered into a tree of nearby
//! directions: the root holds every cone, each node is halved at the median
//! of its axes until a leaf holds at most [`LEAF_SIZE`], and every node has a
//! bounding cone from the same apex over all its members, so that a sphere no
//! nearer to a node's bounding cone than its bound so far skips every member
//! below it at once: a few tests where there were hundreds. Built once
//! per cloud, with its list of rays without a return.
//!
//! Why the bounding cone holds its members: a direction within `alpha_k` of
//! a member's axis `a_k` is within `angle(a, a_k) + alpha_k` of the node's
//! axis `a` (the triangle inequality for angles), so the cone of half angle
//! `max_k (angle(a, a_k) + alpha_k)`, padded by [`ANGLE_PAD`], contains
//! every member cone, and the distance to it is at most the distance to any
//! of them. Each node's cone is computed from its members themselves, never
//! from its halves' cones, so a deep node is no looser for being deep. The
//! cone formula loses at worst a few times `sqrt(eps)` of the distance to
//! the apex to rounding (near a cone's axis), far less than the
//! [`ROUNDING_REL`] allowance a node's distance is reduced by, so a skipped
//! member could not have lowered the computed minimum.

use glam::DVec3;

/// Most members of a leaf: nodes are halved until they hold no more.
pub(crate) const LEAF_SIZE: usize = 8;

/// Padding of a node's half angle (rad) against the rounding of the angles.
const ANGLE_PAD: f64 = 1e-6;

/// A node's cone is used only below this half angle (rad): the distance
/// formula needs less than a right angle.
const MAX_BOUND_ANGLE: f64 = 1.5;

/// Rounding allowance of a node's distance, relative to the distance from
/// the apex (plus one unit).
pub(crate) const ROUNDING_REL: f64 = 1e-6;

/// A cone from the common apex: unit axis, sine and cosine of its half angle.
pub(crate) type Cone = (DVec3, f64, f64);

/// One node of the tree: its members' range in the tree's order, its
/// bounding cone unless the members spread too wide for one, and its two
/// halves (indices in the tree) unless it is a leaf.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ConeNode {
    pub members: [usize; 2],
    pub bound: Option<Cone>,
    pub halves: Option<[usize; 2]>,
}

/// The cones' indices in the tree's order and the tree over that order, its
/// root first (one node, without members, when there are no cones).
pub(crate) fn cone_tree(cones: &[Cone]) -> (Vec<usize>, Vec<ConeNode>) {
    let mut order: Vec<usize> = (0..cones.len()).collect();
    let mut nodes = Vec::new();
    build(cones, &mut order, 0, &mut nodes);
    (order, nodes)
}

/// How many nodes the longest way from the root to a leaf passes.
pub(crate) fn tree_depth(nodes: &[ConeNode]) -> usize {
    let mut depth = vec![0; nodes.len()];
    // Halves come after their node.
    for (index, node) in nodes.iter().enumerate() {
        depth[index] = depth[index].max(1);
        for half in node.halves.into_iter().flatten() {
            depth[half] = depth[index] + 1;
        }
    }
    depth.into_iter().max().unwrap_or(0)
}

/// Adds the node of `members` (starting at `start` in the order) and, unless
/// it is small enough to be a leaf, its halves split at the median of the
/// axes' coordinate that spreads most; returns its index.
fn build(cones: &[Cone], members: &mut [usize], start: usize, nodes: &mut Vec<ConeNode>) -> usize {
    let at = nodes.len();
    nodes.push(ConeNode {
        members: [start, start + members.len()],
        bound: bounding_cone(cones, members),
        halves: None,
    });
    if members.len() <= LEAF_SIZE {
        return at;
    }
    let spread = |k: usize| {
        let (lo, hi) = members
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &i| {
                (lo.min(cones[i].0[k]), hi.max(cones[i].0[k]))
            });
        hi - lo
    };
    let widest = (1..3).fold(0, |w, k| if spread(k) > spread(w) { k } else { w });
    members.sort_unstable_by(|&a, &b| cones[a].0[widest].total_cmp(&cones[b].0[widest]));
    let half = members.len() / 2;
    let (left, right) = members.split_at_mut(half);
    let left = build(cones, left, start, nodes);
    let right = build(cones, right, start + half, nodes);
    nodes[at].halves = Some([left, right]);
    at
}

/// The cone around the members' mean axis that holds them all, or `None`
/// when it would reach [`MAX_BOUND_ANGLE`] (or the axes cancel out).
fn bounding_cone(cones: &[Cone], members: &[usize]) -> Option<Cone> {
    let axis = members
        .iter()
        .map(|&i| cones[i].0)
        .sum::<DVec3>()
        .try_normalize()?;
    let half_angle = members
        .iter()
        .map(|&i| {
            let (a, sin, cos) = cones[i];
            a.cross(axis).length().atan2(a.dot(axis)) + sin.atan2(cos)
        })
        .fold(0.0f64, f64::max)
        + ANGLE_PAD;
    (half_angle < MAX_BOUND_ANGLE).then(|| {
        let (sin, cos) = half_angle.sin_cos();
        (axis, sin, cos)
    })
}

/// Distance from `p` to the cone `(axis, sin, cos)` from `apex` (half angle
/// below a right angle): 0 inside, the distance to the apex behind it, to
/// the lateral surface between.
#[inline]
pub(crate) fn cone_distance(apex: DVec3, cone: Cone, p: DVec3) -> f64 {
    let d = p - apex;
    cone_distance_at(d, d.length_squared(), cone)
}

/// [`cone_distance`] of the point `d` away from the apex, given `d2`, its
/// squared length (`d.length()` is its root): a search of many cones from
/// one point computes both once. The same operations, so the same bits.
#[inline]
pub(crate) fn cone_distance_at(d: DVec3, d2: f64, cone: Cone) -> f64 {
    cone_distance_and_side(d, d2, cone).0
}

/// [`cone_distance_at`], and how far the point lies off the cone's lateral
/// surface (negative inside, the deeper the lower): a search orders by it
/// where the distances are all 0.
#[inline]
pub(crate) fn cone_distance_and_side(d: DVec3, d2: f64, (axis, sin, cos): Cone) -> (f64, f64) {
    let along = d.dot(axis);
    let across = (d2 - along * along).max(0.0).sqrt();
    let side = across * cos - along * sin;
    let distance = if across * cos <= along * sin {
        0.0
    } else if along * cos + across * sin <= 0.0 {
        d2.sqrt()
    } else {
        side
    };
    (distance, side)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field_of_view::tests::random_unit;
    use rand::{Rng, SeedableRng};

    /// Every member cone lies in its node's bounding cone: directions on a
    /// member's rim are inside the node's (with its padding to spare); the
    /// leaves hold every cone once, and a node's halves split its members.
    #[test]
    fn nodes_hold_their_members() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(9);
        for _ in 0..40 {
            let centre = random_unit(&mut rng);
            let n = rng.random_range(1..200);
            let cones: Vec<Cone> = (0..n)
                .map(|_| {
                    let axis =
                        (centre + random_unit(&mut rng) * rng.random_range(0.0..0.8)).normalize();
                    let (sin, cos) = rng.random_range(0.001..0.3f64).sin_cos();
                    (axis, sin, cos)
                })
                .collect();
            let (order, nodes) = cone_tree(&cones);
            let mut seen: Vec<usize> = order.clone();
            seen.sort();
            assert_eq!(seen, (0..n).collect::<Vec<_>>());
            assert_eq!(nodes[0].members, [0, n]);
            // Halved at every level down to leaves of at most LEAF_SIZE.
            let most = 1 + (n as f64 / LEAF_SIZE as f64).log2().ceil().max(0.0) as usize;
            assert!((1..=most).contains(&tree_depth(&nodes)), "{n}");
            for node in &nodes {
                match node.halves {
                    None => assert!(node.members[1] - node.members[0] <= LEAF_SIZE),
                    Some([a, b]) => {
                        assert_eq!(nodes[a].members[0], node.members[0]);
                        assert_eq!(nodes[a].members[1], nodes[b].members[0]);
                        assert_eq!(nodes[b].members[1], node.members[1]);
                    }
                }
                let Some((axis, sin, cos)) = node.bound else {
                    continue;
                };
                for &k in &order[node.members[0]..node.members[1]] {
                    let (a, s, c) = cones[k];
                    let rim = a * c + a.any_orthonormal_vector() * s;
                    assert!(rim.dot(axis) >= cos * rim.length() - 1e-12, "{rim} {axis}");
                    let _ = sin;
                }
            }
        }
    }
}
