//! Criterion benchmarks of the collision guard (`cargo bench -p shroud-core
//! --bench guard`): building the envelope of a 20x20 sandwich of the 30K-point
//! moving-spheres scene, and checking the demo arm (50 spheres, from
//! `launch/arms/demo_arm.toml`) against it in poses far from and near the clouds.

use criterion::{criterion_group, criterion_main, Criterion};
use shroud_core::guard::{check_arm, ArmFile, Envelope};
use shroud_core::surrogate::{fit_surrogate, FitOptions, Sides};
use std::hint::black_box;

const DEMO_ARM: &str = include_str!("../../launch/arms/demo_arm.toml");

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
}

criterion_group!(benches, guard);
criterion_main!(benches);
