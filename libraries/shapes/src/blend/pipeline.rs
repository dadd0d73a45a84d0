//! One blend (Zou et al., Fig. 1c-e): place the child, compute the blending regions,
//! fit the RBF transition surface, sample it, and merge; and compound blending,
//! dropping several children in turn, CSG fashion (Section 1, Fig. 11a).

use super::error::BlendError;
use super::merge::{merge, Merged};
use super::prepared::{Child, Prepared};
use super::rbf::{
    build_constraints, fit_greedy, BatchField, ExactField, GreedyReport, Rbf, RbfParams, SplitField,
};
use super::regions::{blend_regions, BlendRegions, RegionParams};
use super::tetra::{sample_zero_set_with, SampledSurface};
use super::transform::RigidTransform;
use glam::DVec3;
use shroud_geometry::cloud::{orient_normals, BoundaryParams, Orientation};
use std::time::Instant;

/// Everything tunable in a blend.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlendParams {
    pub regions: RegionParams,
    /// Neighbours for normal estimation.
    pub normal_k: usize,
    /// Off-surface distance h, in spacings (the smaller of parent and child).
    pub offset: f64,
    pub rbf: RbfParams,
    /// Marching-tetrahedra cell, in spacings.
    pub cell: f64,
    /// Sampling budget in grid cells.
    pub max_cells: usize,
    /// How the sampling evaluates the RBF.
    pub evaluation: Evaluation,
    /// S1/S2 threshold of the merge, as a fraction of the P_f-P_front distance.
    pub s1_threshold: f64,
    /// Fewer points in F_p or F_c is an error.
    pub min_region_points: usize,
    pub boundary: BoundaryParams,
}

impl Default for BlendParams {
    fn default() -> Self {
        Self {
            regions: RegionParams::default(),
            normal_k: 12,
            offset: 2.0,
            rbf: RbfParams::default(),
            cell: 1.5,
            max_cells: 2_000_000,
            evaluation: Evaluation::Split,
            s1_threshold: 0.5,
            min_region_points: 16,
            boundary: BoundaryParams::default(),
        }
    }
}

/// How the zero-set sampling evaluates the RBF.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Evaluation {
    /// Near sums and an interpolated far field ([`SplitField`]): fast, within
    /// a small fraction of a cell of the direct sum's surface.
    #[default]
    Split,
    /// Every centre at every point ([`ExactField`]): the reference.
    Direct,
}

/// Milliseconds per stage.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StageTimes {
    pub regions: f64,
    pub normals: f64,
    pub rbf: f64,
    pub sampling: f64,
    pub merge: f64,
    pub total: f64,
}

/// Sizes and timings of one blend.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BlendReport {
    pub parent_region: usize,
    pub child_region: usize,
    pub constraints: usize,
    pub greedy: GreedyReport,
    pub cells_visited: usize,
    pub transition_points: usize,
    pub kept_transition: usize,
    pub times: StageTimes,
}

/// The result of one blend, with its intermediate pieces for inspection.
#[derive(Debug, Clone)]
pub struct Blend {
    /// M_r: the combined model.
    pub merged: Merged,
    pub regions: BlendRegions,
    pub rbf: Rbf,
    /// T_R before overlap elimination.
    pub transition: SampledSurface,
    /// The child moved into place, and its normals.
    pub child_points: Vec<DVec3>,
    pub child_normals: Vec<DVec3>,
    /// The parent's normals as used in the output (consistently outward).
    pub parent_normals: Vec<DVec3>,
    pub report: BlendReport,
}

fn ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

fn validate(params: &BlendParams) -> Result<(), BlendError> {
    params.regions.validate()?;
    for (name, value) in [
        ("offset", params.offset),
        ("cell", params.cell),
        ("s1_threshold", params.s1_threshold),
    ] {
        super::regions::check_positive(name, value)?;
    }
    Ok(())
}

/// Normals of `indices` oriented by `orientation`, and whether the cloud's own
/// orientation mostly disagrees with them (then the whole cloud is flipped).
fn region_normals(
    points: &[DVec3],
    normals: &[DVec3],
    indices: &[usize],
    k: usize,
    orientation: Orientation,
) -> (Vec<DVec3>, bool) {
    let pts: Vec<DVec3> = indices.iter().map(|&i| points[i]).collect();
    let mut oriented: Vec<DVec3> = indices.iter().map(|&i| normals[i]).collect();
    orient_normals(&pts, &mut oriented, k, orientation, 0.3);
    let agree = indices
        .iter()
        .zip(&oriented)
        .filter(|(&i, n)| normals[i].dot(**n) >= 0.0)
        .count();
    (oriented, 2 * agree < indices.len())
}

/// Blends `child`, moved by `placement`, into `parent`.
pub fn blend(
    parent: &Prepared,
    child: &Child,
    placement: &RigidTransform,
    params: &BlendParams,
) -> Result<Blend, BlendError> {
    validate(params)?;
    let start = Instant::now();
    let mut times = StageTimes::default();
    let child_points: Vec<DVec3> = child
        .cloud
        .points()
        .iter()
        .map(|&p| placement.apply(p))
        .collect();
    let mut child_normals: Vec<DVec3> = child
        .cloud
        .normals
        .iter()
        .map(|&n| placement.apply_vector(n))
        .collect();
    let polygon = child.polygon.transformed(placement);
    let regions = blend_regions(
        parent.points(),
        &child_points,
        &polygon,
        parent.spacing,
        &params.regions,
    )?;
    for (region, count) in [
        ("F_p", regions.parent_region.len()),
        ("F_c", regions.child_region.len()),
    ] {
        if count < params.min_region_points {
            return Err(BlendError::EmptyRegion {
                region,
                count,
                min: params.min_region_points,
            });
        }
    }
    times.regions = ms(start);

    let t = Instant::now();
    let n = regions.plane.normal;
    let (parent_region_normals, flip_parent) = region_normals(
        parent.points(),
        &parent.normals,
        &regions.parent_region,
        params.normal_k,
        Orientation::Toward(n),
    );
    let axis = Orientation::AwayFromAxis {
        origin: regions.plane.origin,
        axis: n,
    };
    let (child_region_normals, flip_child) = region_normals(
        &child_points,
        &child_normals,
        &regions.child_region,
        params.normal_k,
        axis,
    );
    let parent_normals: Vec<DVec3> = if flip_parent {
        parent.normals.iter().map(|&v| -v).collect()
    } else {
        parent.normals.clone()
    };
    if flip_child {
        child_normals.iter_mut().for_each(|v| *v = -*v);
    }
    times.normals = ms(t);

    let t = Instant::now();
    let spacing = parent.spacing.min(child.cloud.spacing);
    let surface: Vec<DVec3> = regions
        .parent_region
        .iter()
        .map(|&i| parent.points()[i])
        .chain(regions.child_region.iter().map(|&i| child_points[i]))
        .collect();
    let surface_normals: Vec<DVec3> = parent_region_normals
        .into_iter()
        .chain(child_region_normals)
        .collect();
    let constraints = build_constraints(&surface, &surface_normals, params.offset * spacing);
    let rbf_params = RbfParams { ..params.rbf };
    let (rbf, greedy) = fit_greedy(&constraints, &rbf_params)?;
    times.rbf = ms(t);

    let t = Instant::now();
    let cell = params.cell * spacing;
    let low = regions
        .parent_region
        .iter()
        .map(|&i| regions.plane.height(parent.points()[i]))
        .fold(0.0, f64::min)
        - 2.0 * cell;
    let high = regions.front + 1.5 * cell;
    let reach = regions.d_out + 1.5 * cell;
    let inside = |p: DVec3| {
        let (_, h) = regions.to_plane(p);
        h >= low && h <= high && regions.outline_distance(p, reach) <= reach
    };
    let mut split;
    let mut direct;
    let field: &mut dyn BatchField = match params.evaluation {
        Evaluation::Split => {
            split = SplitField::for_sampling(&rbf, cell);
            &mut split
        }
        Evaluation::Direct => {
            direct = ExactField(&rbf);
            &mut direct
        }
    };
    let transition = sample_zero_set_with(
        field,
        &surface,
        regions.plane.origin,
        cell,
        &inside,
        params.max_cells,
    )?;
    times.sampling = ms(t);

    let t = Instant::now();
    let merged = merge(
        &regions,
        parent.points(),
        &parent_normals,
        &child_points,
        &child_normals,
        &transition.points,
        &transition.normals,
        params.s1_threshold * regions.front,
    );
    times.merge = ms(t);
    times.total = ms(start);
    let kept_transition = merged
        .sources
        .iter()
        .filter(|&&s| s == super::merge::Source::Transition)
        .count();
    let report = BlendReport {
        parent_region: regions.parent_region.len(),
        child_region: regions.child_region.len(),
        constraints: constraints.points.len(),
        greedy,
        cells_visited: transition.cells_visited,
        transition_points: transition.points.len(),
        kept_transition,
        times,
    };
    Ok(Blend {
        merged,
        regions,
        rbf,
        transition,
        child_points,
        child_normals,
        parent_normals,
        report,
    })
}

/// Compound blending: drops every `(child, placement)` in turn, each onto the
/// result of the previous ones (the union grows CSG fashion). Returns the final
/// model and the report of every step.
pub fn blend_sequence(
    parent: Prepared,
    drops: &[(&Child, RigidTransform)],
    params: &BlendParams,
) -> Result<(Merged, Vec<BlendReport>), BlendError> {
    let mut current = parent;
    let mut reports = Vec::with_capacity(drops.len());
    let mut last = None;
    for (child, placement) in drops {
        let step = blend(&current, child, placement, params)?;
        reports.push(step.report);
        current = Prepared::with_normals(
            step.merged.points.clone(),
            step.merged.normals.clone(),
            "blended",
        )?;
        last = Some(step.merged);
    }
    let merged = match last {
        Some(m) => m,
        None => Merged {
            points: current.points().to_vec(),
            normals: current.normals.clone(),
            sources: vec![super::merge::Source::Parent; current.points().len()],
        },
    };
    Ok((merged, reports))
}
