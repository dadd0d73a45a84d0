//! Dark cones (`guard::no_return`) gathered into groups of nearby
//! directions, each under one bounding cone from the same apex, so that a
//! sphere no nearer to a group's bounding cone than its bound so far skips
//! every member at once. Built once per cloud, with its list of rays
//! without a return.
//!
//! Why the bounding cone holds its members: a direction within `alpha_k` of
//! a member's axis `a_k` is within `angle(a, a_k) + alpha_k` of the group's
//! axis `a` (the triangle inequality for angles), so the cone of half angle
//! `max_k (angle(a, a_k) + alpha_k)`, padded by [`ANGLE_PAD`], contains
//! every member cone, and the distance to it is at most the distance to any
//! of them. The cone formula loses at worst a few times `sqrt(eps)` of the
//! distance to the apex to rounding (near a cone's axis), far less than the
//! [`ROUNDING_REL`] allowance a group's distance is reduced by, so a skipped
//! member could not have lowered the computed minimum.

use glam::DVec3;

/// Most members of a group: groups are halved until they hold no more.
pub(crate) const GROUP_SIZE: usize = 16;

/// Padding of a group's half angle (rad) against the rounding of the angles.
const ANGLE_PAD: f64 = 1e-6;

/// A group's cone is used only below this half angle (rad): the distance
/// formula needs less than a right angle.
const MAX_GROUP_ANGLE: f64 = 1.5;

/// Rounding allowance of a group's distance, relative to the distance from
/// the apex (plus one unit).
pub(crate) const ROUNDING_REL: f64 = 1e-6;

/// A cone from the common apex: unit axis, sine and cosine of its half angle.
pub(crate) type Cone = (DVec3, f64, f64);

/// One group: its members' range in the grouped order, and its bounding
/// cone unless the members spread too wide for one.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ConeGroup {
    pub members: [usize; 2],
    pub bound: Option<Cone>,
}

/// The cones' indices in grouped order and the groups over that order.
pub(crate) fn group_cones(cones: &[Cone]) -> (Vec<usize>, Vec<ConeGroup>) {
    let mut order: Vec<usize> = (0..cones.len()).collect();
    let mut ranges = Vec::new();
    halve(cones, &mut order, 0, &mut ranges);
    let groups = ranges
        .into_iter()
        .map(|members| ConeGroup {
            members,
            bound: bounding_cone(cones, &order[members[0]..members[1]]),
        })
        .collect();
    (order, groups)
}

/// Splits `members` (starting at `start` in the order) at the median of
/// the axes' coordinate that spreads most, until a part is small enough.
fn halve(cones: &[Cone], members: &mut [usize], start: usize, ranges: &mut Vec<[usize; 2]>) {
    if members.len() <= GROUP_SIZE {
        ranges.push([start, start + members.len()]);
        return;
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
    halve(cones, left, start, ranges);
    halve(cones, right, start + half, ranges);
}

/// The cone around the members' mean axis that holds them all, or `None`
/// when it would reach [`MAX_GROUP_ANGLE`] (or the axes cancel out).
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
    (half_angle < MAX_GROUP_ANGLE).then(|| {
        let (sin, cos) = half_angle.sin_cos();
        (axis, sin, cos)
    })
}

/// Distance from `p` to the cone `(axis, sin, cos)` from `apex` (half angle
/// below a right angle): 0 inside, the distance to the apex behind it, to
/// the lateral surface between.
#[inline]
pub(crate) fn cone_distance(apex: DVec3, (axis, sin, cos): Cone, p: DVec3) -> f64 {
    let d = p - apex;
    let along = d.dot(axis);
    let across = (d.length_squared() - along * along).max(0.0).sqrt();
    if across * cos <= along * sin {
        0.0
    } else if along * cos + across * sin <= 0.0 {
        d.length()
    } else {
        across * cos - along * sin
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field_of_view::tests::random_unit;
    use rand::{Rng, SeedableRng};

    /// Every member cone lies in its group's bounding cone: directions on a
    /// member's rim are inside the group's (with its padding to spare).
    #[test]
    fn groups_hold_their_members() {
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
            let (order, groups) = group_cones(&cones);
            let mut seen: Vec<usize> = order.clone();
            seen.sort();
            assert_eq!(seen, (0..n).collect::<Vec<_>>());
            for group in &groups {
                assert!(group.members[1] - group.members[0] <= GROUP_SIZE);
                let Some((axis, sin, cos)) = group.bound else {
                    continue;
                };
                for &k in &order[group.members[0]..group.members[1]] {
                    let (a, s, c) = cones[k];
                    let rim = a * c + a.any_orthonormal_vector() * s;
                    assert!(rim.dot(axis) >= cos * rim.length() - 1e-12, "{rim} {axis}");
                    let _ = sin;
                }
            }
        }
    }
}
