//! Criterion benchmarks of the blender's hot paths (paper 001): one whole blend of
//! a hemisphere onto a plane, the dense RBF solve at the paper's 617 centres, and
//! the marching-tetrahedra sampling.

#[path = "../tests/blend_scenes/mod.rs"]
mod blend_scenes;

use criterion::{criterion_group, criterion_main, Criterion};
use glam::DVec3;
use shroud_geometry::cloud::BoundaryParams;
use shroud_shapes::blend::rbf::{build_constraints, Rbf};
use shroud_shapes::blend::{blend, sample_zero_set, BlendParams, Child, LocalAdjust, Prepared};
use std::hint::black_box;

fn scene() -> (Prepared, Child) {
    let parent =
        Prepared::new(&blend_scenes::plane(2.0, 20_000, 0.0, 1), "parent", 12).expect("plane");
    let cloud =
        Prepared::new(&blend_scenes::hemisphere(0.5, 4_000), "child", 12).expect("hemisphere");
    let child = Child::new(cloud, None, &BoundaryParams::default()).expect("rim");
    (parent, child)
}

fn whole_blend(c: &mut Criterion) {
    let (parent, child) = scene();
    let placement = child.placement(
        DVec3::new(0.2, -0.1, 0.0),
        DVec3::Z,
        &LocalAdjust::default(),
    );
    let mut params = BlendParams::default();
    params.rbf.max_centres = 617;
    let mut group = c.benchmark_group("blend");
    group.sample_size(10);
    group.bench_function("hemisphere_on_plane_617", |b| {
        b.iter(|| blend(&parent, &child, black_box(&placement), &params).expect("blend"))
    });
    group.finish();
}

fn rbf_parts(c: &mut Criterion) {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let (pts, nrm): (Vec<DVec3>, Vec<DVec3>) = (0..206)
        .map(|i| {
            let y = 1.0 - 2.0 * (f64::from(i) + 0.5) / 206.0;
            let s = (1.0 - y * y).sqrt();
            let n = DVec3::new(
                s * (golden * f64::from(i)).cos(),
                y,
                s * (golden * f64::from(i)).sin(),
            );
            (n, n)
        })
        .unzip();
    let cons = build_constraints(&pts, &nrm, 0.05);
    let mut group = c.benchmark_group("rbf");
    group.sample_size(10);
    group.bench_function(format!("dense_solve_{}", cons.points.len()), |b| {
        b.iter(|| Rbf::interpolate(black_box(&cons.points), &cons.values).expect("regular"))
    });
    let rbf = Rbf::interpolate(&cons.points, &cons.values).expect("regular");
    let inside = |_: DVec3| true;
    group.bench_function("marching_tetrahedra_sphere", |b| {
        b.iter(|| {
            sample_zero_set(&rbf, &pts, DVec3::ZERO, 0.03, &inside, 1_000_000).expect("surface")
        })
    });
    group.finish();
}

criterion_group!(benches, whole_blend, rbf_parts);
criterion_main!(benches);
