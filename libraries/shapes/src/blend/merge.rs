//! Combining T_R, M_c and M_p into one model (Zou et al., Section 5, last part,
//! Fig. 10) without the overlaps a plain union would have: parent points whose
//! projection on P_f lies outside P_out, child points beyond P_front, and of the
//! transition surface the part S1 near P_f (within a threshold) inside P_out and
//! the part S2 between P_f and P_front.
//!
//! Two readings of the paper are made explicit. The child is kept beyond P_front,
//! not beyond P_f, because between the two planes T_R interpolates F_c and keeping
//! both would overlap. Parent points on the back surface (excluded from F_p by
//! depth) are kept wherever they project, since nothing replaces them. S2 is also
//! clipped to P_out, which only matters where the parent rises near P_out.

use super::regions::{BlendRegions, ParentClass};
use glam::DVec3;

/// Which input a point of the blended model comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Source {
    Parent = 0,
    Child = 1,
    Transition = 2,
}

/// A point cloud with unit normals and the source of every point.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Merged {
    pub points: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub sources: Vec<Source>,
}

impl Merged {
    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    fn push(&mut self, p: DVec3, n: DVec3, source: Source) {
        self.points.push(p);
        self.normals.push(n);
        self.sources.push(source);
    }

    /// The plain union M_p + M_c + T_R, overlaps included (the baseline the
    /// overlap rate is compared against).
    pub fn union(parts: [(&[DVec3], &[DVec3], Source); 3]) -> Self {
        let mut out = Self::default();
        for (points, normals, source) in parts {
            for (i, &p) in points.iter().enumerate() {
                out.push(p, normals.get(i).copied().unwrap_or(DVec3::ZERO), source);
            }
        }
        out
    }
}

/// Whether the transition point `p` is kept: S1 (height above P_f at most
/// `s1_threshold`) inside P_out; S2 (above the threshold) up to P_front and
/// inside P_out.
pub fn keep_transition(regions: &BlendRegions, p: DVec3, s1_threshold: f64) -> bool {
    let (_, h) = regions.to_plane(p);
    let inside_out = regions.outline_distance(p, regions.d_out) <= regions.d_out;
    if h <= s1_threshold {
        inside_out
    } else {
        h <= regions.front && inside_out
    }
}

/// The overlap-free combination (see the module docs).
#[allow(clippy::too_many_arguments)]
pub fn merge(
    regions: &BlendRegions,
    parent: &[DVec3],
    parent_normals: &[DVec3],
    child: &[DVec3],
    child_normals: &[DVec3],
    transition: &[DVec3],
    transition_normals: &[DVec3],
    s1_threshold: f64,
) -> Merged {
    let mut out = Merged::default();
    for (i, &p) in parent.iter().enumerate() {
        if matches!(
            regions.parent_class.get(i),
            Some(ParentClass::Outside | ParentClass::Back)
        ) {
            out.push(
                p,
                parent_normals.get(i).copied().unwrap_or(DVec3::ZERO),
                Source::Parent,
            );
        }
    }
    for (i, &p) in child.iter().enumerate() {
        if regions.plane.height(p) > regions.front {
            out.push(
                p,
                child_normals.get(i).copied().unwrap_or(DVec3::ZERO),
                Source::Child,
            );
        }
    }
    for (i, &p) in transition.iter().enumerate() {
        if keep_transition(regions, p, s1_threshold) {
            out.push(
                p,
                transition_normals.get(i).copied().unwrap_or(DVec3::ZERO),
                Source::Transition,
            );
        }
    }
    out
}
