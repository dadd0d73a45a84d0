//! Criterion benchmarks of the collision guard (`cargo bench -p shroud-guard
//! --bench guard`): building the envelope of a 20x20 sandwich of the 30K-point
//! moving-spheres scene, and checking the demo arm (50 spheres, from
//! `launch/arms/demo_arm.toml`) against it in poses far from and near the clouds,
//! and the whole decision ([`CollisionGuard::decide`]) over one view and over
//! three (top, front, side sandwiches of the same cloud): judging by the
//! occupied space alone (`ignore`), counting unseen space (`stop`, the
//! default), and counting the space outside a stated field of view as well
//! (`stop_fov`: a cone from 4 m back along each view's direction), and with
//! the most rays without a return a cloud may list on top (`stop_fov_dark`:
//! 1024 cones of 0.6 degrees on a 32 x 32 grid across that cone, the worst
//! case of `guard::no_return`'s search). Each decision is measured in two
//! poses: over the larger sphere (a contact) and near but clear (the first
//! pose on the way from `FAR` to `OVER` whose clearance is under 0.25 m but
//! not a stop). In the pose over the larger sphere, the first decision
//! after new clouds is measured too (`decide_first_after_new_cloud_*`): a
//! guard whose envelopes have kept no refinement splits yet, cloned afresh
//! for every decision outside the timing, as a fit node's new cloud every
//! frame leaves it.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use shroud_guard::{
    check_arm, ArmFile, CollisionGuard, Envelope, GuardPolicy, SurrogateInput, UnobservedPolicy,
};
use shroud_msg::{Aperture, DarkCone, FieldOfView, NoReturn, MAX_DARK_CONES};
use shroud_surrogate::{fit_surrogate, FitOptions, Sides};
use std::hint::black_box;

const DEMO_ARM: &str = include_str!("../../../launch/arms/demo_arm.toml");

/// Folded up above the mount's side of the scene.
const FAR: [f64; 6] = [0.0, 1.2, 2.2, 1.0, 0.0, 0.0];
/// Reaching over the larger sphere.
const OVER: [f64; 6] = [0.6, 0.7, 0.9, 0.6, 0.0, 0.0];
/// Dipping into the larger sphere (the guard stops).
const NEAR: [f64; 6] = [0.6, 0.3, 0.5, 0.4, 0.5, 0.3];

fn guard(c: &mut Criterion) {
    let points = shroud_sim::MovingSpheres::default()
        .generate(0.3)
        .expect("default scene is valid");
    let options = FitOptions {
        sides: Sides::Sandwich,
        ..FitOptions::default()
    };
    let surrogate = fit_surrogate(&points, &options).expect("the scene fits");
    let file = ArmFile::from_toml_str(DEMO_ARM).expect("the demo arm is valid");
    let mut group = c.benchmark_group("guard");
    group.bench_function("envelope_new_20x20_sandwich", |b| {
        b.iter(|| Envelope::new(black_box(&surrogate)))
    });
    let envelope = Envelope::new(&surrogate).expect("a valid surrogate");
    for (name, q) in [("far", FAR), ("over", OVER), ("near", NEAR)] {
        let pose = file.arm.forward(&q).expect("valid joint values");
        let report = check_arm(&envelope, &pose, &file.guard).expect("valid pose");
        eprintln!(
            "pose {name}: {} shapes, min clearance {:.4} (link {:?}), stop {}",
            pose.shapes.len(),
            report.min_clearance,
            report.closest_link,
            report.stop
        );
        group.bench_function(format!("check_arm_50_spheres_{name}"), |b| {
            b.iter(|| check_arm(black_box(&envelope), black_box(&pose), &file.guard))
        });
        group.bench_function(format!("forward_and_check_{name}"), |b| {
            b.iter(|| {
                let pose = file.arm.forward(black_box(&q))?;
                check_arm(&envelope, &pose, &file.guard)
            })
        });
    }
    group.finish();
    views(c, &points, &file);
}

/// The first pose on the straight joint-space way from `FAR` to `OVER` whose
/// clearance from the top view is under 0.25 m and above the stop distance.
fn near_but_clear(envelope: &Envelope, file: &ArmFile) -> [f64; 6] {
    for step in 0..=200 {
        let t = step as f64 / 200.0;
        let q: [f64; 6] = std::array::from_fn(|i| FAR[i] + t * (OVER[i] - FAR[i]));
        let pose = file.arm.forward(&q).expect("valid joint values");
        let report = check_arm(envelope, &pose, &file.guard).expect("valid pose");
        if !report.stop && report.min_clearance < 0.25 {
            return q;
        }
    }
    panic!("no near-but-clear pose between FAR and OVER on this scene");
}

/// The decision over 1 and 3 views, in the pose over the larger sphere (on
/// today's scene a contact: clearance 0) and in a pose near but clear of it.
fn views(c: &mut Criterion, points: &[[f32; 3]], file: &ArmFile) {
    let directions = [[0.0, 0.0, -1.0], [0.0, -1.0, 0.0], [-1.0, 0.0, 0.0]];
    let inputs: Vec<SurrogateInput> = directions
        .iter()
        .map(|&direction| {
            let options = FitOptions {
                direction,
                sides: Sides::Sandwich,
                ..FitOptions::default()
            };
            let surrogate = fit_surrogate(points, &options).expect("the scene fits");
            SurrogateInput {
                envelope: Envelope::new(&surrogate).expect("a valid surrogate"),
                stamp_ns: 0,
                sequence: 0,
                pipeline_ns: 0,
                published_ns: 0,
                position_error: 0.0,
            }
        })
        .collect();
    let near_clear = near_but_clear(&inputs[0].envelope, file);
    let poses = [("", OVER), ("_near_clear", near_clear)];
    let links: Vec<String> = file.arm.links().iter().map(|l| l.name.clone()).collect();
    let mut group = c.benchmark_group("guard_views");
    let cases = [
        ("ignore", UnobservedPolicy::Ignore, false, false),
        ("stop", UnobservedPolicy::Stop, false, false),
        ("stop_fov", UnobservedPolicy::Stop, true, false),
        ("stop_fov_dark", UnobservedPolicy::Stop, true, true),
    ];
    for count in [1, 3] {
        for ((label, unobserved, fov, dark), (suffix, q)) in cases
            .into_iter()
            .flat_map(|case| poses.map(|pose| (case, pose)))
        {
            let pose = file.arm.forward(&q).expect("valid joint values");
            let policy = GuardPolicy {
                max_skew_ns: u64::MAX,
                unobserved,
                ..GuardPolicy::default()
            };
            let names = (0..count).map(|i| format!("view{i}")).collect();
            let mut guard = CollisionGuard::new(names, links.clone(), policy, file.guard)
                .expect("valid settings");
            for (view, input) in inputs.iter().take(count).enumerate() {
                let mut input = input.clone();
                if fov {
                    input.envelope = input
                        .envelope
                        .with_field_of_view(Some(cone_along(directions[view])))
                        .expect("a valid field of view");
                }
                if dark {
                    input.envelope = input
                        .envelope
                        .with_no_return(Some(&dark_grid(directions[view])))
                        .expect("valid cones");
                }
                guard.accept(view, input, 0, 0).expect("fresh");
            }
            // Before any decision: no refinement split is kept yet.
            let fresh = guard.clone();
            let decision = guard.decide(&pose.shapes, 0).expect("valid pose");
            eprintln!(
                "{count} view(s), {label}{suffix}: {:?}, min clearance {:.4}",
                decision.verdict,
                decision.report.as_ref().map_or(0.0, |r| r.min_clearance)
            );
            let name = format!("decide_50_spheres_{count}_views_{label}{suffix}");
            group.bench_function(name, |b| {
                b.iter(|| guard.decide(black_box(&pose.shapes), 0))
            });
            if suffix.is_empty() {
                let name = format!("decide_first_after_new_cloud_{count}_views_{label}");
                group.bench_function(name, |b| {
                    b.iter_batched_ref(
                        || fresh.clone(),
                        |guard| guard.decide(black_box(&pose.shapes), 0),
                        BatchSize::SmallInput,
                    )
                });
            }
        }
    }
    group.finish();
}

/// [`MAX_DARK_CONES`] thin cones from [`cone_along`]'s apex, on a 32 x 32
/// grid of directions across its 40 degrees.
fn dark_grid(direction: [f64; 3]) -> NoReturn {
    let axis = glam::DVec3::from_array(direction);
    let (e1, e2) = axis.any_orthonormal_pair();
    let side = (MAX_DARK_CONES as f64).sqrt() as usize;
    let span = 40f64.to_radians().tan();
    let cones = (0..side * side)
        .map(|k| {
            let (i, j) = ((k % side) as f64, (k / side) as f64);
            let at = |x: f64| span * (2.0 * (x + 0.5) / side as f64 - 1.0);
            DarkCone {
                axis: (axis + e1 * at(i) + e2 * at(j)).normalize().to_array(),
                half_angle: 0.6f64.to_radians(),
            }
        })
        .collect();
    NoReturn {
        apex: direction.map(|d| -4.0 * d),
        cones,
    }
}

/// A 40-degree cone from 4 m back along `direction`, 8 m deep.
fn cone_along(direction: [f64; 3]) -> FieldOfView {
    FieldOfView {
        apex: direction.map(|d| -4.0 * d),
        axis: direction,
        aperture: Aperture::Cone {
            half_angle: 40f64.to_radians(),
        },
        max_range: 8.0,
    }
}

criterion_group!(benches, guard);
criterion_main!(benches);
