//! The blending regions of Zou et al., Section 4: the least-squares plane P_f of the
//! (placed) polygon of interest, its projection P_prj, the equidistant scalings
//! P_in and P_out (Fig. 8), the parent's region F_p between them with back-surface
//! points excluded by depth (Fig. 9a), and the child's region F_c between P_f and
//! the offset plane P_front (Fig. 9b).

use super::error::BlendError;
use super::polygon::PolygonOfInterest;
use super::polygon2d::Polygon2;
use glam::{DVec2, DVec3};
use shroud_geometry::cloud::Plane;
use std::collections::HashMap;

/// Sizes of the regions, as fractions of the polygon's mean radius rho (mean
/// distance of P_prj's vertices from their centroid), so one setting fits every
/// scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionParams {
    /// P_prj to P_in: the gap on the parent that the transition bridges.
    pub gap: f64,
    /// P_in to P_out: the width of F_p.
    pub ring: f64,
    /// P_f to P_front: the height of F_c.
    pub front: f64,
    /// Parent points deeper than this below the nearest surface seen from the
    /// child's side (in parent spacings) are back surface, not F_p.
    pub depth_tolerance: f64,
    /// Parent points farther than this from P_f (fraction of rho) are not part of
    /// the blend at all, whatever their projection: a child hovering far from
    /// the parent has no F_p.
    pub reach: f64,
}

impl Default for RegionParams {
    fn default() -> Self {
        Self {
            gap: 0.35,
            ring: 0.3,
            front: 0.3,
            depth_tolerance: 6.0,
            reach: 1.5,
        }
    }
}

impl RegionParams {
    pub fn validate(&self) -> Result<(), BlendError> {
        for (name, value) in [
            ("regions.gap", self.gap),
            ("regions.ring", self.ring),
            ("regions.front", self.front),
            ("regions.depth_tolerance", self.depth_tolerance),
            ("regions.reach", self.reach),
        ] {
            check_positive(name, value)?;
        }
        Ok(())
    }
}

/// What a parent point is with respect to the blend.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParentClass {
    /// Projects outside P_out, or lies farther than `reach` from P_f: untouched.
    Outside,
    /// Inside P_out but on the back surface (seen from the child): untouched.
    Back,
    /// Front surface between P_in and P_out: in F_p.
    Region,
    /// Front surface inside P_in: under the child, replaced.
    Covered,
}

/// The regions of one placement.
#[derive(Debug, Clone, PartialEq)]
pub struct BlendRegions {
    /// P_f, through the polygon's centroid, normal toward the child's body.
    pub plane: Plane,
    /// In-plane axes of P_f's frame.
    pub axes: (DVec3, DVec3),
    /// P_prj in P_f's frame.
    pub outline: Polygon2,
    /// Mean radius rho of P_prj.
    pub radius: f64,
    /// Distances from P_prj to P_in and P_out, and from P_f to P_front (absolute).
    pub d_in: f64,
    pub d_out: f64,
    pub front: f64,
    /// Class of every parent point.
    pub parent_class: Vec<ParentClass>,
    /// F_p: indices of parent points.
    pub parent_region: Vec<usize>,
    /// F_c: indices of (placed) child points.
    pub child_region: Vec<usize>,
}

impl BlendRegions {
    /// `p` in P_f's frame: in-plane coordinates and height above P_f.
    pub fn to_plane(&self, p: DVec3) -> (DVec2, f64) {
        let d = p - self.plane.origin;
        (
            DVec2::new(d.dot(self.axes.0), d.dot(self.axes.1)),
            d.dot(self.plane.normal),
        )
    }

    /// Signed distance of `p`'s projection to P_prj (negative inside), exact up to
    /// `cap`.
    pub fn outline_distance(&self, p: DVec3, cap: f64) -> f64 {
        self.outline.signed_distance_capped(self.to_plane(p).0, cap)
    }

    /// P_in (`s = d_in`) or P_out (`s = d_out`) as a 3D polyline in P_f, from the
    /// paper's equidistant scaling.
    pub fn scaled_outline(&self, s: f64) -> Vec<DVec3> {
        self.outline
            .equidistant_offset(s)
            .into_iter()
            .map(|q| self.plane.origin + q.x * self.axes.0 + q.y * self.axes.1)
            .collect()
    }
}

/// Computes the regions for `parent` and the placed `child` (world coordinates)
/// around the placed `polygon`. `parent_spacing` sets the depth test's scale.
pub fn blend_regions(
    parent: &[DVec3],
    child: &[DVec3],
    polygon: &PolygonOfInterest,
    parent_spacing: f64,
    params: &RegionParams,
) -> Result<BlendRegions, BlendError> {
    params.validate()?;
    // (1) P_f, oriented toward the child's body.
    let plane = polygon.plane_toward(child);
    let axes = plane.basis();
    // (2) P_prj and its equidistant scalings P_in, P_out.
    let outline = polygon
        .project(&plane)
        .ok_or_else(|| BlendError::DegeneratePolygon {
            reason: "the placed outline encloses no area in P_f".to_owned(),
        })?;
    let centroid = outline.centroid();
    let radius = outline
        .vertices()
        .iter()
        .map(|v| v.distance(centroid))
        .sum::<f64>()
        / outline.vertices().len() as f64;
    let (d_in, d_out, front) = (
        params.gap * radius,
        (params.gap + params.ring) * radius,
        params.front * radius,
    );
    let mut regions = BlendRegions {
        plane,
        axes,
        outline,
        radius,
        d_in,
        d_out,
        front,
        parent_class: vec![ParentClass::Outside; parent.len()],
        parent_region: Vec::new(),
        child_region: Vec::new(),
    };
    // (3) F_p: project the parent onto P_f, keep the ring, drop the back surface.
    let reach = params.reach * radius;
    let inside: Vec<(usize, DVec2, f64, f64)> = parent
        .iter()
        .enumerate()
        .filter_map(|(i, &p)| {
            let (q, h) = regions.to_plane(p);
            let d = regions.outline.signed_distance_capped(q, d_out);
            (d <= d_out && h.abs() <= reach).then_some((i, q, h, d))
        })
        .collect();
    let spacing = if parent_spacing > 0.0 {
        parent_spacing
    } else {
        radius * 0.02
    };
    let cell = 2.0 * spacing;
    let key = |q: DVec2| ((q.x / cell).floor() as i64, (q.y / cell).floor() as i64);
    let mut top: HashMap<(i64, i64), f64> = HashMap::with_capacity(inside.len());
    for &(_, q, h, _) in &inside {
        let slot = top.entry(key(q)).or_insert(f64::NEG_INFINITY);
        *slot = slot.max(h);
    }
    let tolerance = params.depth_tolerance * spacing;
    for &(i, q, h, d) in &inside {
        let (a, b) = key(q);
        let mut surface = f64::NEG_INFINITY;
        for da in -1..=1 {
            for db in -1..=1 {
                if let Some(&t) = top.get(&(a + da, b + db)) {
                    surface = surface.max(t);
                }
            }
        }
        regions.parent_class[i] = if h < surface - tolerance {
            ParentClass::Back
        } else if d > d_in {
            regions.parent_region.push(i);
            ParentClass::Region
        } else {
            ParentClass::Covered
        };
    }
    // (4) F_c: child points between P_f and P_front.
    regions.child_region = child
        .iter()
        .enumerate()
        .filter(|(_, &p)| {
            let h = regions.plane.height(p);
            (0.0..=front).contains(&h)
        })
        .map(|(i, _)| i)
        .collect();
    Ok(regions)
}

/// A size parameter must be positive and finite (below 1e6, far beyond any scene).
pub(crate) fn check_positive(name: &'static str, value: f64) -> Result<(), BlendError> {
    if value > 0.0 && value < 1e6 {
        Ok(())
    } else {
        Err(BlendError::InvalidParameter {
            name,
            value,
            reason: "must be positive and finite",
        })
    }
}
