//! How far the fit is from the floor (issue 27): median milliseconds of the
//! default fit, `--plain` and `--tight` (exactly what `shroud fit` means by
//! them: `nodes/src/args/surrogate.rs`), each also as a multiple of the floor
//! measured in the same run on the same clouds, and of the default sandwich
//! (`--sides sandwich`) as a multiple of the default fit of one side.
//!
//! The floor is `shroud_surrogate::floor::Floor`, the one `shroud-bench
//! surrogate` times too: the bounding box of the points' `(x, y)`, then the
//! largest `z` of each of `g x g` cells, one thread. Its grid has as many
//! cells along a side as the fit has control points (20x20 cells for a 20x20
//! fit, which has 19x19 cells: a hair more work).
//!
//! The clouds are `bench/src/paper000.rs`'s: `shroud_sim::MovingSpheres` (two
//! moving spherical scatter clouds), seed `1000 + config`, time `0.37 config`.
//! Every fit is checked certified (no violation) before it is counted.
//!
//! `cargo run --release -p shroud-surrogate --example
//! fit_floor [runs] [configs]`: `runs` warm timings per cloud and kind
//! (default 21), over `configs` clouds (default 3). `RAYON_NUM_THREADS` sets
//! the fits' threads; the floor always uses one. `fit_floor profile N g [reps]`
//! only runs `reps` default fits of N points on a g x g grid (for callgrind;
//! a last argument `sandwich` fits both sides);
//! `fit_floor fingerprint` prints a hash of every fit's output (surfaces,
//! certificates, statistics) per configuration, to show that a change of the
//! fitter's speed left its results bit for bit the same.

use shroud_graph::metrics::{live_bytes, peak_bytes, reset_peak, CountingAllocator};
use shroud_surrogate::floor::Floor;
use shroud_surrogate::{FitOptions, Sides, Surrogate, SurrogateFitter, Tightness};
use std::hint::black_box;
use std::time::Instant;

/// Counts live and peak heap bytes, so the fit's extra memory can be reported.
#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

/// The kinds timed, in the order they are printed.
const KINDS: [&str; 5] = ["floor", "default", "plain", "tight", "sandwich"];

/// The configurations of issue 27: (points, grid).
const CONFIGS: [(usize, usize); 5] = [
    (300_000, 20),
    (30_000, 10),
    (30_000, 20),
    (30_000, 40),
    (30_000, 60),
];

/// One configuration of the paper's scene, as `bench/src/paper000.rs` builds it.
fn cloud(points: usize, config: usize) -> Vec<[f32; 3]> {
    shroud_sim::MovingSpheres {
        points,
        seed: 1000 + config as u64,
        ..Default::default()
    }
    .generate(0.37 * config as f64)
    .expect("scene")
}

/// `shroud fit`'s options for a grid: the CLI's defaults but for `tightness`
/// (`--plain` is `Plain`, `--tight` is `Optimal`, neither is `Lowered`).
fn options(grid: usize, tightness: Tightness) -> FitOptions {
    FitOptions {
        cols: grid,
        rows: grid,
        tightness,
        ..Default::default()
    }
}

fn certified(s: &Surrogate) {
    for surface in s.surfaces() {
        assert_eq!(surface.certificate.violations, 0, "uncertified surrogate");
    }
}

/// Milliseconds of one run of kind `k` on `points`.
fn time_kind(k: usize, points: &[[f32; 3]], floor: &mut Floor) -> f64 {
    let grid = floor.grid();
    let start = Instant::now();
    match k {
        0 => {
            black_box(floor.cell_maxima(black_box(points)));
        }
        _ => {
            let tightness = [Tightness::Lowered, Tightness::Plain, Tightness::Optimal][(k - 1) % 3];
            let sides = if k == 4 {
                Sides::Sandwich
            } else {
                Sides::Upper
            };
            let options = FitOptions {
                sides,
                ..options(grid, tightness)
            };
            let fit = SurrogateFitter::new(options)
                .expect("fitter")
                .fit(black_box(points))
                .expect("fit");
            let ms = start.elapsed().as_secs_f64() * 1e3;
            certified(&fit);
            return ms;
        }
    }
    start.elapsed().as_secs_f64() * 1e3
}

fn median(times: &mut [f64]) -> f64 {
    times.sort_by(|a, b| a.total_cmp(b));
    times[times.len() / 2]
}

/// Peak heap MB one default fit allocates beyond what is live before it.
fn peak_mb(points: &[[f32; 3]], grid: usize) -> f64 {
    let before = live_bytes();
    reset_peak();
    let fit = SurrogateFitter::new(options(grid, Tightness::Lowered))
        .expect("fitter")
        .fit(points)
        .expect("fit");
    black_box(fit);
    (peak_bytes() - before) as f64 / 1e6
}

/// Medians per kind over `configs` clouds and `runs` interleaved runs each (the
/// kinds take turns, so a slow spell of the machine hits all of them alike).
fn measure(points: usize, grid: usize, runs: usize, configs: usize) -> [f64; 5] {
    let mut times: [Vec<f64>; 5] = Default::default();
    let mut floor = Floor::new(grid);
    for config in 0..configs {
        let pts = cloud(points, config);
        // Warm: caches, the allocator's pages, rayon's threads.
        for k in 0..KINDS.len() {
            time_kind(k, &pts, &mut floor);
        }
        for _ in 0..runs {
            for (k, out) in times.iter_mut().enumerate() {
                out.push(time_kind(k, &pts, &mut floor));
            }
        }
    }
    times.map(|mut t| median(&mut t))
}

/// `reps` default fits (of one side or of a sandwich) and nothing else, for a
/// profiler.
fn profile(points: usize, grid: usize, reps: usize, sides: Sides) {
    let pts = cloud(points, 0);
    for _ in 0..reps {
        let options = FitOptions {
            sides,
            ..options(grid, Tightness::Lowered)
        };
        let fit = SurrogateFitter::new(options)
            .expect("fitter")
            .fit(&pts)
            .expect("fit");
        certified(&fit);
    }
}

/// A hash of the `Debug` text of default, plain and sandwich fits (a
/// warm-started second frame included) of every configuration.
fn fingerprint() {
    use std::hash::{DefaultHasher, Hash, Hasher};
    for (points, grid) in CONFIGS {
        let pts = cloud(points, 1);
        let mut hasher = DefaultHasher::new();
        for (tightness, sides) in [
            (Tightness::Lowered, Sides::Upper),
            (Tightness::Plain, Sides::Upper),
            (Tightness::Lowered, Sides::Sandwich),
        ] {
            let options = FitOptions {
                sides,
                ..options(grid, tightness)
            };
            let mut fitter = SurrogateFitter::new(options).expect("fitter");
            for _ in 0..2 {
                format!("{:?}", fitter.fit(&pts).expect("fit")).hash(&mut hasher);
            }
        }
        println!("{points} {grid}x{grid}: {:016x}", hasher.finish());
    }
}

fn main() {
    if std::env::args().nth(1).as_deref() == Some("fingerprint") {
        return fingerprint();
    }
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    if std::env::args().nth(1).as_deref() == Some("profile") {
        let at = |i: usize, default: usize| args.get(i).copied().unwrap_or(default);
        let sandwich = std::env::args().any(|a| a == "sandwich");
        let sides = if sandwich {
            Sides::Sandwich
        } else {
            Sides::Upper
        };
        return profile(at(0, 300_000), at(1, 20), at(2, 3), sides);
    }
    let runs = args.first().copied().unwrap_or(21).max(1);
    let configs = args.get(1).copied().unwrap_or(3).max(1);
    let threads = rayon::current_num_threads();
    println!(
        "median ms of {runs} warm runs x {configs} clouds (moving spheres); fits: {threads} rayon threads, floor: 1 thread"
    );
    println!("| N | grid | floor | default | plain | tight | sandwich | default/floor | plain/floor | tight/floor | sandwich/default | peak MB (default) | cloud MB |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut default_30k = Vec::new();
    for (points, grid) in CONFIGS {
        let m = measure(points, grid, runs, configs);
        let peak = peak_mb(&cloud(points, 0), grid);
        println!(
            "| {}K | {grid}x{grid} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.2}x | {:.2}x | {:.2}x | {:.2}x | {:.2} | {:.2} |",
            points / 1000,
            m[0],
            m[1],
            m[2],
            m[3],
            m[4],
            m[1] / m[0],
            m[2] / m[0],
            m[3] / m[0],
            m[4] / m[1],
            peak,
            (points * 12) as f64 / 1e6,
        );
        if points == 30_000 {
            default_30k.push((grid, m[1]));
        }
    }
    if let (Some(&(g0, first)), Some(&(g1, last))) = (default_30k.first(), default_30k.last()) {
        println!(
            "\n30K default fit: {g1}x{g1} takes {:.2}x the {g0}x{g0} time",
            last / first
        );
    }
}
