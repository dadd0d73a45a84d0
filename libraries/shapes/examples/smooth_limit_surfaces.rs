//! Paper 004, Section 6.2 beside Table 4: parametric G1 fits of large point
//! clouds sampled from the Catmull-Clark limit surfaces of closed quad meshes,
//! with three rounds of parameter correction; then the performance
//! target (550K points, 44K functions, three corrections) and the memory of a
//! fit against points and non-zeros, measured by a counting allocator.
//!
//! `cargo run --release -p shroud-shapes --example smooth_limit_surfaces`

use shroud_graph::metrics::{live_bytes, peak_bytes, reset_peak, CountingAllocator};
use shroud_shapes::mesh::{
    catmull_clark, l_block, polycube, refine_parameters, ring_block, sample_limit_surface,
    step_block, G1Domain, QuadMesh,
};
use shroud_shapes::smooth::{Sample, SmoothFitter};
use std::time::Instant;

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

/// Peak heap bytes above what was live when `f` started.
fn peak_during<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = live_bytes();
    reset_peak();
    let out = f();
    (out, peak_bytes().saturating_sub(base))
}

/// `mesh` scaled and centred into a box whose longest side is 100 (the
/// paper's models, Table 4).
fn into_box_100(mesh: QuadMesh) -> QuadMesh {
    let (vertices, faces) = mesh.into_parts();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &vertices {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let scaled = vertices
        .iter()
        .map(|p| [0, 1, 2].map(|k| (p[k] - (lo[k] + hi[k]) / 2.0) * 100.0 / size))
        .collect();
    QuadMesh::new(scaled, faces).expect("scaling keeps the mesh valid")
}

/// A cloud of `count` points on the limit surface of `control`, with its
/// parameters on `control` refined `levels` times (the fitting domain).
fn limit_cloud(control: &QuadMesh, count: usize, levels: usize) -> (Vec<Sample>, Vec<f64>) {
    let cloud = sample_limit_surface(control, count, 7, 6).expect("limit surface");
    let samples = cloud
        .iter()
        .map(|s| {
            let (face, u, v) = refine_parameters(s.face, s.u, s.v, levels);
            Sample { face, u, v }
        })
        .collect();
    let points = cloud.iter().flat_map(|s| s.point).collect();
    (samples, points)
}

/// The fitting domain: `mesh` refined `levels` (at least 1) times, so that its
/// EVs are isolated and `G1Domain` keeps it as it is (the samples' faces
/// refer to it).
fn domain(mesh: &QuadMesh, levels: usize) -> G1Domain {
    let refined = (0..levels).fold(mesh.clone(), |m, _| catmull_clark(&m).expect("refine"));
    let domain = G1Domain::new(refined).expect("domain");
    assert!(!domain.refined, "the samples' faces would not match");
    domain
}

struct Run {
    functions: usize,
    points: usize,
    before: [f64; 3],
    after: [f64; 3],
    basis_s: f64,
    total_s: f64,
}

/// Builds the space over `control` refined `levels` times and fits `count`
/// limit-surface points with three corrections.
fn run(control: &QuadMesh, levels: usize, count: usize) -> Run {
    let (samples, points) = limit_cloud(control, count, levels);
    let start = Instant::now();
    let fitter = SmoothFitter::new(domain(control, levels)).expect("basis");
    let basis_s = start.elapsed().as_secs_f64();
    let fit = fitter
        .fit_parametric(&samples, &points, 0.0, 3)
        .expect("fit");
    let total_s = start.elapsed().as_secs_f64();
    let e = |r: usize| [fit.rounds[r].min, fit.rounds[r].max, fit.rounds[r].rmse];
    Run {
        functions: fitter.basis.len(),
        points: samples.len(),
        before: e(0),
        after: e(3),
        basis_s,
        total_s,
    }
}

fn main() {
    println!("# G1 parametric fits of Catmull-Clark limit surfaces (paper 004, Section 6.2)\n");
    println!(
        "{} rayon threads; models in a box of longest side 100, as the paper's; lambda = 0\n",
        rayon::current_num_threads()
    );
    let bar: Vec<[i32; 3]> = (0..10).map(|k| [0, 0, k]).collect();
    let models = [
        ("L block", into_box_100(l_block()), 3, 560_000),
        ("ring", into_box_100(ring_block()), 3, 600_000),
        ("steps", into_box_100(step_block()), 3, 600_000),
        (
            "bar of 10",
            into_box_100(polycube(&bar).expect("bar")),
            3,
            550_000,
        ),
    ];
    println!("## Table 4 beside ours\n");
    println!("| model | dim, n_P | min | L-inf | RMSE | 3 x correction: min | L-inf | RMSE | basis (s) | total (s) |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let paper = [
        (
            "paper: bird",
            "100386, 549180",
            "2.139e-07",
            "1.380e-01",
            "3.250e-03",
            "1.371e-10",
            "7.540e-04",
            "6.482e-06",
        ),
        (
            "paper: dinosaur",
            "44311, 675000",
            "1.244e-06",
            "5.370e-02",
            "1.640e-03",
            "8.740e-10",
            "3.360e-04",
            "5.392e-06",
        ),
        (
            "paper: hammer",
            "44347, 675000",
            "2.477e-06",
            "1.100e-01",
            "2.800e-03",
            "5.445e-09",
            "4.510e-02",
            "1.830e-04",
        ),
        (
            "paper: hand",
            "68034, 557568",
            "2.390e-06",
            "6.660e-02",
            "3.080e-03",
            "3.427e-08",
            "6.750e-03",
            "2.130e-04",
        ),
        (
            "paper: rabbit",
            "80003, 914628",
            "1.143e-06",
            "8.730e-02",
            "2.910e-03",
            "3.477e-10",
            "7.688e-05",
            "2.195e-06",
        ),
        (
            "paper: venus",
            "44306, 588000",
            "1.734e-06",
            "9.930e-02",
            "2.600e-03",
            "1.416e-09",
            "4.550e-04",
            "1.035e-05",
        ),
    ];
    for (name, dims, a, b, c, d, e, f) in paper {
        println!("| {name} | {dims} | {a} | {b} | {c} | {d} | {e} | {f} | | |");
    }
    for (name, control, levels, count) in &models {
        let r = run(control, *levels, *count);
        println!(
            "| **shroud: {name}** | {}, {} | {:.3e} | {:.3e} | {:.3e} | {:.3e} | {:.3e} | {:.3e} | {:.2} | {:.2} |",
            r.functions, r.points, r.before[0], r.before[1], r.before[2], r.after[0], r.after[1], r.after[2], r.basis_s, r.total_s
        );
    }
    memory(&models[1].1);
}

/// Peak heap of a fit (basis excluded) against points, on one space, and
/// against non-zeros, for one cloud.
fn memory(control: &QuadMesh) {
    println!("\n## Memory of a fit (peak heap above the inputs, counting allocator)\n");
    println!("| levels | functions | non-zeros | points | peak (MB) | bytes / point | bytes / (point + non-zero) |");
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    let cases = [
        (1, 100_000),
        (1, 200_000),
        (1, 400_000),
        (1, 800_000),
        (2, 400_000),
        (3, 400_000),
    ];
    for (levels, count) in cases {
        let (samples, points) = limit_cloud(control, count, levels);
        let fitter = SmoothFitter::new(domain(control, levels)).expect("basis");
        let nonzeros = fitter.normal_matrix_nonzeros();
        let (_, peak) = peak_during(|| {
            fitter
                .fit_parametric(&samples, &points, 0.0, 1)
                .expect("fit")
        });
        println!(
            "| {levels} | {} | {nonzeros} | {count} | {:.1} | {:.0} | {:.0} |",
            fitter.basis.len(),
            peak as f64 / 1e6,
            peak as f64 / count as f64,
            peak as f64 / (count + nonzeros) as f64
        );
    }
}
