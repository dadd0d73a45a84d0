//! Criterion benchmarks of the G1 smooth fitter's hot paths (paper 004): the
//! local basis of Example 1's 3264-function space, the least-squares fit of
//! its 150,528 points, and one round of parameter correction (foot points
//! across patch borders) of a limit-surface cloud.

use criterion::{criterion_group, criterion_main, Criterion};
use shroud_shapes::mesh::{
    catmull_clark, refine_parameters, ring_block, sample_limit_surface, triangle_mesh, G1Basis,
    G1Domain, QuadMesh,
};
use shroud_shapes::smooth::{correct_parameters, Sample, SmoothFitter};
use std::hint::black_box;

fn refine(mesh: QuadMesh, levels: usize) -> QuadMesh {
    (0..levels).fold(mesh, |m, _| catmull_clark(&m).expect("refine"))
}

/// Example 1's 150,528 samples: 224 x 224 per coarse patch of M_T, expressed
/// on M_T refined three times, with f_T's values.
fn example_1() -> (SmoothFitter, Vec<Sample>, Vec<f64>) {
    let coarse = triangle_mesh();
    let fine = refine(coarse.clone(), 3);
    let mut samples = Vec::new();
    let mut values = Vec::new();
    let v = coarse.vertices();
    for (f, quad) in coarse.faces().iter().enumerate() {
        for b in 0..224 {
            for a in 0..224 {
                let (u, w) = ((a as f64 + 0.5) / 224.0, (b as f64 + 0.5) / 224.0);
                let weights = [(1.0 - u) * (1.0 - w), u * (1.0 - w), u * w, (1.0 - u) * w];
                let at = |k: usize| (0..4).map(|c| weights[c] * v[quad[c] as usize][k]).sum();
                let (x, y): (f64, f64) = (at(0), at(1));
                let (face, u, v) = refine_parameters(f, u, w, 3);
                samples.push(Sample { face, u, v });
                values.push(y / 2.0 * (4.0 * (x * x + y - 1.0)).cos());
            }
        }
    }
    let fitter = SmoothFitter::new(G1Domain::new(fine).expect("domain")).expect("basis");
    (fitter, samples, values)
}

fn basis_and_fit(c: &mut Criterion) {
    let (fitter, samples, values) = example_1();
    let mut group = c.benchmark_group("smooth");
    group.sample_size(10);
    group.bench_function("basis_3264", |b| {
        b.iter(|| G1Basis::new(black_box(&fitter.domain)).expect("basis"))
    });
    group.bench_function("fit_150528_points_3264_functions", |b| {
        b.iter(|| {
            fitter
                .fit(black_box(&samples), &values, 1, 0.0)
                .expect("fit")
        })
    });
    group.finish();
}

fn parameter_correction(c: &mut Criterion) {
    let control = ring_block();
    let cloud = sample_limit_surface(&control, 100_000, 3, 5).expect("cloud");
    let samples: Vec<Sample> = cloud
        .iter()
        .map(|s| {
            let (face, u, v) = refine_parameters(s.face, s.u, s.v, 2);
            Sample { face, u, v }
        })
        .collect();
    let points: Vec<f64> = cloud.iter().flat_map(|s| s.point).collect();
    let domain = G1Domain::new(refine(control, 2)).expect("domain");
    let fitter = SmoothFitter::new(domain).expect("basis");
    let surface = fitter.fit(&samples, &points, 3, 0.0).expect("fit");
    let mut group = c.benchmark_group("smooth");
    group.sample_size(10);
    group.bench_function("correct_100k_points_8112_functions", |b| {
        b.iter(|| {
            let mut moved = samples.clone();
            correct_parameters(&surface, fitter.adjacency(), &mut moved, &points)
        })
    });
    group.finish();
}

criterion_group!(benches, basis_and_fit, parameter_correction);
criterion_main!(benches);
