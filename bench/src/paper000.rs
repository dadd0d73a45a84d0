//! Paper 000 (Myles & Peters), Section 7: Table 1 (time vs N at 20 x 20), Table 2
//! (time vs n at N = 30K), Figure 9 (iterations per line), and the Section 3
//! trial-and-error baseline against Heuristic(σ, b, λ).
//!
//! Every fit time of Tables 1 and 2 is also printed as a multiple of the floor
//! (issue 27: `shroud_surrogate::floor`, the bounding box of the cloud and each
//! cell's largest height, one thread) timed in the same run, on the same
//! clouds, its runs taking turns with the default and plain fits'.

use super::{median, timed, BenchArgs};
use anyhow::Result;
use shroud_sim::MovingSpheres;
use shroud_surrogate::floor::Floor;
use shroud_surrogate::{
    fit_curve_above, fit_curve_by_trial_and_error, FitOptions, Histogram, Sides, SurrogateFitter,
    Tightness,
};
use std::hint::black_box;

/// Table 1 of the paper: milliseconds on a 2.4 GHz Pentium 4, 20 x 20.
const TABLE1: [(usize, f64); 5] = [
    (10_000, 14.5),
    (30_000, 42.5),
    (50_000, 71.0),
    (100_000, 141.0),
    (300_000, 445.0),
];
/// Table 2 of the paper: milliseconds for N = 30K and an n x n spline.
const TABLE2: [(usize, f64); 6] = [
    (10, 42.5),
    (20, 42.5),
    (30, 45.0),
    (40, 51.0),
    (50, 55.5),
    (60, 64.5),
];

/// One configuration of the paper's scene: seed and time both vary.
fn cloud(points: usize, config: usize) -> Result<Vec<[f32; 3]>> {
    let scene = MovingSpheres {
        points,
        seed: 1000 + config as u64,
        ..Default::default()
    };
    Ok(scene.generate(0.37 * config as f64)?)
}

struct Timings {
    /// The floor on a grid of as many cells a side as the fit has control
    /// points, one thread.
    floor_ms: f64,
    default_ms: f64,
    plain_ms: f64,
    tight_ms: f64,
    /// Both sides (`--sides sandwich`), default tightness, cold.
    sandwich_ms: f64,
    /// A fresh fitter on each frame of the stream the warm fitter sees.
    cold_stream_ms: f64,
    warm_ms: f64,
}

impl Timings {
    /// The ratio columns: default, plain, tight and warm each over the floor.
    fn over_floor(&self) -> String {
        [self.default_ms, self.plain_ms, self.tight_ms, self.warm_ms]
            .map(|ms| format!(" {:.2}x |", ms / self.floor_ms))
            .concat()
    }
}

/// Median cold-fit times over `configs x runs` fits, plus a stream fitted warm
/// (and, with `sides_and_streams`, sandwiches and the stream fitted cold), and the floor's median over a run
/// before each default, plain and sandwich fit.
fn measure(
    points: usize,
    grid: usize,
    args: &BenchArgs,
    sides_and_streams: bool,
) -> Result<Timings> {
    let (configs, runs) = if args.quick {
        (2, 3)
    } else {
        (args.configs.max(1), args.runs.max(1))
    };
    let options = |tightness| FitOptions {
        cols: grid,
        rows: grid,
        tightness,
        ..Default::default()
    };
    let (mut default, mut plain, mut tight, mut sandwiches) = (vec![], vec![], vec![], vec![]);
    let (mut warm, mut cold_stream) = (vec![], vec![]);
    let (mut floor, mut floor_ms) = (Floor::new(grid), vec![]);
    for config in 0..configs {
        let pts = cloud(points, config)?;
        black_box(floor.cell_maxima(&pts));
        for (tightness, sides, out) in [
            (Tightness::Lowered, Sides::Upper, &mut default),
            (Tightness::Plain, Sides::Upper, &mut plain),
            (Tightness::Lowered, Sides::Sandwich, &mut sandwiches),
        ] {
            if sides == Sides::Sandwich && !sides_and_streams {
                continue;
            }
            for _ in 0..runs {
                let ((), ms) = timed(|| {
                    black_box(floor.cell_maxima(black_box(&pts)));
                });
                floor_ms.push(ms);
                let mut fitter = SurrogateFitter::new(FitOptions {
                    sides,
                    ..options(tightness)
                })?;
                let (fit, ms) = timed(|| fitter.fit(&pts));
                certified(&fit?)?;
                out.push(ms);
            }
        }
        for _ in 0..runs.min(5) {
            let mut fitter = SurrogateFitter::new(options(Tightness::Optimal))?;
            let (fit, ms) = timed(|| fitter.fit(&pts));
            certified(&fit?)?;
            tight.push(ms);
        }
        let stream = fit_stream(points, grid, config, runs, sides_and_streams)?;
        warm.extend(stream.warm);
        cold_stream.extend(stream.cold);
    }
    Ok(Timings {
        floor_ms: median(&mut floor_ms),
        default_ms: median(&mut default),
        plain_ms: median(&mut plain),
        tight_ms: median(&mut tight),
        sandwich_ms: median(&mut sandwiches),
        cold_stream_ms: median(&mut cold_stream),
        warm_ms: median(&mut warm),
    })
}

/// Fit times of one stream, per frame after the first.
struct Stream {
    warm: Vec<f64>,
    cold: Vec<f64>,
}

/// A 30 Hz stream of frames fitted by one warm-started fitter and, if `cold`,
/// on the same frames by a fresh fitter each (the two take turns at being
/// first on a frame, so that neither always meets the new cloud out of cache).
fn fit_stream(
    points: usize,
    grid: usize,
    config: usize,
    frames: usize,
    cold: bool,
) -> Result<Stream> {
    let scene = MovingSpheres {
        points,
        seed: 1000 + config as u64,
        ..Default::default()
    };
    let options = FitOptions {
        cols: grid,
        rows: grid,
        ..Default::default()
    };
    let mut fitter = SurrogateFitter::new(options.clone())?;
    let mut stream = Stream {
        warm: Vec::with_capacity(frames),
        cold: Vec::with_capacity(frames),
    };
    for frame in 0..=frames {
        let pts = scene.generate(0.37 * config as f64 + frame as f64 / 30.0)?;
        let mut warm = || -> Result<f64> {
            let (fit, ms) = timed(|| fitter.fit(&pts));
            certified(&fit?)?;
            Ok(ms)
        };
        let cold_fit = || -> Result<f64> {
            if !cold {
                return Ok(f64::NAN);
            }
            let mut fresh = SurrogateFitter::new(options.clone())?;
            let (fit, ms) = timed(|| fresh.fit(&pts));
            certified(&fit?)?;
            Ok(ms)
        };
        let (warm_ms, cold_ms) = if frame % 2 == 0 {
            let warm_ms = warm()?;
            (warm_ms, cold_fit()?)
        } else {
            let cold_ms = cold_fit()?;
            (warm()?, cold_ms)
        };
        // The first frame warms nothing: both fits are cold.
        if frame > 0 {
            stream.warm.push(warm_ms);
            if cold {
                stream.cold.push(cold_ms);
            }
        }
    }
    Ok(stream)
}

fn certified(s: &shroud_surrogate::Surrogate) -> Result<()> {
    for surface in s.surfaces() {
        anyhow::ensure!(
            surface.certificate.violations == 0,
            "uncertified surrogate in the benchmark"
        );
    }
    Ok(())
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let threads = rayon::current_num_threads();
    println!(
        "# shroud-bench surrogate (fits: {threads} rayon threads, floor: 1 thread; medians of cold fits unless noted)\n"
    );
    table1(args)?;
    table2(args)?;
    figure9(args)?;
    baseline(args)?;
    Ok(())
}

fn table1(args: &BenchArgs) -> Result<()> {
    println!("## Table 1: time vs N, 20 x 20, certification included\n");
    println!("| N | paper (ms, P4 2.4 GHz) | floor (ms) | shroud default (ms) | shroud --plain (ms) | shroud --tight (ms) | warm stream (ms) | default / floor | plain / floor | tight / floor | warm / floor | points/s (default) | speed-up vs paper |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut sides_and_streams = Vec::new();
    for (n, paper) in TABLE1 {
        if args.quick && n > 30_000 {
            continue;
        }
        let t = measure(n, 20, args, true)?;
        println!(
            "| {}K | {paper} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |{} {:.0}M | {:.0}x |",
            n / 1000,
            t.floor_ms,
            t.default_ms,
            t.plain_ms,
            t.tight_ms,
            t.warm_ms,
            t.over_floor(),
            n as f64 / t.default_ms / 1e3,
            paper / t.default_ms,
        );
        sides_and_streams.push((n, t));
    }
    println!();
    print_sides_and_streams(&sides_and_streams);
    Ok(())
}

/// Table 1's sandwiches against one side, and its warm streams against cold
/// fits of the same frames.
fn print_sides_and_streams(rows: &[(usize, Timings)]) {
    println!(
        "### Sandwiches and streams, 20 x 20
"
    );
    println!("| N | default, one side (ms) | sandwich (ms) | sandwich / one side | stream, cold fits (ms) | stream, warm fitter (ms) | warm / cold |");
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for (n, t) in rows {
        println!(
            "| {}K | {:.2} | {:.2} | {:.2}x | {:.2} | {:.2} | {:.2}x |",
            n / 1000,
            t.default_ms,
            t.sandwich_ms,
            t.sandwich_ms / t.default_ms,
            t.cold_stream_ms,
            t.warm_ms,
            t.warm_ms / t.cold_stream_ms,
        );
    }
    println!();
}

fn table2(args: &BenchArgs) -> Result<()> {
    println!("## Table 2: time vs grid n x n, N = 30K\n");
    println!("| n | paper (ms) | floor (ms) | shroud default (ms) | shroud --plain (ms) | shroud --tight (ms) | warm stream (ms) | default / floor | plain / floor | tight / floor | warm / floor |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    // (n, paper, default, tight) of the rows measured.
    let mut rows = Vec::new();
    for (n, paper) in TABLE2 {
        if args.quick && n > 20 {
            continue;
        }
        let t = measure(30_000, n, args, false)?;
        println!(
            "| {n} | {paper} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |{}",
            t.floor_ms,
            t.default_ms,
            t.plain_ms,
            t.tight_ms,
            t.warm_ms,
            t.over_floor()
        );
        rows.push((n, paper, t.default_ms, t.tight_ms));
    }
    if let (Some(&(n0, paper0, first, _)), Some(&(n1, paper1, last, _))) =
        (rows.first(), rows.last())
    {
        println!(
            "\nDefault fit, {n1} x {n1}: {:.2}x the {n0} x {n0} time (paper: {:.2}x).",
            last / first,
            paper1 / paper0
        );
    }
    if let Some(&(_, _, default, tight)) = rows.iter().find(|row| row.0 == 40) {
        println!("--tight, 40 x 40: {:.1}x the default fit.", tight / default);
    }
    println!();
    Ok(())
}

/// Figure 9: total solves of Heuristic(σ, b, λ) per line, N = 30K and 300K, 20 x 20.
fn figure9(args: &BenchArgs) -> Result<()> {
    println!("## Figure 9: solves (LDL decompositions) of Heuristic(σ, b, λ) per line, 20 x 20\n");
    println!("| N | cold: histogram (solves: lines) | cold mean | warm mean | max |");
    println!("|---:|---|---:|---:|---:|");
    let sizes: &[usize] = if args.quick {
        &[30_000]
    } else {
        &[30_000, 300_000]
    };
    for &n in sizes {
        let (mut cold, mut warm) = (Histogram::default(), Histogram::default());
        let configs = if args.quick { 2 } else { args.configs.max(1) };
        for config in 0..configs {
            let scene = MovingSpheres {
                points: n,
                seed: 1000 + config as u64,
                ..Default::default()
            };
            let mut streaming = SurrogateFitter::new(FitOptions::default())?;
            for frame in 0..10 {
                let pts = scene.generate(0.37 * config as f64 + frame as f64 / 30.0)?;
                let fresh = SurrogateFitter::new(FitOptions::default())?.fit(&pts)?;
                cold.merge(&fresh.stats.curve_solves);
                let s = streaming.fit(&pts)?;
                if frame > 0 {
                    warm.merge(&s.stats.curve_solves);
                }
            }
        }
        let bars: Vec<String> = cold
            .counts
            .iter()
            .enumerate()
            .filter(|(_, c)| **c > 0)
            .map(|(v, c)| format!("{v}: {c}"))
            .collect();
        println!(
            "| {}K | {} | {:.2} | {:.2} | {} |",
            n / 1000,
            bars.join(", "),
            cold.mean(),
            warm.mean(),
            cold.max().max(warm.max())
        );
    }
    println!();
    Ok(())
}

/// Section 3 vs Section 5 on curve data: slices of the moving spheres seen from
/// the side (x as parameter, z as value), n = 20.
fn baseline(args: &BenchArgs) -> Result<()> {
    println!("## Section 3 trial-and-error vs Section 5 Heuristic(σ, b, λ), curves, n = 20\n");
    let clouds = if args.quick { 20 } else { 200 };
    let (mut te_ms, mut h_ms, mut te_solves, mut h_solves) = (vec![], vec![], vec![], vec![]);
    let mut converged = 0;
    for config in 0..clouds {
        let pts = cloud(2_000, config)?;
        let (lo, hi) = pts.iter().fold((f64::MAX, f64::MIN), |(a, b), p| {
            (a.min(p[0] as f64), b.max(p[0] as f64))
        });
        let samples: Vec<(f64, f64)> = pts
            .iter()
            .map(|p| ((p[0] as f64 - lo) / (hi - lo) * 19.0, p[2] as f64))
            .collect();
        let (te, ms) = timed(|| fit_curve_by_trial_and_error(&samples, 20, 200));
        let te = te?;
        te_ms.push(ms);
        te_solves.push(te.solves as f64);
        converged += usize::from(te.converged);
        let (h, ms) = timed(|| fit_curve_above(&samples, 20));
        h_ms.push(ms);
        h_solves.push(h?.solves as f64);
    }
    println!("| method | converged (safe) | median solves | median time (ms) |");
    println!("|---|---:|---:|---:|");
    println!(
        "| Section 3 trial-and-error | {converged} / {clouds} | {:.0} | {:.3} |",
        median(&mut te_solves),
        median(&mut te_ms)
    );
    println!(
        "| Section 5 Heuristic(σ, b, λ) | {clouds} / {clouds} | {:.0} | {:.3} |",
        median(&mut h_solves),
        median(&mut h_ms)
    );
    println!();
    Ok(())
}
