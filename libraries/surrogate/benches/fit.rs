//! Criterion benchmarks of the fitting hot paths (`cargo bench -p shroud-surrogate --bench fit`).
//! The paper's tables are reproduced by `shroud-bench surrogate`; these isolate
//! the pieces: the whole surface fit, the Section 5 curve heuristic and the
//! Section 4 broken-line heuristic.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use shroud_surrogate::{
    fit_broken_line_above, fit_curve_above, FitOptions, SurrogateFitter, Tightness,
};
use std::hint::black_box;

fn spheres(points: usize) -> Vec<[f32; 3]> {
    shroud_sim::MovingSpheres {
        points,
        ..Default::default()
    }
    .generate(0.3)
    .expect("default scene is valid")
}

fn surface_fit(c: &mut Criterion) {
    let mut group = c.benchmark_group("surface_fit_20x20");
    group.sample_size(20);
    for n in [30_000usize, 300_000] {
        let pts = spheres(n);
        group.throughput(Throughput::Elements(n as u64));
        for (name, tightness) in [
            ("plain", Tightness::Plain),
            ("default", Tightness::Lowered),
            ("tight", Tightness::Optimal),
        ] {
            let options = FitOptions {
                tightness,
                ..Default::default()
            };
            group.bench_with_input(BenchmarkId::new(name, n), &pts, |b, pts| {
                b.iter(|| {
                    SurrogateFitter::new(options.clone()).and_then(|mut f| f.fit(black_box(pts)))
                })
            });
        }
        let mut warm = SurrogateFitter::new(FitOptions::default()).expect("valid options");
        group.bench_with_input(BenchmarkId::new("default_warm", n), &pts, |b, pts| {
            b.iter(|| warm.fit(black_box(pts)))
        });
    }
    group.finish();
}

fn curve_heuristics(c: &mut Criterion) {
    let samples: Vec<(f64, f64)> = (0..10_000)
        .map(|i| {
            let s = (i as f64 * 0.618_033_988_75).fract() * 19.0;
            (s, (s * 0.7).sin() * 2.0 - ((i * 7919) % 100) as f64 * 0.01)
        })
        .collect();
    c.bench_function("section5_curve_10k_samples_n20", |b| {
        b.iter(|| fit_curve_above(black_box(&samples), 20))
    });
    let values: Vec<f64> = (0..60).map(|i| (i as f64 * 0.4).sin() * 3.0).collect();
    let free = vec![false; 60];
    c.bench_function("section4_broken_line_n60", |b| {
        b.iter(|| fit_broken_line_above(black_box(&values), &free, None))
    });
}

criterion_group!(benches, surface_fit, curve_heuristics);
criterion_main!(benches);
