//! Tests of the point-cloud blender (paper 001): the RBF, the sampler, the
//! placement, boundary loops, the merge and the errors on bad input.

mod blend_scenes;

use blend_scenes::*;
use glam::{DQuat, DVec2, DVec3};
use shroud_geometry::cloud::{
    boundary_loops, to_dvec3, BoundaryFailure, BoundaryParams, NeighbourIndex,
};
use shroud_shapes::blend::rbf::{build_constraints, fit_greedy, Rbf, RbfParams};
use shroud_shapes::blend::AdjustTransform;
use shroud_shapes::blend::{
    blend, blend_sequence, drop_transform, overlap_rate, sample_zero_set, seam_gap, seam_points,
    BlendError, BlendParams, Camera, Child, DragSession, LocalAdjust, Merged, ParentClass,
    PolygonOfInterest, Prepared, RigidTransform, Source,
};

fn fibonacci_sphere(n: usize, r: f64, centre: DVec3) -> (Vec<DVec3>, Vec<DVec3>) {
    shroud_geometry::math::fibonacci_sphere(n)
        .into_iter()
        // The lattice's first point at the +y pole.
        .map(|d| DVec3::new(d.x, d.z, d.y))
        .map(|d| (centre + r * d, d))
        .unzip()
}

fn sphere_rbf() -> (Rbf, Vec<DVec3>, Vec<f64>) {
    let (pts, nrm) = fibonacci_sphere(150, 0.8, DVec3::new(0.3, -0.2, 0.1));
    let c = build_constraints(&pts, &nrm, 0.1);
    let rbf = Rbf::interpolate(&c.points, &c.values).expect("sphere system is regular");
    (rbf, c.points, c.values)
}

#[test]
fn rbf_interpolates_its_constraints() {
    let (rbf, points, values) = sphere_rbf();
    assert_eq!(rbf.centres(), points.len());
    for (p, v) in points.iter().zip(&values) {
        let s = rbf.value(*p);
        assert!((s - v).abs() < 1e-7, "s({p}) = {s}, wanted {v}");
    }
}

#[test]
fn rbf_off_surface_sign_and_gradient() {
    let (rbf, _, _) = sphere_rbf();
    let centre = DVec3::new(0.3, -0.2, 0.1);
    assert!(rbf.value(centre) < 0.0, "inside must be negative");
    assert!(
        rbf.value(centre + DVec3::new(0.0, 0.0, 1.2)) > 0.0,
        "outside must be positive"
    );
    assert!(rbf.value(centre + DVec3::new(0.0, 0.95, 0.0)) > 0.0);
    assert!(rbf.value(centre + DVec3::new(0.65, 0.0, 0.0)) < 0.0);
    // The gradient points outward on the surface and agrees with finite differences.
    let p = centre + 0.8 * DVec3::new(1.0, 1.0, 0.0).normalize();
    let (_, g) = rbf.value_gradient(p);
    assert!(g.normalize().dot((p - centre).normalize()) > 0.98);
    let e = 1e-6;
    let fd = DVec3::new(
        rbf.value(p + DVec3::X * e) - rbf.value(p - DVec3::X * e),
        rbf.value(p + DVec3::Y * e) - rbf.value(p - DVec3::Y * e),
        rbf.value(p + DVec3::Z * e) - rbf.value(p - DVec3::Z * e),
    ) / (2.0 * e);
    assert!(
        (fd - g).length() < 1e-5 * g.length().max(1.0),
        "{fd} vs {g}"
    );
}

#[test]
fn greedy_reduction_meets_its_tolerance_with_fewer_centres() {
    let (pts, nrm) = fibonacci_sphere(400, 1.0, DVec3::ZERO);
    let c = build_constraints(&pts, &nrm, 0.1);
    let params = RbfParams {
        max_centres: 1200,
        initial_centres: 50,
        tolerance: 1e-3,
        max_rounds: 12,
    };
    let (rbf, report) = fit_greedy(&c, &params).unwrap();
    assert!(report.max_residual <= 1e-3, "{report:?}");
    assert!(
        rbf.centres() < c.points.len(),
        "{} of {}",
        rbf.centres(),
        c.points.len()
    );
}

#[test]
fn marching_tetrahedra_points_lie_on_the_zero_set() {
    let (rbf, points, _) = sphere_rbf();
    let centre = DVec3::new(0.3, -0.2, 0.1);
    let cell = 0.05;
    // Restrict to the upper half: surface following must stay inside it.
    let inside = |p: DVec3| p.z > centre.z;
    let upper: Vec<DVec3> = points[..150]
        .iter()
        .copied()
        .filter(|p| p.z > centre.z + 0.1)
        .collect();
    let s = sample_zero_set(&rbf, &upper, centre, cell, &inside, 1_000_000).unwrap();
    assert!(s.points.len() > 500, "{}", s.points.len());
    for (p, n) in s.points.iter().zip(&s.normals) {
        let d = rbf.distance_estimate(*p);
        assert!(d < 1e-3 * cell, "{p}: {d}");
        assert!((p.distance(centre) - 0.8).abs() < 0.02, "{p}");
        assert!(p.z > centre.z - 2.0 * cell, "escaped the region: {p}");
        assert!((n.length() - 1.0).abs() < 1e-9 && n.dot(*p - centre) > 0.0);
    }
}

#[test]
fn drop_transform_maps_the_initial_pair_onto_the_target() {
    let mut rng = Jitter::new(5);
    for _ in 0..50 {
        let mut v = || {
            DVec3::new(
                rng.uniform() - 0.5,
                rng.uniform() - 0.5,
                rng.uniform() - 0.5,
            ) * 4.0
        };
        let (p_i, v_i, p_t, v_t) = (v(), v().normalize(), v(), v().normalize());
        let t = drop_transform(p_i, v_i, p_t, v_t);
        assert!((t.apply(p_i) - p_t).length() < 1e-12);
        assert!((t.apply_vector(v_i) - v_t).length() < 1e-12);
        // With the local adjustment the centroid slides along the (tilted) normal.
        let adjust = LocalAdjust {
            lift: 0.3,
            spin: 0.7,
            tilt: [0.1, -0.2],
        };
        let full = adjust.transform(p_t, v_t).after(&t);
        let n = adjust.normal(v_t);
        assert!((full.apply(p_i) - (p_t + 0.3 * n)).length() < 1e-12);
        assert!((full.apply_vector(v_i) - n).length() < 1e-12);
    }
    // Antiparallel normals still give a proper rotation.
    let t = drop_transform(DVec3::ZERO, DVec3::Z, DVec3::X, DVec3::NEG_Z);
    assert!((t.apply_vector(DVec3::Z) - DVec3::NEG_Z).length() < 1e-12);
}

#[test]
fn boundary_loops_of_a_disc_with_a_hole() {
    let cloud = disc_with_hole(0.35, 1.0, 12_000, 3);
    let index = NeighbourIndex::from_f32(&cloud);
    let loops = boundary_loops(&index, &BoundaryParams::default());
    assert_eq!(
        loops.len(),
        2,
        "lengths {:?}",
        loops.iter().map(|l| l.length).collect::<Vec<_>>()
    );
    let tau = std::f64::consts::TAU;
    assert!(
        (loops[0].length / tau - 1.0).abs() < 0.15,
        "outer {}",
        loops[0].length
    );
    assert!(
        (loops[1].length / (tau * 0.35) - 1.0).abs() < 0.25,
        "inner {}",
        loops[1].length
    );
    for (l, r) in [(&loops[0], 1.0), (&loops[1], 0.35)] {
        for &i in &l.indices {
            let p = index.points()[i];
            assert!(
                (p.truncate().length() - r).abs() < 0.06,
                "{p} not on the r = {r} rim"
            );
        }
    }
}

fn plane_and_hemisphere() -> (Prepared, Child) {
    let parent = Prepared::new(&plane(2.0, 20_000, 0.0, 1), "parent", 12).unwrap();
    let child_cloud = Prepared::new(&hemisphere(0.5, 4_000), "child", 12).unwrap();
    let child = Child::new(child_cloud, None, &BoundaryParams::default()).unwrap();
    (parent, child)
}

fn small_params() -> BlendParams {
    let mut params = BlendParams::default();
    params.rbf.max_centres = 500;
    params.cell = 2.0;
    params
}

#[test]
fn hemisphere_on_a_plane_blends_without_overlap() {
    let (parent, child) = plane_and_hemisphere();
    assert!(
        child.v_i.dot(DVec3::Z) > 0.99,
        "V_I must point into the child's body"
    );
    let placement = child.placement(
        DVec3::new(0.3, -0.2, 0.0),
        DVec3::Z,
        &LocalAdjust::default(),
    );
    let params = small_params();
    let result = blend(&parent, &child, &placement, &params).unwrap();
    let r = &result.report;
    assert!(r.parent_region > 100 && r.child_region > 100, "{r:?}");
    assert!(r.kept_transition > 200, "{r:?}");
    // Overlap elimination: no kept parent point on the front surface inside P_out,
    // no child point below P_front, no transition point outside P_out.
    let regions = &result.regions;
    for ((p, s), n) in result
        .merged
        .points
        .iter()
        .zip(&result.merged.sources)
        .zip(&result.merged.normals)
    {
        let d = regions.outline_distance(*p, regions.d_out);
        let h = regions.plane.height(*p);
        match s {
            Source::Parent => assert!(d > regions.d_out, "parent point {p} inside P_out"),
            Source::Child => assert!(h > regions.front, "child point {p} below P_front"),
            Source::Transition => assert!(d <= regions.d_out + 1e-9 && h <= regions.front + 1e-9),
        }
        assert!((n.length() - 1.0).abs() < 1e-6, "normal {n} at {p}");
    }
    assert!(regions.parent_class.contains(&ParentClass::Covered));
    // The plain union overlaps over whole areas; the merge only along seams.
    let union = Merged::union([
        (parent.points(), &result.parent_normals, Source::Parent),
        (&result.child_points, &result.child_normals, Source::Child),
        (
            &result.transition.points,
            &result.transition.normals,
            Source::Transition,
        ),
    ]);
    let radius = 0.5 * parent.spacing;
    let before = overlap_rate(&union, radius);
    let after = overlap_rate(&result.merged, radius);
    assert!(
        after < 0.25 * before,
        "overlap before {before}, after {after}"
    );
    // The transition surface meets both regions: tiny surface gap at the seams.
    let tr = NeighbourIndex::new(result.transition.points.clone());
    let (seam_p, seam_c) = seam_points(&result, parent.points(), 2.0 * parent.spacing);
    for seam in [seam_p, seam_c] {
        assert!(seam.len() > 20);
        let gap = seam_gap(&result.rbf, &seam, &tr);
        assert!(
            gap.surface_mean < 0.25 * parent.spacing && gap.surface_max < parent.spacing,
            "{gap:?}"
        );
        assert!(gap.sampled_max < 2.0 * parent.spacing, "{gap:?}");
    }
    // Transition normals point away from the merged solid: up over the F_p ring;
    // and the transition has no spurious sheet under the child.
    for ((p, n), s) in result
        .merged
        .points
        .iter()
        .zip(&result.merged.normals)
        .zip(&result.merged.sources)
    {
        if *s == Source::Transition {
            let d = regions.outline_distance(*p, regions.d_out);
            if d >= 0.5 * (regions.d_in + regions.d_out) {
                assert!(
                    n.z > 0.9 && p.z.abs() < parent.spacing,
                    "ring normal {n} at {p}"
                );
            }
            assert!(
                d > -0.1 * regions.radius,
                "transition point {p} under the child (d = {d})"
            );
        }
    }
}

#[test]
fn compound_blending_drops_children_in_turn() {
    let (parent, child) = plane_and_hemisphere();
    let a = child.placement(
        DVec3::new(-0.9, 0.0, 0.0),
        DVec3::Z,
        &LocalAdjust::default(),
    );
    let b = child.placement(
        DVec3::new(0.9, 0.2, 0.0),
        DVec3::Z,
        &LocalAdjust {
            spin: 0.5,
            ..Default::default()
        },
    );
    let (merged, reports) =
        blend_sequence(parent, &[(&child, a), (&child, b)], &small_params()).unwrap();
    assert_eq!(reports.len(), 2);
    // Both children are present: points high above each drop point.
    for x in [-0.9, 0.9] {
        assert!(
            merged
                .points
                .iter()
                .any(|p| (p.x - x).abs() < 0.1 && p.z > 0.45),
            "no child at x = {x}"
        );
    }
}

#[test]
fn drag_follows_the_surface_and_stops_at_its_edge() {
    let (parent, child) = plane_and_hemisphere();
    let camera = Camera {
        eye: DVec3::new(0.0, -4.0, 5.0),
        target: DVec3::ZERO,
        up: DVec3::Z,
        fov_y: 0.8,
        width: 400,
        height: 300,
        near: 0.1,
        far: 50.0,
    };
    let (centre_px, _) = camera.project(DVec3::ZERO).unwrap();
    let mut session =
        DragSession::paste(parent.points(), camera, 10, child.p_i, child.v_i, centre_px).unwrap();
    let (p, n) = session.placement();
    assert!(p.z.abs() < 0.02 && p.truncate().length() < 0.05, "{p}");
    assert!(n.dot(DVec3::Z) > 0.99, "{n}");
    assert!((session.transform().apply(child.p_i) - p).length() < 1e-9);
    // Drag right by 40 pixels: stays on the plane, moves along +x.
    session.drag_to(centre_px + DVec2::new(40.0, 0.0)).unwrap();
    let (p1, n1) = session.placement();
    assert!(p1.x > 0.2 && p1.z.abs() < 0.02 && n1.z > 0.99, "{p1} {n1}");
    // Drag far off the plane's right edge: clamped to the last surface pixel.
    session
        .drag_to(centre_px + DVec2::new(3000.0, 0.0))
        .unwrap();
    let (p2, _) = session.placement();
    // (A block is about 0.18 wide here: the discrete buffer reaches that far out.)
    assert!(
        p2.x > 1.5 && p2.x <= 2.3 && p2.z.abs() < 1e-3,
        "clamped at the edge: {p2}"
    );
    // A paste off the surface is an error, not a panic.
    let err = DragSession::paste(
        parent.points(),
        camera,
        10,
        child.p_i,
        child.v_i,
        DVec2::new(1.0, 1.0),
    );
    assert_eq!(err.unwrap_err(), BlendError::NotOnSurface);
}

#[test]
fn bad_inputs_give_clear_errors() {
    // Too small, non-finite.
    let tiny = plane(1.0, 9, 0.0, 1);
    assert!(matches!(
        Prepared::new(&tiny, "parent", 12),
        Err(BlendError::TooFewPoints { .. })
    ));
    let mut nan = plane(1.0, 400, 0.0, 1);
    nan[17][1] = f32::NAN;
    assert_eq!(
        Prepared::new(&nan, "child", 12).unwrap_err(),
        BlendError::NonFinite {
            what: "child",
            index: 17
        }
    );
    // All points equal.
    let same = vec![[1.0f32, 2.0, 3.0]; 100];
    assert_eq!(
        Prepared::new(&same, "parent", 12).unwrap_err(),
        BlendError::Coincident { what: "parent" }
    );
    // A closed sphere has no boundary loop.
    let (ball, _) = fibonacci_sphere(3000, 1.0, DVec3::ZERO);
    let ball: Vec<[f32; 3]> = ball
        .iter()
        .map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect();
    let closed = Prepared::new(&ball, "child", 12).unwrap();
    assert!(matches!(
        Child::new(closed, None, &BoundaryParams::default()).unwrap_err(),
        BlendError::NoBoundaryLoop {
            what: "child",
            reason: BoundaryFailure::NoGap { .. }
        }
    ));
    // Degenerate polygons of interest.
    let line: Vec<DVec3> = (0..10)
        .map(|i| DVec3::new(f64::from(i), 0.0, 0.0))
        .collect();
    assert!(matches!(
        PolygonOfInterest::from_polyline(line),
        Err(BlendError::DegeneratePolygon { .. })
    ));
    assert!(matches!(
        PolygonOfInterest::from_polyline(vec![DVec3::ZERO; 5]),
        Err(BlendError::DegeneratePolygon { .. })
    ));
    // Singular RBF systems: coplanar centres, duplicated centres, too few.
    let flat: Vec<DVec3> = (0..30)
        .map(|i| DVec3::new(f64::from(i % 6), f64::from(i / 6), 0.0))
        .collect();
    assert!(matches!(
        Rbf::interpolate(&flat, &[0.0; 30]),
        Err(BlendError::SingularSystem { .. })
    ));
    let mut twice: Vec<DVec3> = fibonacci_sphere(20, 1.0, DVec3::ZERO).0;
    twice.push(twice[3]);
    let values: Vec<f64> = (0..21).map(f64::from).collect();
    assert!(matches!(
        Rbf::interpolate(&twice, &values),
        Err(BlendError::SingularSystem { .. })
    ));
    assert!(matches!(
        Rbf::interpolate(&flat[..3], &[0.0; 3]),
        Err(BlendError::TooFewCentres { .. })
    ));
    // A child dropped far from the parent has an empty F_p.
    let (parent, child) = plane_and_hemisphere();
    let away = child.placement(
        DVec3::new(0.0, 0.0, 30.0),
        DVec3::Z,
        &LocalAdjust::default(),
    );
    assert!(matches!(
        blend(&parent, &child, &away, &small_params()),
        Err(BlendError::EmptyRegion { region: "F_p", .. })
    ));
    // Bad parameters.
    let mut params = small_params();
    params.cell = 0.0;
    let here = child.placement(DVec3::ZERO, DVec3::Z, &LocalAdjust::default());
    assert!(matches!(
        blend(&parent, &child, &here, &params),
        Err(BlendError::InvalidParameter { .. })
    ));
    params = small_params();
    params.regions.gap = f64::NAN;
    assert!(matches!(
        blend(&parent, &child, &here, &params),
        Err(BlendError::InvalidParameter { .. })
    ));
    // A degenerate camera.
    let camera = Camera {
        eye: DVec3::ZERO,
        target: DVec3::ZERO,
        up: DVec3::Z,
        fov_y: 0.8,
        width: 10,
        height: 10,
        near: 0.1,
        far: 10.0,
    };
    assert!(matches!(
        DragSession::paste(
            parent.points(),
            camera,
            10,
            child.p_i,
            child.v_i,
            DVec2::ZERO
        ),
        Err(BlendError::DegenerateCamera { .. })
    ));
}

#[test]
fn given_polyline_and_sim_cap_on_terrain() {
    // Simulator shapes: a sphere cap (its rim detected) onto the terrain's hill.
    let terrain = Prepared::new(&sim_terrain(30_000, 2), "parent", 12).unwrap();
    let cap = Prepared::new(&sim_cap(0.5, 0.3, 6_000, 4), "child", 12).unwrap();
    let child = Child::new(cap, None, &BoundaryParams::default()).unwrap();
    assert!(
        child.v_i.dot(DVec3::Z) > 0.95,
        "cap opens downward: V_I up, got {}",
        child.v_i
    );
    let (p_t, v_t) = terrain
        .surface_pair(DVec3::new(-1.5, -1.0, 1.0), 16)
        .unwrap();
    assert!(v_t.z > 0.9, "hill top normal {v_t}");
    let placement = child.placement(p_t, v_t, &LocalAdjust::default());
    let result = blend(&terrain, &child, &placement, &small_params()).unwrap();
    assert!(result.report.kept_transition > 100);
    // A given polyline instead of the detected loop: a square around the rim.
    let square: Vec<DVec3> = [(-0.4, -0.4), (0.4, -0.4), (0.4, 0.4), (-0.4, 0.4)]
        .iter()
        .map(|&(x, y)| DVec3::new(x, y, -0.15))
        .collect();
    let polygon = PolygonOfInterest::from_polyline(square).unwrap();
    let cap = Prepared::new(&sim_cap(0.5, 0.3, 6_000, 4), "child", 12).unwrap();
    let child = Child::new(cap, Some(polygon), &BoundaryParams::default()).unwrap();
    assert!((child.p_i - DVec3::new(0.0, 0.0, -0.15)).length() < 1e-9);
    let _ = RigidTransform::IDENTITY;
    let _ = DQuat::IDENTITY;
    let _ = to_dvec3([0.0; 3]);
}

/// The interactive session: drop, adjust, clear, commit; a refused command
/// leaves the last good model.
#[test]
fn session_follows_drops_adjustments_and_commits() {
    use shroud_shapes::blend::{BlendCommand, BlendSession, ModelSources};
    let (parent, child) = plane_and_hemisphere();
    let parent_len = parent.points().len();
    let mut session = BlendSession::new(parent, child, small_params());
    let count = |s: &BlendSession, source: Source| {
        let (points, sources) = s.model();
        (0..points.len())
            .filter(|&i| sources.get(i) == source)
            .count()
    };
    assert!(matches!(session.model().1, ModelSources::AllParent));
    let drop = BlendCommand::Drop {
        at: DVec3::new(0.2, -0.1, 0.0),
        normal: None,
    };
    let report = session.apply(&drop).unwrap().expect("a blend");
    assert!(report.kept_transition > 0);
    assert!(count(&session, Source::Child) > 100 && count(&session, Source::Transition) > 0);
    let placed = session.drop_state().unwrap();

    // Lifting the child moves it along the normal, and is remembered by the next drop.
    let lift = LocalAdjust {
        lift: 0.02,
        ..Default::default()
    };
    session.apply(&BlendCommand::Adjust(lift)).unwrap();
    assert_eq!(session.drop_state().unwrap().adjust, lift);
    assert_eq!(session.drop_state().unwrap().p_t, placed.p_t);
    let moved = BlendCommand::Drop {
        at: DVec3::new(-0.3, 0.2, 0.0),
        normal: Some(DVec3::Z),
    };
    session.apply(&moved).unwrap();
    assert_eq!(session.drop_state().unwrap().adjust, lift);

    // A refused drop keeps the model.
    let before = session.model().0.len();
    let bad = BlendCommand::Drop {
        at: DVec3::new(f64::NAN, 0.0, 0.0),
        normal: None,
    };
    assert!(session.apply(&bad).is_err());
    assert_eq!(session.model().0.len(), before);

    // Clear: the parent alone; commit without a drop is refused.
    session.apply(&BlendCommand::Clear).unwrap();
    assert_eq!(session.model().0.len(), parent_len);
    assert!(matches!(
        session.apply(&BlendCommand::Commit),
        Err(BlendError::NothingDropped)
    ));

    // Commit: the blend becomes the parent of the next drop.
    session.apply(&drop).unwrap();
    let blended = session.model().0.len();
    session.apply(&BlendCommand::Commit).unwrap();
    assert_eq!(session.commits(), 1);
    assert_eq!(session.model().0.len(), blended);
    assert!(session.drop_state().is_none());
}
