//! Timing harness of the surface fit: median milliseconds per phase (domain pass,
//! binning pass, one certification pass) and of the whole fit, for the moving-sphere
//! scene at N = 10K..300K on a 20x20 grid and at N = 30K on n x n grids, plus the
//! peak heap the fit allocates beyond the input cloud.
//!
//! `cargo run --release -p shroud-surrogate --example phases [reps] [points grid]`
//! (with `points grid`, only that configuration). `MIN=1` reports the best run
//! instead of the median (steadier on a shared machine), `CPU=1` CPU time summed
//! over threads instead of wall time, and `RAYON_NUM_THREADS` sets the threads.

use shroud_geometry::spline::UniformCubicSurface;
use shroud_geometry::Frame;
use shroud_surrogate::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Counts live and peak heap bytes, so the harness can report the fit's memory.
struct PeakAlloc;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for PeakAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(live, Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static ALLOCATOR: PeakAlloc = PeakAlloc;

/// CPU time of all threads of this process in ns (`/proc/self/task/*/schedstat`),
/// which a busy machine inflates much less than wall time.
fn cpu_ns() -> u64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return 0;
    };
    tasks
        .flatten()
        .filter_map(|task| std::fs::read_to_string(task.path().join("schedstat")).ok())
        .filter_map(|stat| {
            stat.split_whitespace()
                .next()
                .and_then(|ns| ns.parse::<u64>().ok())
        })
        .sum()
}

/// Median wall time in ms, or with `CPU=1` in the environment the median CPU time
/// summed over threads.
fn median_ms(reps: usize, mut run: impl FnMut()) -> f64 {
    let cpu = std::env::var("CPU").is_ok();
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let (t0, c0) = (Instant::now(), if cpu { cpu_ns() } else { 0 });
            run();
            if cpu {
                (cpu_ns() - c0) as f64 / 1e6
            } else {
                t0.elapsed().as_secs_f64() * 1e3
            }
        })
        .collect();
    times.sort_by(|a, b| a.total_cmp(b));
    // `MIN=1`: the best run (robust on a busy machine) instead of the median.
    times[if std::env::var_os("MIN").is_some() {
        0
    } else {
        reps / 2
    }]
}

struct Row {
    domain: f64,
    bin: f64,
    bin_fine: f64,
    certify: f64,
    plain: f64,
    lowered: f64,
    corrected: u64,
    peak_plain: f64,
    peak_lowered: f64,
}

/// Heap bytes (MB) `run` allocates beyond what is live when it starts, at most.
fn peak_mb(run: impl FnOnce()) -> f64 {
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    run();
    (PEAK.load(Ordering::Relaxed) - before) as f64 / 1e6
}

fn measure(points: usize, grid: usize, reps: usize) -> Row {
    let pts = shroud_sim::MovingSpheres {
        points,
        ..Default::default()
    }
    .generate(0.3)
    .expect("scene");
    let frame = Frame::from_direction(glam::DVec3::new(0.0, 0.0, -1.0)).expect("frame");
    let opts = |tightness| FitOptions {
        cols: grid,
        rows: grid,
        tightness,
        ..Default::default()
    };
    let domain = domain_of_cloud(&pts, &frame, grid, grid).expect("domain");
    let domain_ms = median_ms(reps, || {
        std::hint::black_box(domain_of_cloud(&pts, &frame, grid, grid).expect("domain"));
    });
    // The candidates' resolution (4 x 4 sub-cells) and the check points' (8 x 8),
    // which the fit bins at when the cloud fills them.
    let bin_at = |sub| {
        median_ms(reps, || {
            std::hint::black_box(bins::bin_points(&pts, &frame, &domain, &[Side::Upper], sub));
        })
    };
    let (bin, bin_fine) = (bin_at(4), bin_at(8));
    let fitted = fit_surrogate(&pts, &opts(Tightness::Lowered)).expect("fit");
    let upper = fitted.upper.expect("upper surface");
    // A surface that already passes: one certification pass, no correction.
    let certify = median_ms(reps, || {
        let mut surface: UniformCubicSurface = upper.surface.clone();
        std::hint::black_box(
            certify_surface(&pts, &frame, &domain, &mut surface, Side::Upper).expect("certify"),
        );
    });
    let fit_ms = |tightness| {
        let mut fitter = SurrogateFitter::new(opts(tightness)).expect("fitter");
        median_ms(reps, || {
            std::hint::black_box(fitter.fit(&pts).expect("fit"));
        })
    };
    let (plain, lowered) = (fit_ms(Tightness::Plain), fit_ms(Tightness::Lowered));
    let peak_of = |tightness| {
        peak_mb(|| {
            std::hint::black_box(fit_surrogate(&pts, &opts(tightness)).expect("fit"));
        })
    };
    Row {
        domain: domain_ms,
        bin,
        bin_fine,
        certify,
        plain,
        lowered,
        corrected: upper.certificate.corrected_points,
        peak_plain: peak_of(Tightness::Plain),
        peak_lowered: peak_of(Tightness::Lowered),
    }
}

fn print(label: &str, r: &Row) {
    println!(
        "{label:>14} | {:6.2} {:6.2} {:6.2} {:7.2} | {:6.2} {:7.2} | {:9} | {:5.2} {:5.2}",
        r.domain,
        r.bin,
        r.bin_fine,
        r.certify,
        r.plain,
        r.lowered,
        r.corrected,
        r.peak_plain,
        r.peak_lowered
    );
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    let reps = args.first().copied().unwrap_or(31).max(1);
    let threads = rayon::current_num_threads();
    let statistic = if std::env::var_os("MIN").is_some() {
        "best"
    } else {
        "median"
    };
    println!("{statistic} ms of {reps} runs; moving spheres t=0.3, 20x20 unless given, upper side, {threads} threads");
    println!("phases: domain pass, binning at 4x4 and 8x8 sub-cells, one certification pass (no correction);");
    println!("fits: whole fit, Plain and Lowered (default); corrected: points the Lowered fit raised; peak heap MB");
    println!(
        "{:>14} | {:>6} {:>6} {:>6} {:>7} | {:>6} {:>7} | {:>9} | {:>5} {:>5}",
        "", "domain", "bin4", "bin8", "certify", "plain", "lowered", "corrected", "peakP", "peakL"
    );
    let configs: Vec<(usize, usize)> = match args[..] {
        [_, n, grid, ..] => vec![(n, grid)],
        _ => [10_000, 30_000, 50_000, 100_000, 300_000]
            .map(|n| (n, 20))
            .into_iter()
            .chain([10, 20, 30, 40, 50, 60].map(|grid| (30_000, grid)))
            .collect(),
    };
    for (n, grid) in configs {
        print(&format!("N={n} {grid}x{grid}"), &measure(n, grid, reps));
    }
}
